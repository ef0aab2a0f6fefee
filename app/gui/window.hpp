// The one small wrapper over GLFW: a window with a GL 3.3 core context.
#pragma once
#include <string>

struct GLFWwindow;

namespace isolux::app {

// Creates the window and makes its context current. nullptr with `error` set
// when there is no display or no GL 3.3 (GLFW 3.3 has no headless platform).
GLFWwindow* open_window(int width, int height, bool visible, std::string& error);
void close_window(GLFWwindow* w);

}  // namespace isolux::app
