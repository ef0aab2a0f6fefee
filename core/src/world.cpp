#include "isolux/world.hpp"

#include <atomic>

namespace isolux {

namespace {
std::atomic<std::uint64_t> next_revision{1};
}  // namespace

void touch(World& w) { w.revision = next_revision++; }

World make_world(Tileset tileset, const Scene& scene) {
    World w;
    w.tileset = std::move(tileset);
    w.map = generate_map(scene.seed, scene.width, scene.height, scene.layout, w.tileset);
    w.placed = place_sprites(w.map, w.tileset);
    w.revision = next_revision++;
    return w;
}

}  // namespace isolux
