#include "common/world.hpp"

#include "common/assets.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"

namespace isolux::app {

World build_world(const Scene& scene) {
    std::filesystem::path manifest = scene.tileset;
    if (manifest.empty()) {
        manifest = default_tileset_manifest();
        if (manifest.empty())
            throw Error("default tileset not found: set ISOLUX_ASSETS to the assets/ folder or pass --tileset");
    }
    return make_world(load_tileset(manifest), scene);
}

}  // namespace isolux::app
