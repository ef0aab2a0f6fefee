// Paper 3.2: "a simple box-blur algorithm is applied" to the light texture,
// hiding the gaps skipped rays leave. The CPU reference of shaders/blur.frag.
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/light_texture.hpp"

namespace isolux {

// Each texel becomes the mean of the (2r+1) x (2r+1) texels around it,
// rounded to nearest, with coordinates clamped to the texture's edge (the
// shader's GL_CLAMP_TO_EDGE). radius 0 returns the input; any radius works,
// larger than the texture included. O(1) per texel.
LightTexture box_blur(const LightTexture& tex, int radius);

// The same values written into `out` (resized to `tex`'s rectangle when it
// differs; kept otherwise, so a frame reuses its buffer) for the texels of
// `region` (world pixels) only: a band of rows for one thread, or where the
// light changed. Row-major exact integer running sums, a few rows of scratch.
void box_blur_into(const LightTexture& tex, int radius, Rect region, LightTexture& out);

// Beyond the paper: the blur within surfaces (with occluders solids or
// shapes, docs/beyond.md). Which surface each pixel shows, over `rect`
// (world pixels): the overlay instance (PlacedMap::instances' index), -1 the
// ground; -1 outside `rect`.
struct SurfaceIds {
    Rect rect;
    std::vector<std::int32_t> id;  // rect.w * rect.h, row by row
    // Per pixel, how far its surface reaches around it: the Chebyshev
    // distance to the nearest pixel of another surface (outside `rect`
    // counting as the ground), capped at surface_reach_cap; index_surfaces
    // fills it. A texel whose distance exceeds the blur's radius blurs as
    // box_blur does.
    std::vector<std::uint8_t> reach;
    // Per pixel, whether its right neighbour (join_right) and the one below
    // it (join_down) show the same surface; index_surfaces fills it. The
    // blur near outlines reads these bytes, sixteen pixels at a time, where
    // it would otherwise compare ids one by one.
    static constexpr std::uint8_t join_right = 1, join_down = 2;
    std::vector<std::uint8_t> joins;
    std::int32_t at(int wx, int wy) const {
        return rect.contains(wx, wy) ? id[std::size_t(wy - rect.y) * rect.w + std::size_t(wx - rect.x)] : -1;
    }
};

// The largest reach index_surfaces stores: one past the largest radius the
// blur compares a reach with (past it the blur never reads the reach).
constexpr int surface_reach_cap = 8;

// Fills `ids.reach` and `ids.joins` from `ids.id` (a pass along the rows,
// then one reading the surface_reach_cap - 1 rows each side: O(1) per pixel).
void index_surfaces(SurfaceIds& ids);

// Each texel becomes the mean, rounded to nearest, of the texels reached from
// it by up to `radius` steps along its column and then up to `radius` along
// their rows, never crossing into another surface (`ids`) nor past the
// texture's edge (no clamping: a texel outside counts for nothing). So light
// on the ground never bleeds onto a sprite in front of it, nor one sprite's
// onto another's. Written into `out` for the texels of `region` only, as
// box_blur_into. `ids` may cover any rectangle; with `reach` filled
// (index_surfaces) a texel far from other surfaces costs what box_blur's do,
// one near them O(radius^2) up to radius 7, O(radius) past it.
// shaders/blur.frag mirrors it (u_within_surfaces).
void box_blur_within_into(const LightTexture& tex, int radius, const SurfaceIds& ids, Rect region, LightTexture& out);
LightTexture box_blur_within(const LightTexture& tex, int radius, const SurfaceIds& ids);

}  // namespace isolux
