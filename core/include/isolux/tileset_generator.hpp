// The tilesets' generator: sprites drawn from simple 3D shapes (boxes,
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

// The town tileset (assets/town): what real games draw beside trees, drawn
// from the same shapes in another look (the sun from the upper right, dark
// outlines, another palette): walls, houses under stepped and conical roofs,
// a town of several buildings in one tile, low rocks, a boulder pile, a
// mountain wider than a tile, a tower, a fence, a hedge, a grove of six
// trees whose crowns merge and a tall thin tree. Its manifest carries the
// shapes and height maps, so the 3D reference judges the estimate on it.
GeneratedTileset generate_town_tileset(double scale = 1.0);

// The editor's walking character, drawn by the same generator (a figure of
// cylinders and ellipsoids with a lantern): about 48 x 80 pixels at scale 1,
// anchored at its feet.
Sprite generate_character_sprite(double scale = 1.0);

}  // namespace isolux
