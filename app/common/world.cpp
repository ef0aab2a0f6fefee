#include "common/world.hpp"

#include <cstdio>
#include <iostream>

#include "common/assets.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/image_file.hpp"
#include "isolux/tiled.hpp"

namespace isolux::app {

Tileset load_scene_tileset(const Scene& scene) {
    std::filesystem::path manifest = scene.tileset;
    if (manifest.empty()) {
        manifest = default_tileset_manifest();
        if (manifest.empty())
            throw Error("default tileset not found: set ISOLUX_ASSETS to the assets/ folder or pass --tileset");
    }
    return load_tileset(manifest);
}

EndlessWindow build_endless_window(const Scene& scene, WorldRect view, std::string_view source) {
    Tileset tileset = load_scene_tileset(scene);
    const ChunkRange chunks = endless_chunks(tileset, scene.layout, view, endless_reach(scene, tileset), source);
    return make_endless_window(std::move(tileset), scene, chunks, source);
}

WorldRect parse_endless_view(const std::string& text) {
    long long x = 0, y = 0, w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%lld,%lld,%lld,%lld%c", &x, &y, &w, &h, &tail) != 4 || w < 1 || h < 1 ||
        w > max_image_side || h > max_image_side)
        throw Error("--view \"" + text + "\": expected X,Y,W,H with W and H in [1, " + std::to_string(max_image_side) + "]");
    return WorldRect{x, y, int(w), int(h)};
}

World build_world(const Scene& scene, std::string_view source, std::vector<std::string>* warnings) {
    if (!scene.map.empty()) {
        // A Tiled map: its own tileset and sprites (tiled.hpp).
        TiledMap t = load_tiled(scene.map);
        for (const std::string& line : t.warnings) {
            if (warnings) warnings->push_back(line);
            else std::cerr << "isolux: warning: " << printable(line) << "\n";
        }
        return std::move(t.world);
    }
    std::vector<std::string> own;
    World w = make_world(load_scene_tileset(scene), scene, source, warnings ? warnings : &own);
    for (const std::string& line : own) std::cerr << "isolux: warning: " << printable(line) << "\n";
    return w;
}

}  // namespace isolux::app
