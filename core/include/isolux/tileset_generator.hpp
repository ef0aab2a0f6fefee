// The default tileset's generator: sprites drawn from simple 3D shapes (boxes,
// cylinders, cones, ellipsoids) ray-cast in 2:1 isometric projection with baked
// shading. Deterministic: the committed assets/ are its output, byte for byte.
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/tileset.hpp"

namespace isolux {

struct GeneratedTileset {
    Tileset tileset;
    // Per sprite, per pixel: the true height above the ground plane, in pixels
    // (0 where transparent or on the ground). The geometry Algorithm 1 estimates.
    std::vector<std::vector<std::uint16_t>> heights;
    std::vector<std::string> image_files;  // file name per sprite
};

// scale 1: the paper's 128x64 floor diamonds and 128x128 sprites; other
// scales resize everything (0.5: 64x32 diamonds, 64x64 sprites).
GeneratedTileset generate_default_tileset(double scale = 1.0);

// The editor's walking character, drawn by the same generator (a figure of
// cylinders and ellipsoids with a lantern): about 48 x 80 pixels at scale 1,
// anchored at its feet.
Sprite generate_character_sprite(double scale = 1.0);

}  // namespace isolux
