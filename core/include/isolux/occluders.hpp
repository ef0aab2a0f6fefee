// Beyond the paper: rays stopped by solids with height, not by footprints
// (Params::occluders). Each ground pixel holds the span of heights
// [z_low, z_high) the solids standing over it fill; each sprite pixel, the
// height of the 3D point it shows. A light stands at its height H.
//
// Ground pixels keep the paper's border rays: along one ray every ground
// pixel shares the occluders before it, and a span [z_low, z_high) s steps
// out shades the steps from s H / (H - z_low) to s H / (H - z_high) (to the
// area's border where z_high >= H; nothing where z_low >= H), so one pass per
// ray suffices. A sprite pixel showing a point at height h over ground pixel g
// (h pixels below it on screen) is lit when the segment from the light to
// that point clears the spans along g's own line from the light's centre.
// That replaces the opacity correction (light_sprite_points, timed as that
// stage), which only guesses which sprite pixels stand above a light.
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/params.hpp"
#include "isolux/truth.hpp"
#include "isolux/world.hpp"

namespace isolux {

struct OccluderMap {
    Rect rect;                       // world pixels, as the obstacle map's
    std::vector<float> low, high;    // per ground pixel: the span filled; high <= low: none
    Surface surface;                 // per pixel: what it shows (ground or an overlay) and its height

    bool span(std::int64_t x, std::int64_t y, float& z_low, float& z_high) const {
        if (!rect.contains(int(x), int(y))) return false;
        const std::size_t i = std::size_t(y - rect.y) * rect.w + std::size_t(x - rect.x);
        z_low = low[i];
        z_high = high[i];
        return z_high > z_low;
    }
};

// The occluders of every overlay meeting `region` (and those standing near
// it), by `p.occluders`: solids estimated from the sprites, or the manifest's
// shapes (Error naming the tileset and the sprite when an overlay has none).
OccluderMap build_occluders(const World& world, const Params& p, Rect region);

// One light at (cx, cy), half-extents a, b, at `height` above the ground,
// traced against `occ` as ground everywhere: value = falloff(max(|dx|, |dy|))
// where lit, as trace_light's (shape_light applies the falloff's shape
// after). Border rays with ray skip, or every pixel; light and shadow modes
// (`reached` filled in shadow mode: every pixel of the area).
LightMask trace_light_solids(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b, double height,
                             const Params& p, Rect clip);

// Then every pixel of the mask that shows a sprite, lit (or not) by the 3D
// point it shows: in place of the opacity correction, and timed as it.
void light_sprite_points(LightMask& mask, const OccluderMap& occ, double height, const Params& p);

}  // namespace isolux
