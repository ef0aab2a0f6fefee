#include "scenes.hpp"

#include <map>

#include "isolux/isolux.hpp"
#include "isolux/obstacle_map.hpp"

namespace isolux::bench {

namespace {
const Tileset& tileset() {
    static Tileset t = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json");
    return t;
}
}  // namespace

const World& world(const std::string& name, int side) {
    static std::map<std::pair<std::string, int>, World> cache;
    auto key = std::make_pair(name, side);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    Scene s;
    s.width = s.height = side;
    World w = make_world(tileset(), s);
    if (name == "forest") {
        const std::vector<int> trees = w.tileset.find(SpriteKind::overlay, "tree");
        const std::vector<int> grass = w.tileset.find(SpriteKind::floor, "grass");
        for (std::size_t i = 0; i < w.map.tiles.size(); ++i) {
            Tile& t = w.map.tiles[i];
            t.floor = grass[0];
            t.overlay_count = 3;
            const int slots[3][2] = {{0, 0}, {-25, 0}, {25, 0}};
            for (int k = 0; k < 3; ++k) t.overlays[k] = {trees[(i + k) % trees.size()], slots[k][0], slots[k][1]};
        }
        w.placed = place_sprites(w.map, w.tileset);
    }
    return cache.emplace(key, std::move(w)).first->second;
}

const TraceScene& trace_scene(const std::string& name) {
    static std::map<std::string, TraceScene> cache;
    auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    TraceScene t;
    t.name = name;
    if (name == "empty" || name == "corridors") {
        t.obstacles = Mask(Rect{0, 0, 1600, 1200});
        t.cx = 800, t.cy = 600;
        if (name == "corridors") {
            // Walls every 40 rows with a doorway every 120 px; pillars between.
            for (int y = 20; y < 1200; y += 40)
                for (int x = 0; x < 1600; ++x)
                    if ((x % 120) > 24) t.obstacles.set(x, y), t.obstacles.set(x, y + 1);
            for (int y = 0; y < 1200; y += 40)
                for (int x = 60; x < 1600; x += 120) t.obstacles.set(x, y + 5), t.obstacles.set(x + 1, y + 5);
            t.cy = 600 + 0;  // between two walls
        }
    } else {
        const World& w = world(name == "default" ? "default" : "forest", 24);
        Params p;
        t.obstacles = build_obstacle_map(w.tileset, w.placed, p, w.placed.bounds);
        t.cx = w.placed.bounds.w / 2;
        t.cy = w.placed.bounds.h / 2;
        // Stand the light on a clear pixel near the middle.
        for (int r = 0; r < 200 && t.obstacles.get(t.cx, t.cy); ++r) ++t.cx;
    }
    return cache.emplace(name, std::move(t)).first->second;
}

}  // namespace isolux::bench
