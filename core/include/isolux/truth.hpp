// References the paper's 2.5D estimate is measured against (docs/accuracy.md).
// Not in the paper: the paper compares with nothing.
//   every_pixel: the 2.5D model itself with a ray to every pixel (the paper's 4ab rays);
//   exact_line:  a pixel is lit exactly when its own Bresenham line from the
//                light's centre is clear of obstacles (2D, exact);
//   3d:          the true shapes: a pixel's 3D surface point is lit when the
//                segment to the light (at its height) clears every solid;
//   3d_facing:   3d, and the surface faces the light;
//   3d_shaded:   3d, each sprite pixel's light times Lambert's cosine between
//                its true surface's normal and the direction to the light
//                (what sprite_shading models; the ground as in 3d).
// Every reference uses the model's intensity (shaped_falloff: its falloff,
// shape and edge fade), so only visibility differs.
#pragma once
#include <cstdint>
#include <string_view>
#include <vector>

#include "isolux/light_texture.hpp"
#include "isolux/solid.hpp"
#include "isolux/world.hpp"

namespace isolux {

enum class Reference { every_pixel, exact_line, three_d, three_d_facing, three_d_shaded };
std::string_view to_string(Reference r);  // "every_pixel", "exact_line", "3d", "3d_facing", "3d_shaded"
Reference parse_reference(std::string_view s, std::string_view source);  // throws Error naming source

// What each pixel of `rect` shows: the ground (height 0) or the topmost
// overlay sprite whose alpha is above its opacity threshold, and the height of
// its visible surface (the sprite's height map, else its shape cast along the
// view line).
struct Surface {
    Rect rect;
    std::vector<std::int32_t> instance;  // the overlay's index in PlacedMap::instances; -1: ground
    std::vector<float> height;           // pixels above the ground
};
// `heights`, when given, holds per sprite (by index) the height of each of its
// pixels, in place of its height map or shape (an estimate's).
Surface build_surface(const World& world, Rect rect, double opacity_threshold,
                      const std::vector<std::vector<float>>* heights = nullptr);
// The same into `s`, reusing its storage (a map rebuilt over the same
// region touches no new memory).
void build_surface_into(Surface& s, const World& world, Rect rect, double opacity_threshold,
                        const std::vector<std::vector<float>>* heights = nullptr);

// The overlay solids whose sprites meet `region`, in the world's ground frame
// (each sprite's shape moved to its anchor). Throws Error naming the tileset
// and sprite when an overlay there has no shape.
struct WorldSolids {
    std::vector<Solid> solids;
    std::vector<std::array<Vec3, 2>> bounds;
    std::vector<std::int32_t> instance;  // the placed instance each solid belongs to
};
WorldSolids world_solids(const World& world, Rect region);

// The same check alone, with no solids built: throws world_solids' Error
// when an overlay meeting `region` has no shape.
void require_shapes(const World& world, Rect region);

// A light's height above the ground, pixels: its own, else the preset's.
double light_height(const Light& light, const Params& p);

// One light (centre pixel cx, cy; half-extents a, b; `height` above the
// ground) against the true shapes: value = shaped_falloff(dx, dy, dy_scale) where the
// pixel's surface point sees the light, 0 elsewhere. `surface` must cover
// `clip`. With `facing`, a surface turned away from the light is dark too.
// With `shaded`, a lit sprite pixel's value is multiplied by Lambert's
// cosine between its solid's normal and the direction to the light, rounded.
LightMask truth_light(const Surface& surface, const WorldSolids& solids, std::int64_t cx, std::int64_t cy,
                      double height, int a, int b, const Params& p, Rect clip, bool facing, double dy_scale,
                      bool shaded = false);

// One light, exact in 2D: a pixel is lit when no pixel of its own Bresenham
// line from the centre (both ends included) is an obstacle.
LightMask exact_line_light(const Mask& obstacles, std::int64_t cx, std::int64_t cy, int a, int b, const Params& p,
                           Rect clip, double dy_scale);

// The work of reference_texture over `rect`, in trace_work's steps, known
// before it starts: every_pixel's own trace; for exact_line a Bresenham line
// per lit pixel (half the area's width long on average); for the 3D
// references a segment per lit pixel tested against every overlay that
// meets the lights' areas.
double reference_work(const World& world, const Scene& scene, Rect rect, Reference ref);

// The scene's light texture over `rect` by the reference: every light that
// meets `rect`, accumulated as the model does (colour, intensity), light mode,
// no blur. Only every_pixel (the model's own rays) has an opacity correction,
// and only when `opacity_correction` (so that it matches the model measured).
LightTexture reference_texture(const World& world, const Scene& scene, Rect rect, Reference ref,
                               bool opacity_correction = true);

// Where the model and a reference disagree about lit (> 0 in any channel),
// over the model's rectangle: magenta where the model lights what the
// reference leaves dark, cyan for the reverse, transparent where they agree.
inline constexpr std::uint8_t lit_only_in_model[4] = {255, 0, 255, 255};
inline constexpr std::uint8_t lit_only_in_reference[4] = {0, 255, 255, 255};
Image lit_difference(const LightTexture& model, const LightTexture& reference);

}  // namespace isolux
