// The GLSL sources: read from shaders/ (hot-reloaded when a file changes),
// with a copy embedded at build time for an installed app.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

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

}  // namespace isolux::app
