// The obstacle map (paper 3.1): Algorithm 1 per overlay sprite, then the n x n
// box-shaped noise reduction, over the world in pixels.
#pragma once
#include <vector>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/map.hpp"
#include "isolux/params.hpp"

namespace isolux {

// What Algorithm 1 read on one sprite, for tests and the app's Δy overlay.
struct SpriteObstacleTrace {
    int first_line = 0, last_line = -1;  // sprite rows read (the Δy lines), inclusive
    int chosen_line = -1;                // row of the run s with least deviation from the mean
    int run_start = 0, run_length = 0;   // s
};

// Algorithm 1 on one sprite's opacity map. Reads the delta_y rows that end at
// the sprite's lowest opaque row (where it stands on the ground), keeps the
// longest opaque run of each row, takes the run whose length deviates least
// from the mean run length (ties: the lower row), marks it, and marks
// run_length/4 pixels above and below its centre pixel. Rows without an opaque
// pixel take no part. Returns a mask in sprite pixels; it may reach outside the
// sprite (above or below) when the run is long. delta_y >= 1.
Mask sprite_obstacle(const Mask& opacity, int delta_y, SpriteObstacleTrace* trace = nullptr);

// The paper's box-shaped noise reduction: for every window position, in raster
// order, if the n x n window whose top-left is (x, y) holds fewer than n set
// pixels, unset (x, y). Windows are clipped at the mask's edge (outside counts
// as unset). A pixel cleared here never lies in a later window, so this
// in-place pass equals the same test against the unfiltered mask. n >= 1.
Mask noise_filter(const Mask& obstacles, int n);

// The obstacle map over `region` (world pixels): every overlay instance's
// Algorithm 1 mask stamped in, then the noise filter. Exact for any region: the
// filter reads n-1 pixels past the region's right and bottom edges.
// `footprints`, when given, holds each sprite's Algorithm 1 mask (the
// frame keeps them), so a small region does not pay for every sprite's.
Mask build_obstacle_map(const Tileset& tileset, const PlacedMap& placed, const Params& params,
                        Rect region, const std::vector<Mask>* footprints = nullptr);

}  // namespace isolux
