// Paper 3.1: the obstacle map. Algorithm 1 estimates, per overlay sprite, the
// footprint where it stands; the n x n box-shaped noise reduction then erases
// tiny obstacles.
#include "isolux/obstacle_map.hpp"

#include "isolux/footprint.hpp"

#include <cassert>
#include <algorithm>
#include <cmath>
#include <limits>

#include "isolux/opacity_map.hpp"

namespace isolux {

Mask sprite_obstacle(const Mask& opacity, int delta_y, SpriteObstacleTrace* trace) {
    assert(delta_y >= 1);
    const int w = opacity.width, h = opacity.height;
    int bottom = -1;  // the sprite's lowest opaque row: where it stands on the ground
    for (int y = h - 1; y >= 0 && bottom < 0; --y)
        for (int x = 0; x < w; ++x)
            if (opacity.bits[std::size_t(y) * w + x]) {
                bottom = y;
                break;
            }
    SpriteObstacleTrace t;
    if (bottom < 0) {
        if (trace) *trace = t;
        return Mask(Rect{0, 0, 0, 0});
    }
    t.last_line = bottom;
    t.first_line = std::max(0, bottom - delta_y + 1);

    // Step 1: the longest run of non-transparent pixels of each Δy line.
    struct Run { int row, start, length; };
    std::vector<Run> runs;
    for (int y = t.first_line; y <= t.last_line; ++y) {
        Run best{y, 0, 0};
        int start = 0, len = 0;
        for (int x = 0; x <= w; ++x) {
            bool on = x < w && opacity.bits[std::size_t(y) * w + x];
            if (on) {
                if (len == 0) start = x;
                ++len;
            } else {
                if (len > best.length) best = {y, start, len};  // ties: the leftmost run
                len = 0;
            }
        }
        if (best.length > 0) runs.push_back(best);
    }
    // Step 2: the run with the least deviation from the mean length (ties: the
    // lower line, nearer the ground).
    double mean = 0;
    for (const Run& r : runs) mean += r.length;
    mean /= double(runs.size());
    const Run* s = &runs.front();
    for (const Run& r : runs)
        if (std::abs(r.length - mean) <= std::abs(s->length - mean)) s = &r;
    t.chosen_line = s->row;
    t.run_start = s->start;
    t.run_length = s->length;

    // Steps 3 and 4: mark s, then length/4 pixels above and below its centre.
    const int arm = s->length / 4;
    const int cx = s->start + (s->length - 1) / 2;
    Mask m(Rect{0, s->row - arm, w, 2 * arm + 1});
    for (int x = s->start; x < s->start + s->length; ++x) m.set(x, s->row);
    for (int y = s->row - arm; y <= s->row + arm; ++y) m.set(cx, y);
    if (trace) *trace = t;
    return m;
}

Mask noise_filter(const Mask& in, int n) {
    assert(n >= 1);
    const int w = in.width, h = in.height;
    // Summed-area table of the unfiltered mask: the in-place pass never reads a
    // pixel it cleared (see the header), so the original counts are the ones
    // the paper's sliding window sees.
    std::vector<std::int64_t> sat(std::size_t(w + 1) * (h + 1), 0);
    auto S = [&](int x, int y) -> std::int64_t& { return sat[std::size_t(y) * (w + 1) + x]; };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            S(x + 1, y + 1) = in.bits[std::size_t(y) * w + x] + S(x, y + 1) + S(x + 1, y) - S(x, y);
    Mask out = in;
    for (int y = 0; y < h; ++y) {
        const int y1 = std::min(h, y + n);
        for (int x = 0; x < w; ++x) {
            std::uint8_t& px = out.bits[std::size_t(y) * w + x];
            if (!px) continue;
            const int x1 = std::min(w, x + n);
            std::int64_t count = S(x1, y1) - S(x, y1) - S(x1, y) + S(x, y);
            if (count < n) px = 0;
        }
    }
    return out;
}

Mask build_obstacle_map(const Tileset& ts, const PlacedMap& placed, const Params& p, Rect region,
                        const std::vector<Mask>* footprints) {
    assert(p.delta_y >= 1 && p.noise_window >= 1 && p.opacity_threshold >= 0 && p.opacity_threshold <= 1);
    // Algorithm 1 depends only on the sprite, Δy and the threshold: run it once
    // per sprite, then stamp it at every instance.
    std::vector<Mask> per_sprite(ts.sprites.size());
    std::vector<char> done(ts.sprites.size(), 0);
    const Rect grown{region.x, region.y, region.w + p.noise_window - 1, region.h + p.noise_window - 1};
    Mask raw(grown);
    // Algorithm 1's arms may reach past a sprite's rectangle by a quarter of
    // its width: look that far around the region.
    int reach = 0;
    for (const Sprite& s : ts.sprites) reach = std::max(reach, s.image.width / 4 + 1);
    std::vector<std::uint32_t> near;
    instances_in(placed, grown, true, near, reach);
    for (std::uint32_t i : near) {
        const SpriteInstance& in = placed.instances[i];
        const Sprite& s = ts.sprites[in.sprite];
        if (!footprints && !done[in.sprite]) {
            per_sprite[in.sprite] = tileset_footprint(ts, s, p);
            done[in.sprite] = 1;
        }
        const Mask& m = footprints ? (*footprints)[std::size_t(in.sprite)] : per_sprite[in.sprite];
        Rect r = intersect({in.x + m.x0, in.y + m.y0, m.width, m.height}, grown);
        for (int y = r.y; y < r.y + r.h; ++y)
            for (int x = r.x; x < r.x + r.w; ++x)
                if (m.bits[std::size_t(y - in.y - m.y0) * m.width + (x - in.x - m.x0)]) raw.set(x, y);
    }
    Mask filtered = noise_filter(raw, p.noise_window);
    Mask out(region);
    for (int y = 0; y < region.h; ++y)
        std::copy_n(&filtered.bits[std::size_t(y) * grown.w], region.w, &out.bits[std::size_t(y) * region.w]);
    return out;
}

}  // namespace isolux
