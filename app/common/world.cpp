#include "common/world.hpp"

#include "common/assets.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"

namespace isolux {

World build_world(const Scene& scene) {
    World w;
    std::filesystem::path manifest = scene.tileset;
    if (manifest.empty()) {
        manifest = default_tileset_manifest();
        if (manifest.empty())
            throw Error("default tileset not found: set ISOLUX_ASSETS to the assets/ folder or pass --tileset");
    }
    w.tileset = load_tileset(manifest);
    w.map = generate_map(scene.seed, scene.width, scene.height, scene.layout, w.tileset);
    w.placed = place_sprites(w.map, w.tileset);
    return w;
}

}  // namespace isolux
