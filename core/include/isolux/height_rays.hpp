// Beyond the paper: rays that pass over low obstacles. The paper's rays stop
// at the first obstacle pixel whatever the light's height; here each obstacle
// pixel carries the height of the sprite it belongs to (estimated from the
// sprite's alpha: its opaque rows, no hand-made geometry), and a ray from a
// light `height` pixels above the ground reaches a ground pixel unless an
// obstacle on the way stands at least as high as the ray there. Measured
// against the 3D reference in docs/accuracy.md; off by default
// (Params::rays_over_obstacles).
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/map.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

// Per pixel of the obstacle map's rectangle: the estimated height above the
// ground of the obstacle there (0 where there is none), pixels.
struct ObstacleHeights {
    Rect rect;
    std::vector<std::uint16_t> height;
    std::uint16_t at(int x, int y) const {
        return rect.contains(x, y) ? height[std::size_t(y - rect.y) * rect.w + (x - rect.x)] : 0;
    }
};

// A sprite's estimated height, pixels: its opaque rows, less the depth on
// screen of a footprint `footprint_width` wide (half the width, in 2:1
// isometric), at least 1.
int estimated_height(const Mask& opacity, int footprint_width);

// The heights of `obstacles` (built by build_obstacle_map with the same
// parameters): each obstacle pixel takes the tallest estimated height among
// the instances whose Algorithm 1 footprint covers it.
ObstacleHeights build_obstacle_heights(const Tileset& tileset, const PlacedMap& placed, const Params& p,
                                       const Mask& obstacles);

// Algorithm 2's rays with heights: along a ray, an obstacle j steps from the
// centre with height h_j < height shades the pixels from j + 1 to
// j / (1 - h_j / height) steps (where the ray to them is lower than h_j at j);
// one at least as high as the light shades everything beyond it. Obstacle
// pixels themselves stay dark, as in the paper. Same rays (border with skip,
// or every pixel), same falloff; light and flat modes.
LightMask trace_light_over(const Mask& obstacles, const ObstacleHeights& heights, std::int64_t cx, std::int64_t cy,
                           int a, int b, double height, const Params& p, Rect clip);

}  // namespace isolux
