// Where a sprite meets the ground, on real art: Algorithm 1 (paper 3.1) run on
// what is left of the sprite once a baked ground diamond and baked shadows are
// taken out, or a footprint the manifest gives. Not in the paper, which draws
// its own sprites with neither (docs/beyond.md has the evidence for the
// default).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

// A tree's foot: the bottom row of its trunk and the mean column of the
// trunk's lowest three rows.
struct TrunkFoot {
    double x = 0;  // pixel column (its centre is x + 0.5)
    int y = 0;     // pixel row
};
// The trunks a sprite's colours show (bark-coloured, taller than wide),
// in row-major order of their first pixel (footprint.cpp says how).
std::vector<TrunkFoot> find_trunks(const Image& image);
// Of those, the trees' feet on the floor diamond of a tw x th tile anchored
// at (ax, ay), pieces of one trunk merged (footprint.cpp says how), by column.
std::vector<TrunkFoot> trunks_on_tile(const std::vector<TrunkFoot>& found, int ax, int ay, int tw, int th);

// The crowns of a grove painted as one sprite: the regions of `object`'s
// pixels (no bark, no dark outline) that each hold one smoothly shaded
// colour, of 5 % of its pixels or more, in row-major order of their first
// pixel (footprint.cpp says how). A crown partly hidden behind another
// keeps its visible part.
std::vector<Mask> crown_regions(const Image& sprite, const Mask& object);

// A part of an object that stands apart on its tile (a rock of a scatter,
// a hut of a hamlet): its pixels, and Algorithm 1's footprint of them.
struct ObjectPart {
    Mask object, footprint;
};

// What the estimate saw, for check-tileset and the inspector.
struct FootprintReport {
    bool baked_ground = false;  // the tile's floor diamond around the anchor was mostly opaque ground
    bool baked_shadow = false;  // translucent dark pixels were left out
    // The object fills its tile or spans several: its footprint is its whole
    // base, the parallelogram (left, front, right and back corners, sprite
    // pixels) closed by its outline's two lower edges.
    bool whole_base = false;
    std::vector<std::pair<int, int>> base;

    Mask estimate;              // the object's pixels: what Algorithm 1 read, and the opacity map the correction uses
    SpriteObstacleTrace trace;  // Algorithm 1's lines and run
    // The trunks (find_trunks) whose feet stand on the tile's floor diamond:
    // a tree grows from its tile's ground; bark higher up is a branch
    // (FreedroidRPG's trees show a dozen).
    std::vector<TrunkFoot> trunks;
    // With two trunks or more (a grove), its crowns (crown_regions).
    std::vector<Mask> crowns;
    // The object's parts standing apart on the tile: its 8-connected
    // components of 2 % of its pixels or more whose lowest pixel lies on the
    // floor diamond, when there are two or more (else none). Not for a
    // whole base, nor where the manifest draws the footprint.
    std::vector<ObjectPart> parts;
};


// The footprint of a sprite whose opacity map is `opacity`, anchored at
// (anchor_x, anchor_y) on a tile_w x tile_h floor diamond, by `mode`, as an
// obstacle mask in sprite pixels (it may reach outside the sprite, as
// Algorithm 1's does).
Mask sprite_footprint(const Image& sprite, const Mask& opacity, int anchor_x, int anchor_y, int tile_w, int tile_h,
                      int delta_y, FootprintMode mode, const FootprintSpec& spec, FootprintReport* report = nullptr);

// The footprint of tileset sprite `s` under the preset `p` (its own mode, else
// the preset's footprint), as build_obstacle_map stamps it.
Mask tileset_footprint(const Tileset& tileset, const Sprite& s, const Params& p, FootprintReport* report = nullptr);

// The most pixels the footprint mask of a w x h sprite may hold, whatever
// the preset's footprint: Algorithm 1 marks run/4 pixels above and below a
// run as wide as the sprite (w x (w/2 + 1)), a run footprint as much about
// its own length. Readers count it against max_input_sprite_pixels, so a
// small file cannot ask for gigabytes of mask (one 65536 x 1 sprite would).
std::int64_t footprint_pixels(int w, int h, const FootprintSpec& spec);

// The centre (mean of its pixels) and bounding box of a mask; false when empty.
bool mask_centre(const Mask& m, double& x, double& y, Rect& box);

}  // namespace isolux
