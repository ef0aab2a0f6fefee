// Paper 3.2, Algorithm 2: rays from a light's centre, traced with the adapted
// Bresenham, stopping at the obstacle map.
#pragma once
#include <atomic>
#include <cstdint>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/params.hpp"

namespace isolux {

// The paper's Bresenham stepping (Algorithm 2), one pixel per step from the
// origin to the destination inclusive. 64-bit coordinates: no overflow near
// 2^31. Usage: for (BresenhamRay r(x0, y0, x1, y1); !r.done(); r.step()) use(r.x, r.y);
struct BresenhamRay {
    std::int64_t x, y;
    std::int64_t longest, shortest, numerator, i = 0;
    int dx1 = 0, dy1 = 0, dx2 = 0, dy2 = 0;

    BresenhamRay(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1);
    bool done() const { return i > longest; }
    void step() {
        numerator += shortest;
        if (!(numerator < longest)) {
            numerator -= longest;
            x += dx1;
            y += dy1;
        } else {
            x += dx2;
            y += dy2;
        }
        ++i;
    }
};

// The paper's intensity, i = 255 / (1 + d / falloff_scale) with d = max(|Δx|, |Δy|),
// truncated to 8 bits; falloff_scale 1 gives exactly 255 / (1 + d) in integers.
std::uint8_t falloff(std::int64_t d, double falloff_scale);

// The intensity at offset (dx, dy) from a light with half-extents a, b under
// the falloff shape and edge fade of `p` (not in the paper): falloff() of the
// Chebyshev or Euclidean distance, times the fade curve of t (its distance to
// the border as a share) when edge_fade. With the paper's settings it is
// falloff(max(|dx|,|dy|)).
// dy_scale multiplies |dy| in the distance d (falloff_dy_scale: 1 on the
// screen, the tile ratio on the ground); the fade's t keeps the a x b area.
std::uint8_t shaped_falloff(std::int64_t dx, std::int64_t dy, int a, int b, const Params& p, double dy_scale);
// shaped_falloff before it is truncated to 8 bits (edge_fade on; real dx, dy).
double faded_intensity(double dx, double dy, int a, int b, const Params& p, double dy_scale);
// The factor on |dy| in a light's distance: 1 with falloff_space screen (the
// paper), tile_width / tile_height with ground.
double falloff_dy_scale(const Params& p, int tile_width, int tile_height);
// Whether `p` asks for anything but the paper's falloff.
inline bool shaped(const Params& p) {
    return p.falloff_shape != FalloffShape::chebyshev || p.edge_fade || p.falloff_space != FalloffSpace::screen;
}

// One light's traced pixels, over the part of its area that matters (`clip`,
// world pixels). value[i] is what Algorithm 2 draws there: the paper's
// intensity falloff(d) where a ray reached the pixel before any obstacle (the
// light texture of one white light), 0 where none did. (A lit pixel so far out
// that the falloff is 0 reads as unlit; it adds nothing either way.)
// reached[i] (shadow mode only) is 1 where any ray passed: shadow mode's
// "beyond the obstacle" is reached and not lit.
struct LightMask {
    Rect clip;
    std::int64_t cx = 0, cy = 0;  // the light's centre pixel
    int a = 0, b = 0;             // the area's half-extents (for shaped falloffs)
    double falloff_scale = 1.0;
    double dy_scale = 1.0;        // falloff_dy_scale: what shape_light and the shadow mode's sum measure with
    std::vector<std::uint8_t> value, reached;

    bool lit(std::size_t i) const { return value[i] != 0; }
};

// Readies `mask` for a light at (cx, cy) with half-extents a, b over `clip`:
// its fields set, `value` all unlit (its capacity kept), `reached` emptied
// unless `with_reached` (the shadow mode's tracers fill it). Its dy_scale is
// left as it was: the caller, which knows the tileset, sets it.
void start_mask(LightMask& mask, std::int64_t cx, std::int64_t cy, int a, int b, const Params& p, Rect clip,
                bool with_reached = false);

// Rewrites every lit pixel of a traced (and corrected) mask with shaped_falloff.
void shape_light(LightMask& mask, const Params& p);

// The border pixels of the (2a+1) x (2b+1) area around the origin, each once,
// clockwise from the top-left corner. a = b = 0 gives the single centre pixel.
std::vector<std::pair<int, int>> border_offsets(int a, int b);

// Progress and cancel for a long trace, shared with another thread (the
// app's approved long work). As rays are traced, `done` grows by each ray's
// estimated steps, max(a, b) + 1 (trace_work's unit), checked every 64 rays
// or so; once `cancel` is set the trace stops at its next check and leaves an
// incomplete mask (the caller throws it away).
struct TraceControl {
    const std::atomic<bool>* cancel = nullptr;
    std::atomic<std::int64_t>* done = nullptr;
    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
    void add(std::int64_t steps) const {
        if (done) done->fetch_add(steps, std::memory_order_relaxed);
    }
};

// The steps trace_work counts for one light of half-extents a, b: its rays
// times max(a, b) + 1, an upper bound of what Algorithm 2 walks.
double light_trace_work(int a, int b, const Params& p);

// Calls target(x, y) for every pixel a ray is traced to: each pixel of the
// area (Rays::every_pixel), else every ray_skip-th border pixel.
template <class Target>
void for_each_ray_target(std::int64_t cx, std::int64_t cy, int a, int b, const Params& p, Target&& target) {
    if (p.rays == Rays::every_pixel) {
        for (int y = -b; y <= b; ++y)
            for (int x = -a; x <= a; ++x) target(cx + x, cy + y);
        return;
    }
    const auto border = border_offsets(a, b);
    for (std::size_t i = 0; i < border.size(); i += std::size_t(p.ray_skip))
        target(cx + border[i].first, cy + border[i].second);
}

// Traces one light centred at pixel (cx, cy) with half-extents a, b:
// Rays::border traces to every ray_skip-th border pixel, Rays::every_pixel to
// every pixel of the area (the paper's 4ab rays). Mode::light stops each ray at
// its first obstacle pixel (left dark); Mode::shadow continues and records the
// rest as reached; Mode::flat ignores obstacles. Only pixels inside `clip` are
// recorded; obstacles are read along the whole ray (outside `obstacles` there
// are none).
//
// Fast path (the common case: the clip is the whole area and the obstacle map
// covers it): rays step through the obstacle map and the mask by pointer,
// branch-free, with no bounds tests. `area_is_clear` (the caller knows no
// obstacle lies in the area) lets k = 1 and every-pixel tracing fill the area
// from its closed form: every pixel is lit (see docs/beyond.md). The result is
// the same bytes as the general path's.
// `control` (optional) reports progress and may cancel (TraceControl).
LightMask trace_light(const Mask& obstacles, std::int64_t cx, std::int64_t cy, int a, int b, const Params& p,
                      Rect clip, bool area_is_clear = false, const TraceControl* control = nullptr);
// The same into `m`, reusing its vectors' capacity (a frame retracing its
// lights allocates nothing).
void trace_light_into(LightMask& m, const Mask& obstacles, std::int64_t cx, std::int64_t cy, int a, int b,
                      const Params& p, Rect clip, bool area_is_clear = false, const TraceControl* control = nullptr);

// Whether `area` holds no obstacle pixel (outside `obstacles` there are none):
// the condition for trace_light's closed form.
bool area_is_clear(const Mask& obstacles, Rect area);

}  // namespace isolux
