// Paper 3.2, Figures 6 and 7: "the opacity maps of the sprites are subtracted
// or added to the light texture. If the iterated sprite is at a higher
// position than the center of the light in the vertical direction, the
// opacity map of the same is added ... Otherwise ... subtracted."
#include "isolux/opacity_correction.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "base/cpu_dispatch.hpp"
#include "base/cpu.hpp"
#include "base/rows_ahead.hpp"

namespace isolux {

int correct_with_opacity_maps(LightMask& mask, const PlacedMap& placed, const std::vector<Mask>& opacity) {
    int touched = 0;
    const Rect clip = mask.clip;
    // The falloff by distance, tabulated for the clip's extent.
    const std::int64_t dmax = std::max<std::int64_t>({std::llabs(clip.x - mask.cx), std::llabs(clip.x + clip.w - 1 - mask.cx),
                                                      std::llabs(clip.y - mask.cy), std::llabs(clip.y + clip.h - 1 - mask.cy)});
    std::vector<std::uint8_t> table(std::size_t(std::max<std::int64_t>(0, dmax)) + 1);
    for (std::size_t d = 0; d < table.size(); ++d) table[d] = falloff(std::int64_t(d), mask.falloff_scale);
    std::vector<std::uint32_t> near;
    instances_in(placed, clip, true, near);
    for (std::uint32_t k : near) {
        const SpriteInstance& in = placed.instances[k];
        const Mask& op = opacity[in.sprite];
        const Rect r = intersect({in.x, in.y, op.width, op.height}, clip);
        if (r.empty()) continue;
        ++touched;
        const bool added = opacity_map_added(in, mask.cy);
        for (int y = r.y; y < r.y + r.h; ++y) {
            const std::uint8_t* src = &op.bits[std::size_t(y - in.y) * op.width + (r.x - in.x)];
            std::uint8_t* dst = &mask.value[std::size_t(y - clip.y) * clip.w + (r.x - clip.x)];
            const std::int64_t dy = std::llabs(y - mask.cy);
            for (int x = 0; x < r.w; ++x)
                if (src[x])
                    dst[x] = added ? table[std::size_t(std::max<std::int64_t>(std::llabs(r.x + x - mask.cx), dy))] : 0;
        }
        // In shadow mode the corrected pixels count as reached, so an
        // unlit (subtracted) sprite pixel joins the shadow.
        if (!mask.reached.empty())
            for (int y = r.y; y < r.y + r.h; ++y) {
                const std::uint8_t* src = &op.bits[std::size_t(y - in.y) * op.width + (r.x - in.x)];
                std::uint8_t* dst = &mask.reached[std::size_t(y - clip.y) * clip.w + (r.x - clip.x)];
                for (int x = 0; x < r.w; ++x)
                    if (src[x]) dst[x] = 1;
            }
    }
    return touched;
}

}  // namespace isolux

namespace isolux {

namespace {

bool fits_a_byte(std::int16_t below) { return below == GroundLines::none || (below >= -127 && below <= 127); }

// The part of row y from x0 to x1: how many of its pixels do not fit below8.
std::uint32_t wide_pixels(const GroundLines& lines, int y, int x0, int x1) {
    const std::int16_t* below = &lines.below[std::size_t(y - lines.rect.y) * lines.rect.w + std::size_t(x0 - lines.rect.x)];
    std::uint32_t n = 0;
    for (int x = 0; x < x1 - x0; ++x) n += !fits_a_byte(below[x]);
    return n;
}

void paint(GroundLines& lines, const PlacedMap& placed, const std::vector<Mask>& opacity, Rect part) {
    part = intersect(part, lines.rect);
    if (part.empty()) return;
    const int w = lines.rect.w;
    for (int y = part.y; y < part.y + part.h; ++y)
        lines.wide[std::size_t(y - lines.rect.y)] -= wide_pixels(lines, y, part.x, part.x + part.w);
    for (int y = part.y; y < part.y + part.h; ++y)
        std::fill_n(&lines.below[std::size_t(y - lines.rect.y) * w + (part.x - lines.rect.x)], part.w, GroundLines::none);
    std::vector<std::uint32_t> near;
    instances_in(placed, part, true, near);
    for (std::uint32_t k : near) {  // draw order: the sprite in front decides
        const SpriteInstance& in = placed.instances[k];
        const Mask& op = opacity[in.sprite];
        const Rect r = intersect({in.x, in.y, op.width, op.height}, part);
        for (int y = r.y; y < r.y + r.h; ++y) {
            const std::int64_t d = std::int64_t(in.ground_y) - y;
            if (d <= GroundLines::none || d >= INT16_MAX) lines.exact = false;
            const std::int16_t below = std::int16_t(std::clamp<std::int64_t>(d, GroundLines::none + 1, INT16_MAX - 1));
            const std::uint8_t* src = &op.bits[std::size_t(y - in.y) * op.width + (r.x - in.x)];
            std::int16_t* dst = &lines.below[std::size_t(y - lines.rect.y) * w + (r.x - lines.rect.x)];
            for (int x = 0; x < r.w; ++x) dst[x] = src[x] ? below : dst[x];  // a select: vectorised
        }
    }
    for (int y = part.y; y < part.y + part.h; ++y) {
        const std::size_t at = std::size_t(y - lines.rect.y) * w + std::size_t(part.x - lines.rect.x);
        for (int x = 0; x < part.w; ++x) {
            const std::int16_t b = lines.below[at + std::size_t(x)];
            lines.below8[at + std::size_t(x)] = b == GroundLines::none || !fits_a_byte(b) ? 0 : std::uint8_t(b + 128);
        }
        lines.wide[std::size_t(y - lines.rect.y)] += wide_pixels(lines, y, part.x, part.x + part.w);
    }
}

}  // namespace

GroundLines ground_lines(const PlacedMap& placed, const std::vector<Mask>& opacity, Rect region) {
    GroundLines lines;
    lines.rect = region.empty() ? Rect{} : region;
    lines.below.assign(std::size_t(std::max(0, lines.rect.w)) * std::max(0, lines.rect.h), GroundLines::none);
    lines.below8.assign(lines.below.size(), 0);
    lines.wide.assign(std::size_t(std::max(0, lines.rect.h)), 0);
    paint(lines, placed, opacity, lines.rect);
    return lines;
}

void repaint_ground_lines(GroundLines& lines, const PlacedMap& placed, const std::vector<Mask>& opacity, Rect part) {
    paint(lines, placed, opacity, part);
}

void pan_ground_lines(GroundLines& lines, const PlacedMap& placed, const std::vector<Mask>& opacity, Rect region) {
    const Rect from = lines.rect;
    move_grid(lines.below, from, region, GroundLines::none);
    move_grid(lines.below8, from, region);
    lines.rect = region;
    // Columns moved into and out of every row: each row's wide pixels counted again.
    lines.wide.assign(std::size_t(region.h), 0);
    for (int y = region.y; y < region.y + region.h; ++y)
        lines.wide[std::size_t(y - region.y)] = wide_pixels(lines, y, region.x, region.x + region.w);
    for (const Rect& r : outside(region, intersect(from, region))) paint(lines, placed, opacity, r);
}

namespace {

// 32 pixels of a row as one value: GCC's vector extensions, which the
// baseline build lowers to two SSE2 halves and the AVX2 build to one register.
// (Loads and stores by memcpy: unaligned, and no vector crosses a call.)
using Bytes32 = std::uint8_t __attribute__((vector_size(32)));

// 32 pixels of correct_byte_row: from the bytes at b8, f8 and v8 into `to`.
// Two selects (one vpblendvb, one and): two ops fewer than masks combined by
// hand.
[[gnu::always_inline]] inline void correct_32(const std::uint8_t* b8, const std::uint8_t* f8, const std::uint8_t* v8,
                                              const Bytes32& vys, const Bytes32& tops, std::uint8_t* to) {
    Bytes32 b, f, v;
    std::memcpy(&b, b8, 32), std::memcpy(&f, f8, 32), std::memcpy(&v, v8, 32);
    const Bytes32 zero{};
    const Bytes32 lit = b <= tops ? (f < vys ? f : vys) : zero;
    v = b == zero ? v : lit;
    std::memcpy(to, &v, 32);
}

// One row of the byte lines, `w` pixels: value = none ? value : (stands
// above ? min(fx, vy) : 0), where "stands above" is below8 <= top.
[[gnu::always_inline]] inline void correct_byte_row(std::uint8_t* value, std::uint8_t* reached, const std::uint8_t* below8,
                                                    const std::uint8_t* fx, std::uint8_t vy, std::uint8_t top, int w) {
    const Bytes32 vys = Bytes32{} + vy, tops = Bytes32{} + top;
    if (w >= 32) {
        // The last 32 pixels, ending at w, computed before any store and
        // stored last, over pixels the loop may have done: with the same
        // bytes, each pixel's depending on its own alone. (Loaded after the
        // loop's stores they would wait for them: no store forwarding on a
        // partial overlap.)
        alignas(32) std::uint8_t last[32];
        correct_32(below8 + w - 32, fx + w - 32, value + w - 32, vys, tops, last);
        int x = 0;
        for (; x + 32 <= w; x += 32) correct_32(below8 + x, fx + x, value + x, vys, tops, value + x);
        if (x < w) std::memcpy(value + w - 32, last, 32);
    } else {
        for (int x = 0; x < w; ++x) {  // branch-free: the pixels' kinds do not follow a pattern
            const std::uint8_t b = below8[x], f = fx[x] < vy ? fx[x] : vy;
            const std::uint8_t keep = std::uint8_t(-std::uint8_t(b == 0)), lit = std::uint8_t(-std::uint8_t(b <= top));
            value[x] = std::uint8_t((value[x] & keep) | (f & lit & std::uint8_t(~keep)));
        }
    }
    if (reached)
        for (int x = 0; x < w; ++x) reached[x] = below8[x] == 0 ? reached[x] : std::uint8_t(1);
}

// The pass at two widths (base/cpu.hpp): the same code, vectorised twice.
[[gnu::always_inline]] inline void correct_lines(LightMask& mask, const GroundLines& lines) {
    const Rect clip = mask.clip;
    const Rect r = intersect(clip, lines.rect);
    if (r.empty()) return;
    // falloff(max(|dx|, |dy|)) = min(falloff(|dx|), falloff(|dy|)): it never
    // increases. Tabulated by distance once, kept while the scale holds.
    thread_local std::vector<std::uint8_t> by_d;
    thread_local double by_d_scale = 0;
    const std::size_t far = std::size_t(std::max({std::llabs(r.x - mask.cx), std::llabs(r.x + r.w - 1 - mask.cx),
                                                  std::llabs(r.y - mask.cy), std::llabs(r.y + r.h - 1 - mask.cy)}));
    if (by_d_scale != mask.falloff_scale) by_d.clear(), by_d_scale = mask.falloff_scale;
    // (A light centred far outside its clip does not grow the table.)
    for (std::size_t d = by_d.size(); d <= std::min<std::size_t>(far, 1 << 16); ++d)
        by_d.push_back(falloff(std::int64_t(d), mask.falloff_scale));
    // (The tables' pointers read once: each use of a thread_local calls its guard.)
    const std::uint8_t* const table = by_d.data();
    const std::size_t table_size = by_d.size();
    auto fall = [&](std::int64_t d) {
        return std::size_t(d) < table_size ? table[std::size_t(d)] : falloff(d, mask.falloff_scale);
    };
    thread_local std::vector<std::uint8_t> by_x;
    by_x.resize(std::size_t(r.w));
    std::uint8_t* const fx = by_x.data();
    if (far < table_size) {
        // The table itself, read outwards from the centre's column (c) and
        // mirrored left of it: a copy, not a lookup per pixel.
        const std::int64_t c = mask.cx - r.x;
        const int left = int(std::clamp<std::int64_t>(c + 1, 0, r.w));
        for (int x = 0; x < left; ++x) fx[x] = table[std::size_t(c - x)];
        if (left < r.w) std::memcpy(fx + left, table + std::size_t(left - c), std::size_t(r.w - left));
    } else {
        for (int x = 0; x < r.w; ++x) fx[x] = fall(std::llabs(r.x + x - mask.cx));
    }
    const bool shadow = !mask.reached.empty();
    const std::size_t stride = std::size_t(lines.rect.w);
    for (int y = r.y; y < r.y + r.h;) {
        const std::size_t line = std::size_t(y - lines.rect.y) * stride + std::size_t(r.x - lines.rect.x);
        const std::size_t m = std::size_t(y - clip.y) * clip.w + std::size_t(r.x - clip.x);
        // A sprite stands above the centre when ground_y < cy, i.e. below < cy - y.
        if (lines.wide[std::size_t(y - lines.rect.y)] == 0) {
            // The rows from here that fit a byte, in one lean loop.
            int y1 = y + 1;
            while (y1 < r.y + r.h && lines.wide[std::size_t(y1 - lines.rect.y)] == 0) ++y1;
            const std::uint8_t* below8 = &lines.below8[line];
            std::uint8_t* value = &mask.value[m];
            std::uint8_t* reached = shadow ? &mask.reached[m] : nullptr;
            // The lines are a world-wide array (rows_ahead.hpp).
            for (int k = 0; k < rows_ahead && y + k < y1; ++k) ask_for_row(below8 + std::size_t(k) * stride, std::size_t(r.w));
            for (; y < y1; ++y, below8 += stride, value += clip.w, reached += shadow ? clip.w : 0) {
                if (y + rows_ahead < y1) ask_for_row(below8 + std::size_t(rows_ahead) * stride, std::size_t(r.w));
                // below < cy - y  <=>  below8 = below + 128 <= cy - y + 127 (below8 >= 1).
                const std::uint8_t top = std::uint8_t(std::clamp<std::int64_t>(mask.cy - y + 127, 0, 255));
                correct_byte_row(value, reached, below8, fx, fall(std::llabs(y - mask.cy)), top, r.w);
            }
            continue;
        }
        std::uint8_t* value = &mask.value[m];
        const std::uint8_t vy = fall(std::llabs(y - mask.cy));
        const std::int16_t* below = &lines.below[line];
        const std::int16_t above = std::int16_t(std::clamp<std::int64_t>(mask.cy - y, GroundLines::none + 1, INT16_MAX));
        for (int x = 0; x < r.w; ++x) {
            const std::int16_t b = below[x];
            std::uint8_t f = fx[x];
            f = f < vy ? f : vy;
            const std::uint8_t keep = std::uint8_t(-std::uint8_t(b == GroundLines::none));
            const std::uint8_t lit = std::uint8_t(-std::uint8_t(b < above));
            value[x] = std::uint8_t((value[x] & keep) | (f & lit & std::uint8_t(~keep)));
        }
        if (shadow)
            for (int x = 0; x < r.w; ++x)
                mask.reached[m + std::size_t(x)] = below[x] == GroundLines::none ? mask.reached[m + std::size_t(x)] : std::uint8_t(1);
        ++y;
    }
}

void correct_lines_baseline(LightMask& mask, const GroundLines& lines) { correct_lines(mask, lines); }
ISOLUX_AVX2 void correct_lines_avx2(LightMask& mask, const GroundLines& lines) { correct_lines(mask, lines); }

}  // namespace

void correct_with_ground_lines(LightMask& mask, const GroundLines& lines) {
    wide_kernels() ? correct_lines_avx2(mask, lines) : correct_lines_baseline(mask, lines);
}

}  // namespace isolux
