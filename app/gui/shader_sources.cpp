#include "gui/shader_sources.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace isolux::app {

fs::path shader_folder() {
    if (const char* env = std::getenv("ISOLUX_SHADERS"); env && *env && fs::exists(fs::path(env) / "composite.frag"))
        return env;
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        fs::path installed = exe.parent_path().parent_path() / "share" / "isolux" / "shaders";
        if (fs::exists(installed / "composite.frag")) return installed;
    }
    fs::path source = ISOLUX_SOURCE_SHADERS;
    if (fs::exists(source / "composite.frag")) return source;
    return {};
}

std::string shader_source(const fs::path& folder, const std::string& name) {
    if (!folder.empty()) {
        std::ifstream f(folder / name, std::ios::binary);
        if (f) {
            std::ostringstream ss;
            ss << f.rdbuf();
            return ss.str();
        }
    }
    for (const EmbeddedShader& s : embedded_shaders())
        if (name == s.name) return s.source;
    return {};
}

}  // namespace isolux::app
