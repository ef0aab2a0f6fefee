// The GLSL sources: read from shaders/ (hot-reloaded when a file changes),
// with a copy embedded at build time for an installed app.
#pragma once
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

#include "gpu/gl.hpp"

namespace isolux::app {

struct EmbeddedShader {
    const char* name;
    const char* source;
};
const std::vector<EmbeddedShader>& embedded_shaders();

// The shaders/ folder to read: $ISOLUX_SHADERS, <exe>/../share/isolux/shaders,
// or the source tree's; empty when none exists (the embedded copy is used).
std::filesystem::path shader_folder();

// The source of `name` from `folder` when it is readable there, else the
// embedded copy; empty when neither has it.
std::string shader_source(const std::filesystem::path& folder, const std::string& name);

// One stage of a program: its type (GL_VERTEX_SHADER, ...) and file name.
struct ShaderStage {
    GLenum type;
    std::string name;
};

// The stages (read by shader_source) compiled and linked into one program;
// 0 when a source is missing or the driver refuses it, with `error` naming
// the files and the driver's log.
GLuint build_program(const std::filesystem::path& folder, std::initializer_list<ShaderStage> stages, std::string& error);

}  // namespace isolux::app
