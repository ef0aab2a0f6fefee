// A scene's world: its tileset, generated map and placed sprites, built once
// and shared by the front ends.
#pragma once
#include <string>

#include "isolux/map.hpp"
#include "isolux/scene.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

struct World {
    Tileset tileset;
    Map map;
    PlacedMap placed;
};

// Loads the scene's tileset (the default one when empty), generates the map
// from its seed and places the sprites. Throws Error.
World build_world(const Scene& scene);

}  // namespace isolux
