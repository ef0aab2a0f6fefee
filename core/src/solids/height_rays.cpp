// Beyond the paper (height_rays.hpp): rays over low obstacles.
#include "isolux/height_rays.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "isolux/footprint.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"

namespace isolux {

int estimated_height(const Mask& opacity, int footprint_width) {
    int top = -1, bottom = -1;
    for (int y = 0; y < opacity.height; ++y)
        for (int x = 0; x < opacity.width; ++x)
            if (opacity.bits[std::size_t(y) * opacity.width + x]) {
                if (top < 0) top = y;
                bottom = y;
                break;
            }
    // The opaque rows span the height plus the footprint's depth on screen,
    // which in 2:1 isometric is half its width.
    return top < 0 ? 0 : std::max(1, bottom - top + 1 - footprint_width / 2);
}

ObstacleHeights build_obstacle_heights(const Tileset& ts, const PlacedMap& placed, const Params& p,
                                       const Mask& obstacles) {
    ObstacleHeights out;
    out.rect = obstacles.rect();
    out.height.assign(obstacles.bits.size(), 0);
    if (out.rect.empty()) return out;
    std::vector<Mask> footprint(ts.sprites.size());
    std::vector<int> tall(ts.sprites.size(), -1);
    int reach = 0;
    for (const Sprite& s : ts.sprites) reach = std::max(reach, s.image.width / 4 + 1);
    std::vector<std::uint32_t> near;
    instances_in(placed, out.rect, true, near, reach);
    for (std::uint32_t i : near) {
        const SpriteInstance& in = placed.instances[i];
        const Sprite& s = ts.sprites[std::size_t(in.sprite)];
        if (tall[std::size_t(in.sprite)] < 0) {
            FootprintReport report;
            footprint[std::size_t(in.sprite)] = tileset_footprint(ts, s, p, &report);
            tall[std::size_t(in.sprite)] = std::min(65535, estimated_height(report.estimate, report.trace.run_length));
        }
        const Mask& m = footprint[std::size_t(in.sprite)];
        const auto h = std::uint16_t(tall[std::size_t(in.sprite)]);
        const Rect r = intersect({in.x + m.x0, in.y + m.y0, m.width, m.height}, out.rect);
        for (int y = r.y; y < r.y + r.h; ++y)
            for (int x = r.x; x < r.x + r.w; ++x) {
                if (!m.bits[std::size_t(y - in.y - m.y0) * m.width + (x - in.x - m.x0)] || !obstacles.get(x, y)) continue;
                std::uint16_t& cell = out.height[std::size_t(y - out.rect.y) * out.rect.w + (x - out.rect.x)];
                cell = std::max(cell, h);
            }
    }
    return out;
}

LightMask trace_light_over(const Mask& obstacles, const ObstacleHeights& heights, std::int64_t cx, std::int64_t cy,
                           int a, int b, double height, const Params& p, Rect clip) {
    assert(a >= 0 && b >= 0 && p.ray_skip >= 1 && height >= 0);
    LightMask m;
    start_mask(m, cx, cy, a, b, p, clip);
    if (clip.empty()) return m;
    const int dmax = std::max(a, b);
    std::vector<std::uint8_t> table(std::size_t(dmax) + 1);
    for (int d = 0; d <= dmax; ++d) table[std::size_t(d)] = falloff(d, p.falloff_scale);
    const bool flat = p.mode == Mode::flat;
    auto trace = [&](std::int64_t tx, std::int64_t ty) {
        // reach: the furthest step an obstacle passed so far still shades.
        double reach = -1;
        std::int64_t step = 0;
        for (BresenhamRay r(cx, cy, tx, ty); !r.done(); r.step(), ++step) {
            const bool obstacle = !flat && obstacles.get(int(r.x), int(r.y));
            if (obstacle) {
                const double h = heights.at(int(r.x), int(r.y));
                reach = h >= height ? std::numeric_limits<double>::infinity()
                                    : std::max(reach, double(step) / (1 - h / height));
            }
            const std::int64_t lx = r.x - clip.x, ly = r.y - clip.y;
            if (obstacle || double(step) <= reach || lx < 0 || ly < 0 || lx >= clip.w || ly >= clip.h) continue;
            m.value[std::size_t(ly) * clip.w + std::size_t(lx)] =
                table[std::size_t(std::max(std::llabs(r.x - cx), std::llabs(r.y - cy)))];
        }
    };
    for_each_ray_target(cx, cy, a, b, p, trace);
    return m;
}

}  // namespace isolux
