#include "common/assets.hpp"

#include <cstdlib>
#include <system_error>

namespace fs = std::filesystem;

namespace isolux::app {

fs::path default_tileset_manifest() {
    const fs::path rel = fs::path("default") / "tileset.json";
    if (const char* env = std::getenv("ISOLUX_ASSETS"); env && *env) {
        if (fs::exists(fs::path(env) / rel)) return fs::path(env) / rel;
    }
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        fs::path installed = exe.parent_path().parent_path() / "share" / "isolux" / "assets" / rel;
        if (fs::exists(installed)) return installed;
    }
    fs::path source = fs::path(ISOLUX_SOURCE_ASSETS) / rel;
    if (fs::exists(source)) return source;
    return {};
}

}  // namespace isolux::app
