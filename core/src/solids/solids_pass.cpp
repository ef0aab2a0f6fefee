// Beyond the paper: tracing against solids with height (occluder_map.hpp).
#include "isolux/occluder_map.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "solids/solids_pass_tree.hpp"
#include "solids/oracles.hpp"

namespace isolux {

namespace {

// A sprite pixel's own line is not tested over its last steps: its point
// stands at its own solid's surface, and the ground pixels just before it
// hold that solid's span at about its height.
constexpr int own_steps = 2;

// Walks the Bresenham ray from (cx, cy) to (tx, ty), calling
// body(i, x, y, g, v) at each step: g the step's index in `grid` (-1 off
// it), v its index in `clip` (-1 outside). A ray whose ends both lie in
// both (its box does, so every step does) steps the two indices by offsets,
// with no test per step: the common case, a light inside the map and the view.
template <class Body>
void walk_ray(std::int64_t cx, std::int64_t cy, std::int64_t tx, std::int64_t ty, Rect grid, Rect clip, Body&& body) {
    BresenhamRay r(cx, cy, tx, ty);
    auto in = [](Rect q, std::int64_t x, std::int64_t y) { return q.contains(int(x), int(y)); };
    if (!(in(grid, cx, cy) && in(grid, tx, ty) && in(clip, cx, cy) && in(clip, tx, ty))) {
        for (; !r.done(); r.step())
            body(r.i, r.x, r.y,
                 in(grid, r.x, r.y) ? std::ptrdiff_t(r.y - grid.y) * grid.w + std::ptrdiff_t(r.x - grid.x) : -1,
                 in(clip, r.x, r.y) ? std::ptrdiff_t(r.y - clip.y) * clip.w + std::ptrdiff_t(r.x - clip.x) : -1);
        return;
    }
    std::ptrdiff_t g = std::ptrdiff_t(cy - grid.y) * grid.w + std::ptrdiff_t(cx - grid.x);
    std::ptrdiff_t v = std::ptrdiff_t(cy - clip.y) * clip.w + std::ptrdiff_t(cx - clip.x);
    const std::ptrdiff_t g_diagonal = std::ptrdiff_t(r.dy1) * grid.w + r.dx1, g_straight = std::ptrdiff_t(r.dy2) * grid.w + r.dx2;
    const std::ptrdiff_t v_diagonal = std::ptrdiff_t(r.dy1) * clip.w + r.dx1, v_straight = std::ptrdiff_t(r.dy2) * clip.w + r.dx2;
    std::int64_t x = cx, y = cy, numerator = r.numerator;
    for (std::int64_t i = 0; i <= r.longest; ++i) {
        body(i, x, y, g, v);
        numerator += r.shortest;
        if (!(numerator < r.longest)) {
            numerator -= r.longest;
            g += g_diagonal, v += v_diagonal, x += r.dx1, y += r.dy1;
        } else {
            g += g_straight, v += v_straight, x += r.dx2, y += r.dy2;
        }
    }
}

// The falloff by distance max(|dx|, |dy|), the step count along a ray.
std::vector<std::uint8_t> falloff_table(int a, int b, double scale) {
    std::vector<std::uint8_t> t(std::size_t(std::max(a, b)) + 1);
    for (std::size_t d = 0; d < t.size(); ++d) t[d] = falloff(std::int64_t(d), scale);
    return t;
}

// A sprite pixel's point h high over ground point (gx, gy) that no ray walks:
// lit unless a span on its own line from the light's centre (but the last
// own_steps) holds the segment's height there. Inside the map the line steps
// by index and reads a span only where the flags say one stands.
bool own_line_lit(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, std::int64_t gx, std::int64_t gy, double h,
                  double H) {
    const std::int64_t steps = std::max(std::llabs(gx - cx), std::llabs(gy - cy));
    bool lit = true;
    walk_ray(cx, cy, gx, gy, occ.rect, occ.rect, [&](std::int64_t i, std::int64_t, std::int64_t, std::ptrdiff_t g, std::ptrdiff_t) {
        if (!lit || i > steps - own_steps || g < 0 || !(occ.flags[std::size_t(g)] & OccluderMap::has_span)) return;
        const double z = H + (h - H) * double(i) / double(steps);
        lit = !occ.spans[std::size_t(g)].holds(z);
    });
    return lit;
}

}  // namespace

namespace {

// The ground pass ray by ray: the reference the tree pass is held to, and
// what serves every light the tree does not.
void ground_by_rays(LightMask& m, const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b, double H,
                    const std::vector<std::uint8_t>& table, const Params& p) {
    // Ground pixels: one pass per ray, each span before a pixel shading a
    // stretch of the ray beyond it (its own pixel too when it stands on the
    // ground). Stretches that run to the border are one: from the nearest
    // start; one that overlaps the last kept joins it (the same union, so
    // the same pixels, from a handful of stretches a ray).
    // (shaders/trace_solids.comp is this loop on the GPU.)
    struct Shade { double from, to; };
    std::vector<Shade> shades;
    const double inf = std::numeric_limits<double>::infinity();
    const Spans* spans = occ.spans.data();
    const std::uint8_t* flags = occ.flags.data();
    for_each_ray_target(cx, cy, a, b, p, [&](std::int64_t tx, std::int64_t ty) {
        shades.clear();
        double endless_from = inf;
        walk_ray(cx, cy, tx, ty, occ.rect, m.clip, [&](std::int64_t i, std::int64_t, std::int64_t, std::ptrdiff_t g, std::ptrdiff_t v) {
            const double k = double(i);
            if (g >= 0 && (flags[g] & OccluderMap::has_span))
                for (const Span& sp : {spans[g].lower, spans[g].upper}) {  // the lower first, as the GPU
                    if (!sp.any() || sp.low >= H) continue;
                    const float lo = sp.low, hi = sp.high;
                    const double from = lo <= 0 ? k : k * H / (H - lo);
                    const double to = k * H / (H - hi);
                    if (hi >= H)
                        endless_from = std::min(endless_from, from);
                    else if (!shades.empty() && from <= shades.back().to && shades.back().from <= to)
                        shades.back() = {std::min(shades.back().from, from), std::max(shades.back().to, to)};
                    else
                        shades.push_back({from, to});
                }
            bool shaded = endless_from <= k;
            for (std::size_t s = 0; s < shades.size();) {
                if (shades[s].to <= k) {  // behind the ray's front: done with
                    shades[s] = shades.back();
                    shades.pop_back();
                    continue;
                }
                shaded = shaded || shades[s].from <= k;
                ++s;
            }
            if (!shaded && v >= 0) m.value[std::size_t(v)] = table[std::size_t(i)];
        });
    });
}

LightMask solids_mask(std::int64_t cx, std::int64_t cy, int a, int b, const Params& p, Rect clip) {
    LightMask m;
    start_mask(m, cx, cy, a, b, p, clip, p.mode == Mode::shadow);
    if (p.mode == Mode::shadow) std::fill(m.reached.begin(), m.reached.end(), std::uint8_t(1));
    return m;
}

}  // namespace

LightMask trace_light_solids(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b, double height,
                             const Params& p, Rect clip, int threads) {
    LightMask m = solids_mask(cx, cy, a, b, p, clip);
    if (m.clip.empty()) return m;
    assert(occ.flags.size() == occ.spans.size());  // index_occluders
    const double H = std::max(height, 0.0);
    const std::vector<std::uint8_t> table = falloff_table(a, b, p.falloff_scale);
    const Rect area{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
    if (!occluder_tree_serves(occ, area, p)) {
        ground_by_rays(m, occ, cx, cy, a, b, H, table, p);
        return m;
    }
    if (m.clip == area) {
        trace_ground_tree(m, occ, H, table, p, area, threads);
        return m;
    }
    // Clipped: the whole area over the tree, then the part of it the clip
    // holds copied (rays run to the border whatever the clip; past the area
    // the clip stays unlit). Leaving each ray once it moves away from the
    // clip, the tree walks fewer steps than the rays one by one would.
    const Rect inside = intersect(m.clip, area);
    thread_local LightMask whole;
    start_mask(whole, cx, cy, a, b, p, area);
    trace_ground_tree(whole, occ, H, table, p, inside, threads);
    for (int y = inside.y; y < inside.y + inside.h; ++y)
        std::memcpy(&m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(inside.x - m.clip.x)],
                    &whole.value[std::size_t(y - area.y) * area.w + std::size_t(inside.x - area.x)], std::size_t(inside.w));
    return m;
}

LightMask trace_light_solids_by_rays(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b,
                                     double height, const Params& p, Rect clip) {
    LightMask m = solids_mask(cx, cy, a, b, p, clip);
    if (m.clip.empty()) return m;
    ground_by_rays(m, occ, cx, cy, a, b, std::max(height, 0.0), falloff_table(a, b, p.falloff_scale), p);
    return m;
}

namespace {

// The sprite pass's first step: every sprite pixel of the mask's area
// unlit, but those whose ground point no ray of the pass walks (outside the
// map), each tested along its own line from the light's centre. The rays
// then light what they reach. (shaders/start_layers.comp starts each GPU
// light's layer so.)
void start_sprite_points(LightMask& m, const OccluderMap& occ, double height, const Params& p) {
    if (m.clip.empty()) return;
    const double H = std::max(height, 0.0);
    const Surface& surface = occ.surface;
    const std::int64_t cx = m.cx, cy = m.cy;
    const Rect area = intersect(Rect{int(cx) - m.a, int(cy) - m.b, 2 * m.a + 1, 2 * m.b + 1}, m.clip);
    auto at = [&](std::int64_t x, std::int64_t y) {
        return std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(x - surface.rect.x);
    };
    // The rays run to the border of the light's area grown by the tallest
    // point's rows, so a sprite standing below the area whose top shows in
    // it is reached too (the tree's rays are the same bytes). One whose
    // ground point no ray walks (off the map) is tested along its own line
    // (own_line_lit).
    const Rect ray_area{int(cx) - m.a, int(cy) - m.b - occ.tallest, 2 * m.a + 1, 2 * (m.b + occ.tallest) + 1};
    const Rect rows = intersect(area, surface.rect);  // outside the surface: no sprite
    for (int y = rows.y; y < rows.y + rows.h; ++y) {
        const std::int32_t* instance = &surface.instance[at(rows.x, y)];
        const float* heights = &surface.height[at(rows.x, y)];
        std::uint8_t* value = &m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(rows.x - m.clip.x)];
        for (int i = 0; i < rows.w; ++i) {
            if (instance[i] < 0) continue;
            value[i] = 0;
            const double h = heights[i];
            const std::int64_t gx = rows.x + i, gy = y + rows_above(h);
            if (ray_area.contains(int(gx), int(gy)) && surface.rect.contains(int(gx), int(gy))) continue;
            if (own_line_lit(occ, cx, cy, gx, gy, h, H))
                value[i] = falloff(std::max(std::llabs(gx - cx), std::llabs(std::int64_t(y) - cy)), p.falloff_scale);
        }
    }
}

// The sprite pass ray by ray: the reference the tree pass is held to, and
// what serves every light the tree does not.
void sprite_points_by_rays(LightMask& m, const OccluderMap& occ, double height, const Params& p) {
    const double H = std::max(height, 0.0);
    const std::int64_t cx = m.cx, cy = m.cy;
    const Rect area = intersect(Rect{int(cx) - m.a, int(cy) - m.b, 2 * m.a + 1, 2 * m.b + 1}, m.clip);
    auto index = [&](std::int64_t x, std::int64_t y) { return std::size_t(y - m.clip.y) * m.clip.w + std::size_t(x - m.clip.x); };
    start_sprite_points(m, occ, height, p);
    // Along each ray: the descents blocked by the spans passed at least
    // own_steps before (the last steps hold the point's own solid at about
    // its height), then the points over this step's ground pixel.
    const std::vector<std::uint8_t> table = falloff_table(m.a, m.b, p.falloff_scale);
    std::array<Spans, own_steps + 1> passed{};  // the spans of the last steps
    auto sprite_ray = [&](std::int64_t tx, std::int64_t ty) {
        RayShadow blocked;
        walk_ray(cx, cy, tx, ty, occ.rect, m.clip, [&](std::int64_t i, std::int64_t x, std::int64_t y, std::ptrdiff_t g, std::ptrdiff_t) {
            const std::int64_t s = i - own_steps;
            if (s >= 0) blocked.pass(passed[std::size_t(s) % passed.size()], int(s), H);
            const std::uint8_t f = g >= 0 ? occ.flags[std::size_t(g)] : 0;
            passed[std::size_t(i) % passed.size()] = f & OccluderMap::has_span ? occ.spans[std::size_t(g)] : Spans{};
            if (!(f & OccluderMap::has_shown)) return;
            for (std::uint32_t k = occ.shown_start[std::size_t(g)]; k < occ.shown_start[std::size_t(g) + 1]; ++k) {
                const double h = occ.shown[k].height;
                const std::int64_t rows = occ.shown[k].rows;
                if (!area.contains(int(x), int(y - rows))) continue;
                std::uint8_t& v = m.value[index(x, y - rows)];
                if (v) continue;
                const double u = i > 0 ? (H - h) / double(i) : 0;
                if (i <= own_steps || !blocked.blocks(u)) v = table[std::size_t(std::max(std::llabs(x - cx), std::llabs(y - rows - cy)))];
            }
        });
    };
    for_each_ray_target(cx, cy, m.a, m.b + occ.tallest, p, sprite_ray);
}

}  // namespace


void light_sprite_points(LightMask& m, const OccluderMap& occ, double height, const Params& p, int threads) {
    if (m.clip.empty()) return;
    assert(occ.flags.size() == occ.surface.instance.size());  // index_occluders
    const Rect whole_area{int(m.cx) - m.a, int(m.cy) - m.b, 2 * m.a + 1, 2 * m.b + 1};
    const Rect ray_area{whole_area.x, whole_area.y - occ.tallest, whole_area.w, whole_area.h + 2 * occ.tallest};
    if (!occluder_tree_serves(occ, ray_area, p)) return sprite_points_by_rays(m, occ, height, p);
    // Over the tree: every ground point lies in the rays' area, inside the
    // map. A clipped light's sprite pixels come from its whole area's (rays
    // run to the border whatever the clip, so each pixel's answer is the
    // same), the walk asked for the clip's alone.
    const Rect wanted = intersect(whole_area, m.clip);
    const Surface& surface = occ.surface;
    const bool whole = m.clip == whole_area;
    thread_local LightMask whole_mask;
    if (!whole) start_mask(whole_mask, m.cx, m.cy, m.a, m.b, p, whole_area);
    LightMask& into = whole ? m : whole_mask;
    for (int y = wanted.y; y < wanted.y + wanted.h; ++y) {  // every sprite pixel starts unlit
        const std::int32_t* instance = &surface.instance[std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(wanted.x - surface.rect.x)];
        std::uint8_t* value = &into.value[std::size_t(y - into.clip.y) * into.clip.w + std::size_t(wanted.x - into.clip.x)];
        for (int i = 0; i < wanted.w; ++i)
            if (instance[i] >= 0) value[i] = 0;
    }
    const std::vector<std::uint8_t> table = falloff_table(m.a, m.b, p.falloff_scale);
    light_sprite_points_tree(into, occ, std::max(height, 0.0), table, p, own_steps, wanted, threads);
    if (whole) return;
    for (int y = wanted.y; y < wanted.y + wanted.h; ++y)
        for (int x = wanted.x; x < wanted.x + wanted.w; ++x)
            if (surface.instance[std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(x - surface.rect.x)] >= 0)
                m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(x - m.clip.x)] =
                    whole_mask.value[std::size_t(y - whole_area.y) * whole_area.w + std::size_t(x - whole_area.x)];
}

void light_sprite_points_by_rays(LightMask& m, const OccluderMap& occ, double height, const Params& p) {
    if (m.clip.empty()) return;
    sprite_points_by_rays(m, occ, height, p);
}

}  // namespace isolux
