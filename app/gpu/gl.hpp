// All OpenGL of the app, in one place: GL 3.3 core entry points from glvnd's
// libOpenGL (every GL 4.x function is exported there).
#pragma once
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
