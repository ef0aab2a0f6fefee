// A scene's world: its tileset, the map generated from its seed and the placed
// sprites. Built once per seed, size, layout or tileset change.
#pragma once
#include <cstdint>

#include "isolux/map.hpp"
#include "isolux/scene.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

struct World {
    Tileset tileset;
    Map map;
    PlacedMap placed;
    std::uint64_t revision = 0;  // changes whenever the world is rebuilt, so caches know
};

// Generates the map for the scene's seed, size and layout on `tileset` and
// places its sprites. Throws Error on a bad size or tileset.
World make_world(Tileset tileset, const Scene& scene);

// Marks the world changed in place (a sprite's footprint edited, say), so
// every cache built from it is rebuilt.
void touch(World& w);

}  // namespace isolux
