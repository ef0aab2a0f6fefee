// Beyond the paper: tracing against solids with height (occluders.hpp).
#include "isolux/occluders.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "isolux/footprint.hpp"
#include "isolux/solid_estimate.hpp"

namespace isolux {

namespace {

constexpr double sqrt2 = 1.4142135623730951;
// A sprite pixel's own line is not tested over its last steps: its point
// stands at its own solid's surface, and the ground pixels just before it
// hold that solid's span at about its height.
constexpr int own_steps = 3;

// Widens the span at ground pixel i to hold [lo, hi).
void fill(OccluderMap& m, std::size_t i, double lo, double hi) {
    lo = std::max(0.0, lo);
    if (hi <= lo) return;
    if (m.high[i] <= m.low[i]) {
        m.low[i] = float(lo);
        m.high[i] = float(hi);
    } else {
        m.low[i] = std::min(m.low[i], float(lo));
        m.high[i] = std::max(m.high[i], float(hi));
    }
}

// The heights the solid fills on the vertical line through ground point (X, Y).
bool vertical_span(const Solid& s, double X, double Y, double& lo, double& hi) {
    switch (s.kind) {
        case SolidKind::box:
            if (X < s.a.x || X > s.b.x || Y < s.a.y || Y > s.b.y) return false;
            lo = s.a.z, hi = s.b.z;
            return true;
        case SolidKind::cylinder:
        case SolidKind::cone: {
            const double d = std::hypot(X - s.a.x, Y - s.a.y), r = s.b.x;
            if (r <= 0 || d > r) return false;
            lo = s.a.z;
            hi = s.a.z + s.b.z * (s.kind == SolidKind::cone ? 1 - d / r : 1);
            return true;
        }
        case SolidKind::ellipsoid: {
            if (s.b.x <= 0 || s.b.y <= 0) return false;
            const double u = (X - s.a.x) / s.b.x, v = (Y - s.a.y) / s.b.y, q = u * u + v * v;
            if (q > 1) return false;
            const double half = s.b.z * std::sqrt(1 - q);
            lo = s.a.z - half, hi = s.a.z + half;
            return true;
        }
    }
    return false;
}

// Each overlay's estimated objects, their spans by ground distance (a
// quarter-pixel table, rounded outwards so a span is never wider than the
// solid's), and the height of each sprite pixel's point.
struct SpriteSolids {
    std::vector<EstimatedObject> objects;
    std::vector<std::vector<std::pair<float, float>>> spans;  // per object, per quarter pixel of distance
    std::vector<float> heights;                               // per sprite pixel
};

SpriteSolids sprite_solids(const Tileset& ts, const Sprite& s, const Params& p) {
    SpriteSolids out;
    out.objects = sprite_objects(ts, s, p);
    for (const EstimatedObject& o : out.objects) {
        double widest = 0;
        for (double r : o.radius) widest = std::max(widest, r);
        std::vector<std::pair<float, float>> table(std::size_t(std::ceil(widest * 4)) + 2, {0.f, 0.f});
        for (std::size_t k = 0; k < table.size(); ++k) {
            double lo = 0, hi = 0;
            if (o.span_at(double(k) / 4, lo, hi)) table[k] = {float(lo), float(hi)};
        }
        out.spans.push_back(std::move(table));
    }
    // The point a pixel shows: the topmost point of a solid on its view line
    // (the first the viewer meets), else its row's height above the footprint.
    out.heights.assign(std::size_t(s.image.width) * s.image.height, 0.f);
    for (int y = 0; y < s.image.height; ++y)
        for (int x = 0; x < s.image.width; ++x) {
            float best = -1;
            for (const EstimatedObject& o : out.objects) {
                for (double z = o.height(); z >= 0 && best < 0; z -= 0.5)
                    if (o.contains(ground_frame(x + 0.5 - o.center_x, y + 0.5 - o.center_y, z))) best = float(z);
                if (best < 0) best = float(std::max(0.0, o.center_y - (y + 0.5)));
            }
            out.heights[std::size_t(y) * s.image.width + x] = std::max(best, 0.f);
        }
    return out;
}

void fill_estimated(OccluderMap& m, const World& world, const Params& p, const std::vector<std::uint32_t>& near,
                    std::vector<std::vector<float>>& heights) {
    std::vector<SpriteSolids> per_sprite(world.tileset.sprites.size());
    std::vector<char> made(per_sprite.size(), 0);
    for (std::uint32_t k : near) {
        const SpriteInstance& in = world.placed.instances[k];
        const std::size_t si = std::size_t(in.sprite);
        if (!made[si]) {
            per_sprite[si] = sprite_solids(world.tileset, world.tileset.sprites[si], p);
            heights[si] = per_sprite[si].heights;
            made[si] = 1;
        }
        const SpriteSolids& ss = per_sprite[si];
        for (std::size_t j = 0; j < ss.objects.size(); ++j) {
            const EstimatedObject& o = ss.objects[j];
            const auto& table = ss.spans[j];
            const double fx = in.x + o.center_x, fy = in.y + o.center_y, widest = (table.size() - 1) / 4.0;
            const Rect box = intersect(Rect{int(std::floor(fx - widest * sqrt2)) - 1, int(std::floor(fy - widest / sqrt2)) - 1,
                                            int(std::ceil(2 * widest * sqrt2)) + 3, int(std::ceil(2 * widest / sqrt2)) + 3},
                                       m.rect);
            for (int y = box.y; y < box.y + box.h; ++y)
                for (int x = box.x; x < box.x + box.w; ++x) {
                    const Vec3 q = ground_frame(x + 0.5 - fx, y + 0.5 - fy, 0);
                    const std::size_t t = std::size_t(std::ceil(std::hypot(q.x, q.y) * 4));
                    if (t >= table.size() || table[t].second <= table[t].first) continue;
                    fill(m, std::size_t(y - m.rect.y) * m.rect.w + (x - m.rect.x), table[t].first, table[t].second);
                }
        }
    }
}

void fill_shapes(OccluderMap& m, const World& world, Rect region) {
    const WorldSolids solids = world_solids(world, region);  // Error naming a sprite without a shape
    for (std::size_t k = 0; k < solids.solids.size(); ++k) {
        const auto& b = solids.bounds[k];
        // The ground rectangle under the solid, on screen: x = X - Y, y = (X + Y) / 2.
        const Rect box = intersect(Rect{int(std::floor(b[0].x - b[1].y)) - 1, int(std::floor((b[0].x + b[0].y) / 2)) - 1,
                                        int(std::ceil((b[1].x - b[0].y) - (b[0].x - b[1].y))) + 3,
                                        int(std::ceil((b[1].x + b[1].y - b[0].x - b[0].y) / 2)) + 3},
                                   m.rect);
        for (int y = box.y; y < box.y + box.h; ++y)
            for (int x = box.x; x < box.x + box.w; ++x) {
                const Vec3 q = ground_frame(x + 0.5, y + 0.5, 0);
                double lo = 0, hi = 0;
                if (vertical_span(solids.solids[k], q.x, q.y, lo, hi))
                    fill(m, std::size_t(y - m.rect.y) * m.rect.w + (x - m.rect.x), lo, hi);
            }
    }
}

}  // namespace

OccluderMap build_occluders(const World& world, const Params& p, Rect region) {
    OccluderMap m;
    m.rect = region;
    const std::size_t n = std::size_t(std::max(0, region.w)) * std::max(0, region.h);
    m.low.assign(n, 0.f);
    m.high.assign(n, 0.f);
    if (region.empty() || p.occluders == Occluders::footprints) {
        m.surface = build_surface(world, region, p.opacity_threshold);
        return m;
    }
    std::vector<std::uint32_t> near;
    instances_in(world.placed, region, true, near);
    if (p.occluders == Occluders::shapes) {
        fill_shapes(m, world, region);
        m.surface = build_surface(world, region, p.opacity_threshold);
    } else {
        std::vector<std::vector<float>> heights(world.tileset.sprites.size());
        fill_estimated(m, world, p, near, heights);
        m.surface = build_surface(world, region, p.opacity_threshold, &heights);
    }
    return m;
}

LightMask trace_light_solids(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b, double height,
                             const Params& p, Rect clip) {
    LightMask m;
    start_mask(m, cx, cy, a, b, p, clip, p.mode == Mode::shadow);
    if (m.clip.empty()) return m;
    const double H = std::max(height, 0.0);
    auto index = [&](std::int64_t x, std::int64_t y) { return std::size_t(y - m.clip.y) * m.clip.w + std::size_t(x - m.clip.x); };
    auto intensity = [&](std::int64_t x, std::int64_t y) {
        return falloff(std::max(std::llabs(x - cx), std::llabs(y - cy)), p.falloff_scale);
    };
    // Ground pixels: one pass per ray, each span before a pixel shading a
    // stretch of the ray beyond it (its own pixel too when it stands on the ground).
    struct Shade { double from, to; };
    std::vector<Shade> shades;
    const double inf = std::numeric_limits<double>::infinity();
    for_each_ray_target(cx, cy, a, b, p, [&](std::int64_t tx, std::int64_t ty) {
        shades.clear();
        for (BresenhamRay r(cx, cy, tx, ty); !r.done(); r.step()) {
            const double k = double(r.i);
            float lo = 0, hi = 0;
            if (occ.span(r.x, r.y, lo, hi) && lo < H)
                shades.push_back({lo <= 0 ? k : k * H / (H - lo), hi >= H ? inf : k * H / (H - hi)});
            bool shaded = false;
            for (std::size_t s = 0; s < shades.size();) {
                if (shades[s].to <= k) {  // behind the ray's front: done with
                    shades[s] = shades.back();
                    shades.pop_back();
                    continue;
                }
                shaded = shaded || shades[s].from <= k;
                ++s;
            }
            if (!shaded && m.clip.contains(int(r.x), int(r.y))) m.value[index(r.x, r.y)] = intensity(r.x, r.y);
        }
    });
    if (p.mode == Mode::shadow) std::fill(m.reached.begin(), m.reached.end(), std::uint8_t(1));
    return m;
}

void light_sprite_points(LightMask& m, const OccluderMap& occ, double height, const Params& p) {
    if (m.clip.empty()) return;
    const double H = std::max(height, 0.0);
    const Surface& surface = occ.surface;
    const std::int64_t cx = m.cx, cy = m.cy;
    auto index = [&](std::int64_t x, std::int64_t y) { return std::size_t(y - m.clip.y) * m.clip.w + std::size_t(x - m.clip.x); };
    auto shows_sprite = [&](std::int64_t x, std::int64_t y) {
        return surface.rect.contains(int(x), int(y)) &&
               surface.instance[std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(x - surface.rect.x)] >= 0;
    };
    // The point each sprite pixel shows, against the spans on its own line.
    const Rect area = intersect(Rect{int(cx) - m.a, int(cy) - m.b, 2 * m.a + 1, 2 * m.b + 1}, m.clip);
    for (int y = area.y; y < area.y + area.h; ++y)
        for (int x = area.x; x < area.x + area.w; ++x) {
            if (!shows_sprite(x, y)) continue;
            const double h = surface.height[std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(x - surface.rect.x)];
            const std::int64_t gx = x, gy = y + std::llround(h);
            const std::int64_t steps = std::max(std::llabs(gx - cx), std::llabs(gy - cy));
            bool lit = true;
            for (BresenhamRay r(cx, cy, gx, gy); lit && !r.done() && r.i <= steps - own_steps; r.step()) {
                float lo = 0, hi = 0;
                if (!occ.span(r.x, r.y, lo, hi)) continue;
                const double z = H + (h - H) * double(r.i) / double(steps);
                lit = !(z >= lo && z < hi);
            }
            m.value[index(x, y)] = lit ? falloff(std::max(std::llabs(x - cx), std::llabs(y - cy)), p.falloff_scale) : 0;
        }
}

}  // namespace isolux
