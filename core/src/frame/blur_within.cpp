// Beyond the paper: the blur within surfaces (blur.hpp, box_blur_within):
// the paper's box blur, its windows never crossing into another surface, so
// light on the ground never bleeds onto a sprite in front of it.
#include "isolux/blur.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "frame/fused_radius.hpp"
#include "frame/oracles.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace isolux {

namespace {

// A texel whose window lies inside the texture and the surfaces' rectangle,
// summed as box_blur_within's rule says: straight reads, and no branch on
// the runs' lengths (a flag carried outwards from the centre along the
// column and each row). R is the radius, known when compiled.
template <int C, int R>
void blur_within_texel(const LightTexture& tex, const SurfaceIds& ids, int x, int y, LightTexture& out) {
    const Rect t = tex.rect, s = ids.rect;
    const std::int32_t* id0 = &ids.id[std::size_t(y - s.y) * s.w + std::size_t(x - s.x)];
    const std::uint8_t* v0 = &tex.texels[(std::size_t(y - t.y) * t.w + std::size_t(x - t.x)) * C];
    const std::int32_t surface = *id0;
    std::uint32_t sum[C] = {};
    std::uint32_t n = 0;
    auto add_row = [&](int dy, std::uint32_t on) {
        const std::int32_t* row = id0 + std::ptrdiff_t(dy) * s.w;
        const std::uint8_t* v = v0 + std::ptrdiff_t(dy) * t.w * C;
        for (int k = 0; k < C; ++k) sum[k] += v[k] & (0u - on);
        n += on;
        std::uint32_t left = on, right = on;
        for (int i = 1; i <= R; ++i) {
            left &= std::uint32_t(row[-i] == surface);
            right &= std::uint32_t(row[i] == surface);
            for (int k = 0; k < C; ++k) sum[k] += (v[-i * C + k] & (0u - left)) + (v[i * C + k] & (0u - right));
            n += left + right;
        }
    };
    add_row(0, 1);
    std::uint32_t up = 1, down = 1;
    for (int k = 1; k <= R; ++k) {
        up &= std::uint32_t(id0[-std::ptrdiff_t(k) * s.w] == surface);
        down &= std::uint32_t(id0[std::ptrdiff_t(k) * s.w] == surface);
        add_row(-k, up);
        add_row(k, down);
    }
    std::uint8_t* o = &out.texels[(std::size_t(y - t.y) * t.w + std::size_t(x - t.x)) * C];
    for (int k = 0; k < C; ++k) o[k] = std::uint8_t((sum[k] + n / 2) / n);
}

// Whether every texel of the (2R + 1)^2 window around v0 (inside the
// texture) holds v0's value: then the rule's mean is that value whatever
// surfaces the window meets, the plain blur's too, and the texel needs no
// redo. Most texels near a sprite's outline lie in the dark between lights.
template <int C, int R>
bool window_uniform(const std::uint8_t* v0, std::ptrdiff_t row_bytes) {
    std::uint32_t differ = 0;
    for (int dy = -R; dy <= R; ++dy) {
        const std::uint8_t* row = v0 + dy * row_bytes;
        for (int i = -R; i <= R; ++i)
            for (int k = 0; k < C; ++k) differ |= std::uint32_t(row[i * C + k] ^ v0[k]);
    }
    return differ == 0;
}

#if defined(__SSE2__)
// Whether the windows of sixteen texels in a row, from `first` on (inside
// the texture), hold nothing but 0: the dark between lights, where every
// texel's blur is 0 by either rule. Overlapping loads keep to the rows.
template <int C, int R>
bool windows_dark(const std::uint8_t* first, std::ptrdiff_t row_bytes) {
    constexpr int bytes = (16 + 2 * R) * C;
    static_assert(bytes >= 16);
    __m128i any = _mm_setzero_si128();
    for (int dy = -R; dy <= R; ++dy) {
        const std::uint8_t* row = first - R * C + dy * row_bytes;
        for (int i = 0; i + 16 < bytes; i += 16)
            any = _mm_or_si128(any, _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i)));
        any = _mm_or_si128(any, _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + bytes - 16)));
    }
    return _mm_movemask_epi8(_mm_cmpeq_epi8(any, _mm_setzero_si128())) == 0xffff;
}

// The rule for a strip sixteen texels wide, rows [ya, yb) (their windows
// inside the texture and the surfaces' rectangle), from column x, for the
// texels near another surface: per row of the window, each lane's run along
// the row (the joins to the right, carried outwards from the lane), kept for
// the next rows down the strip; then the rows kept while the lane's column
// stays on its surface (the joins down). The sums fit 16 bits (225 x 255 at
// radius 7); the rounded mean (s + n / 2) / n comes from a float division,
// exact here: a quotient that is not whole lies at least 1 / n >= 1 / 225
// from a whole number, more than half a float's step (1 / 512) below 65,536.
template <int R>
void blur_within_strip(const LightTexture& tex, const SurfaceIds& ids, int x, int ya, int yb, LightTexture& out) {
    const Rect t = tex.rect, s = ids.rect;
    const std::ptrdiff_t row_bytes = t.w, join_w = s.w;
    const std::uint8_t* values = &tex.texels[std::size_t(ya - t.y) * t.w + std::size_t(x - t.x)];
    const std::uint8_t* joins = &ids.joins[std::size_t(ya - s.y) * s.w + std::size_t(x - s.x)];
    const std::uint8_t* reach = &ids.reach[std::size_t(ya - s.y) * s.w + std::size_t(x - s.x)];
    std::uint8_t* result = &out.texels[std::size_t(ya - t.y) * t.w + std::size_t(x - t.x)];
    const __m128i zero = _mm_setzero_si128(), all = _mm_cmpeq_epi8(zero, zero), one = _mm_set1_epi8(1),
                  limit = _mm_set1_epi8(char(R)), right_bit = _mm_set1_epi8(char(SurfaceIds::join_right)),
                  down_bit = _mm_set1_epi8(char(SurfaceIds::join_down));
    auto load = [](const std::uint8_t* p) __attribute__((always_inline)) {
        return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    };
    auto joined = [&](const std::uint8_t* j, __m128i bit) __attribute__((always_inline)) {
        return _mm_cmpeq_epi8(_mm_and_si128(load(j), bit), bit);
    };
    // The rows' runs, by row (dy from ya) modulo 2R + 1: sums (16-bit, low
    // and high lanes) and counts (bytes).
    constexpr int rows = 2 * R + 1;
    struct Run {
        __m128i lo, hi, n;
        __m128i down;  // where the row's pixel joins the one below it
        int row;
    };
    std::array<Run, rows> run;
    for (Run& r : run) r.row = std::numeric_limits<int>::min();
    auto run_of = [&](int dy) __attribute__((always_inline)) -> const Run& {
        Run& r = run[std::size_t(dy + R) % rows];
        if (r.row == dy) return r;
        r.row = dy;
        const std::uint8_t* v = values + dy * row_bytes;
        const std::uint8_t* j = joins + dy * join_w;
        const __m128i centre = load(v);
        r.down = joined(j, down_bit);
        r.lo = _mm_unpacklo_epi8(centre, zero), r.hi = _mm_unpackhi_epi8(centre, zero), r.n = one;
        __m128i left = all, right = all;
        for (int i = 1; i <= R; ++i) {
            right = _mm_and_si128(right, joined(j + i - 1, right_bit));  // x + i - 1 joins x + i
            left = _mm_and_si128(left, joined(j - i, right_bit));        // x - i joins x - i + 1
            const __m128i a = _mm_and_si128(load(v + i), right), b = _mm_and_si128(load(v - i), left);
            r.lo = _mm_add_epi16(r.lo, _mm_add_epi16(_mm_unpacklo_epi8(a, zero), _mm_unpacklo_epi8(b, zero)));
            r.hi = _mm_add_epi16(r.hi, _mm_add_epi16(_mm_unpackhi_epi8(a, zero), _mm_unpackhi_epi8(b, zero)));
            r.n = _mm_add_epi8(r.n, _mm_sub_epi8(zero, _mm_add_epi8(right, left)));  // each -1 where kept
        }
        return r;
    };
    for (int dy = 0; dy < yb - ya; ++dy) {
        const std::uint8_t* v0 = values + dy * row_bytes;
        const __m128i r = load(reach + dy * join_w);
        const __m128i near = _mm_cmpeq_epi8(_mm_min_epu8(r, limit), r);
        if (_mm_movemask_epi8(near) == 0 || windows_dark<1, R>(v0, row_bytes)) continue;
        const Run& mid = run_of(dy);
        __m128i lo = mid.lo, hi = mid.hi, n = mid.n;
        auto add = [&](const Run& w, __m128i on) __attribute__((always_inline)) {
            lo = _mm_add_epi16(lo, _mm_and_si128(w.lo, _mm_unpacklo_epi8(on, on)));
            hi = _mm_add_epi16(hi, _mm_and_si128(w.hi, _mm_unpackhi_epi8(on, on)));
            n = _mm_add_epi8(n, _mm_and_si128(w.n, on));
        };
        __m128i up = all, down = mid.down;
        for (int k = 1; k <= R; ++k) {
            const Run& above = run_of(dy - k);
            up = _mm_and_si128(up, above.down);  // row y - k joins y - k + 1
            add(above, up);
            const Run& below = run_of(dy + k);
            add(below, down);
            if (k < R) down = _mm_and_si128(down, below.down);  // row y + k joins y + k + 1
        }
        // (s + n / 2) / n, four lanes at a time.
        const __m128i n_lo = _mm_unpacklo_epi8(n, zero), n_hi = _mm_unpackhi_epi8(n, zero);
        lo = _mm_add_epi16(lo, _mm_srli_epi16(n_lo, 1));
        hi = _mm_add_epi16(hi, _mm_srli_epi16(n_hi, 1));
        auto quotient = [&](__m128i s16, __m128i n16) __attribute__((always_inline)) {
            auto q = [&](__m128i sv, __m128i nv) {
                return _mm_cvttps_epi32(_mm_div_ps(_mm_cvtepi32_ps(sv), _mm_cvtepi32_ps(nv)));
            };
            return _mm_packs_epi32(q(_mm_unpacklo_epi16(s16, zero), _mm_unpacklo_epi16(n16, zero)),
                                   q(_mm_unpackhi_epi16(s16, zero), _mm_unpackhi_epi16(n16, zero)));
        };
        const __m128i q = _mm_packus_epi16(quotient(lo, n_lo), quotient(hi, n_hi));
        std::uint8_t* o = result + dy * row_bytes;
        _mm_storeu_si128(reinterpret_cast<__m128i*>(o), _mm_or_si128(_mm_and_si128(near, q), _mm_andnot_si128(near, load(o))));
    }
}
#endif

// Whether every texel of `window` (inside the texture) is 0.
template <int C>
bool window_dark(const LightTexture& tex, Rect window) {
    const Rect t = tex.rect;
    std::uint32_t any = 0;
    for (int y = window.y; y < window.y + window.h; ++y) {
        const std::uint8_t* v = &tex.texels[(std::size_t(y - t.y) * t.w + std::size_t(window.x - t.x)) * C];
        for (int i = 0; i < window.w * C; ++i) any |= v[i];
    }
    return any == 0;
}

// The same for any texel: the texture's edge bounds the walks, and pixels
// outside the surfaces' rectangle are the ground.
template <int C>
void blur_within_texel_any(const LightTexture& tex, int r, const SurfaceIds& ids, int x, int y, LightTexture& out) {
    const Rect t = tex.rect;
    const std::int32_t surface = ids.at(x, y);
    std::uint32_t sum[C] = {};
    std::uint32_t n = 0;
    auto add_row = [&](int yy) {
        const std::uint8_t* v = &tex.texels[std::size_t(yy - t.y) * t.w * C];
        int lo = x, hi = x;
        while (lo > t.x && x - lo < r && ids.at(lo - 1, yy) == surface) --lo;
        while (hi + 1 < t.x + t.w && hi - x < r && ids.at(hi + 1, yy) == surface) ++hi;
        for (int xx = lo; xx <= hi; ++xx)
            for (int k = 0; k < C; ++k) sum[k] += v[std::size_t(xx - t.x) * C + k];
        n += std::uint32_t(hi - lo + 1);
    };
    add_row(y);
    for (int k = 1; k <= r && y - k >= t.y && ids.at(x, y - k) == surface; ++k) add_row(y - k);
    for (int k = 1; k <= r && y + k < t.y + t.h && ids.at(x, y + k) == surface; ++k) add_row(y + k);
    std::uint8_t* o = &out.texels[(std::size_t(y - t.y) * t.w + std::size_t(x - t.x)) * C];
    for (int k = 0; k < C; ++k) o[k] = std::uint8_t((sum[k] + n / 2) / n);
}

// box_blur_within_into's work over z (inside the texture) for radii the
// plain blur fuses. Where a texel's whole window lies inside the texture and
// on its own surface (its reach exceeds R), the rule is the plain box blur's,
// whose clamping never applies there: so the plain blur first, at its speed,
// then only the texels near another surface or the edge summed by the rule.
template <int C, int R>
void blur_within_region(const LightTexture& tex, const SurfaceIds& ids, Rect z, LightTexture& out) {
    box_blur_into(tex, R, z, out);
    const Rect t = tex.rect, s = ids.rect;
    // Where a window lies inside both the texture and the surfaces' rectangle.
    const Rect inner = intersect(Rect{t.x + R, t.y + R, t.w - 2 * R, t.h - 2 * R}, Rect{s.x + R, s.y + R, s.w - 2 * R, s.h - 2 * R});
    const int ya = std::clamp(inner.y, z.y, z.y + z.h), yb = std::clamp(inner.y + inner.h, ya, z.y + z.h);
    const int xa = std::clamp(inner.x, z.x, z.x + z.w), xb = std::clamp(inner.x + inner.w, xa, z.x + z.w);
    // One channel with the joins indexed: the inner columns in strips
    // sixteen wide, down the rows (blur_within_strip); the rest by the texel.
#if defined(__SSE2__)
    const bool strips = C == 1 && ids.joins.size() == ids.id.size();
#else
    const bool strips = false;
#endif
    const int strips_end = strips ? xa + (xb - xa) / 16 * 16 : xa;
    for (int y = z.y; y < z.y + z.h; ++y) {
        const bool row_inner = y >= ya && y < yb;
        auto edge = [&](int x) {
            // Off `inner`: plain only inside the texture with no surface's
            // rectangle in reach (the ground all round); else by the rule.
            const Rect window = intersect(Rect{x - R, y - R, 2 * R + 1, 2 * R + 1}, t);
            const bool texture_inside = window.w == 2 * R + 1 && window.h == 2 * R + 1;
            if (texture_inside && intersect(window, s).empty()) return;
            if (window_dark<C>(tex, window)) return;  // 0 by either rule
            blur_within_texel_any<C>(tex, R, ids, x, y, out);
        };
        if (!row_inner) {
            for (int x = z.x; x < z.x + z.w; ++x) edge(x);
            continue;
        }
        for (int x = z.x; x < xa; ++x) edge(x);
        // Only texels another surface lies within R of (reach <= R), and of
        // those only where the window's values differ, take the rule.
        const std::uint8_t* reach = &ids.reach[std::size_t(y - s.y) * s.w] - s.x;
        const std::uint8_t* values = &tex.texels[std::size_t(y - t.y) * t.w * C] - std::ptrdiff_t(t.x) * C;
        const std::ptrdiff_t row_bytes = std::ptrdiff_t(t.w) * C;
        auto redo = [&](int x) {
            if (!window_uniform<C, R>(values + std::ptrdiff_t(x) * C, row_bytes)) blur_within_texel<C, R>(tex, ids, x, y, out);
        };
        int x = strips_end;
#if defined(__SSE2__)
        // Sixteen reaches at a time: a row is mostly far from any outline.
        const __m128i limit = _mm_set1_epi8(char(R));
        for (; x + 16 <= xb; x += 16) {
            const __m128i r = _mm_loadu_si128(reinterpret_cast<const __m128i*>(reach + x));
            unsigned near = unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_min_epu8(r, limit), r)));
            if (near && windows_dark<C, R>(values + std::ptrdiff_t(x) * C, row_bytes)) continue;
            for (; near; near &= near - 1) redo(x + __builtin_ctz(near));
        }
#endif
        for (; x < xb; ++x)
            if (reach[x] <= R) redo(x);
        for (x = std::max(xb, xa); x < z.x + z.w; ++x) edge(x);
    }
#if defined(__SSE2__)
    // In bands of rows that stay in the cache from one strip to the next.
    constexpr int band = 32;
    if constexpr (C == 1)
        for (int y = ya; y < yb; y += band)
            for (int x = xa; x < strips_end; x += 16) blur_within_strip<R>(tex, ids, x, y, std::min(yb, y + band), out);
#endif
}

template <int C, int... R>
void blur_within_fused(int r, const LightTexture& tex, const SurfaceIds& ids, Rect z, LightTexture& out,
                       std::integer_sequence<int, R...>) {
    ((r == R ? blur_within_region<C, R>(tex, ids, z, out) : void()), ...);
}

// The same for any radius, O(radius) per texel: per row, prefix sums cut into
// runs of one surface give each texel's row sum and count in O(1); then per
// output row, the rows above and below are added while every texel's column
// stays on its surface (flags, r rows each way: O(r) per texel, branch-free).
template <int C>
void blur_within_separable(const LightTexture& tex, int radius, const std::int32_t* id, Rect z, LightTexture& out) {
    const Rect t = tex.rect;
    const int w = t.w;
    const int y0 = std::max(t.y, z.y - radius), y1 = std::min(t.y + t.h, z.y + z.h + radius);
    const int zx = z.x - t.x, zw = z.w;
    const int xa = std::max(0, zx - radius), xb = std::min(w, zx + zw + radius);
    std::vector<std::uint32_t> sums(std::size_t(y1 - y0) * zw * C), counts(std::size_t(y1 - y0) * zw);
    std::vector<std::uint32_t> prefix(std::size_t(xb - xa + 1) * C);
    std::vector<int> left(std::size_t(xb - xa)), right(std::size_t(xb - xa));
    for (int y = y0; y < y1; ++y) {
        const std::int32_t* ids = id + std::size_t(y - t.y) * w;
        const std::uint8_t* v = &tex.texels[std::size_t(y - t.y) * w * C];
        for (int k = 0; k < C; ++k) prefix[std::size_t(k)] = 0;
        for (int x = xa; x < xb; ++x)
            for (int k = 0; k < C; ++k)
                prefix[std::size_t(x - xa + 1) * C + k] = prefix[std::size_t(x - xa) * C + k] + v[std::size_t(x) * C + k];
        for (int x = xa; x < xb; ++x)
            left[std::size_t(x - xa)] = x > xa && ids[x - 1] == ids[x] ? left[std::size_t(x - xa - 1)] : x;
        for (int x = xb - 1; x >= xa; --x)
            right[std::size_t(x - xa)] = x + 1 < xb && ids[x + 1] == ids[x] ? right[std::size_t(x - xa + 1)] : x;
        std::uint32_t* s = &sums[std::size_t(y - y0) * zw * C];
        std::uint32_t* n = &counts[std::size_t(y - y0) * zw];
        for (int i = 0; i < zw; ++i) {
            const int x = zx + i;
            const int lo = std::max(left[std::size_t(x - xa)], x - radius), hi = std::min(right[std::size_t(x - xa)], x + radius);
            for (int k = 0; k < C; ++k)
                s[std::size_t(i) * C + k] = prefix[std::size_t(hi - xa + 1) * C + k] - prefix[std::size_t(lo - xa) * C + k];
            n[i] = std::uint32_t(hi - lo + 1);
        }
    }
    std::vector<std::uint32_t> sum(std::size_t(zw) * C), count(std::size_t(zw), 0u);
    std::vector<std::uint8_t> on(std::size_t(zw), std::uint8_t(1));
    for (int y = z.y; y < z.y + z.h; ++y) {
        const std::int32_t* own = id + std::size_t(y - t.y) * w + zx;
        std::copy_n(&sums[std::size_t(y - y0) * zw * C], std::size_t(zw) * C, sum.begin());
        std::copy_n(&counts[std::size_t(y - y0) * zw], std::size_t(zw), count.begin());
        for (int dir : {-1, 1}) {
            std::fill(on.begin(), on.end(), std::uint8_t(1));
            for (int k = 1; k <= radius; ++k) {
                const int yy = y + dir * k;
                if (yy < y0 || yy >= y1) break;
                const std::int32_t* ids = id + std::size_t(yy - t.y) * w + zx;
                const std::uint32_t* s = &sums[std::size_t(yy - y0) * zw * C];
                const std::uint32_t* n = &counts[std::size_t(yy - y0) * zw];
                for (int i = 0; i < zw; ++i) {
                    on[std::size_t(i)] &= std::uint8_t(ids[i] == own[i]);
                    const std::uint32_t m = 0u - std::uint32_t(on[std::size_t(i)]);
                    for (int c = 0; c < C; ++c) sum[std::size_t(i) * C + c] += s[std::size_t(i) * C + c] & m;
                    count[std::size_t(i)] += n[i] & m;
                }
            }
        }
        std::uint8_t* o = &out.texels[(std::size_t(y - t.y) * w + std::size_t(zx)) * C];
        for (int i = 0; i < zw; ++i)
            for (int c = 0; c < C; ++c)
                o[std::size_t(i) * C + c] = std::uint8_t((sum[std::size_t(i) * C + c] + count[std::size_t(i)] / 2) / count[std::size_t(i)]);
    }
}

}  // namespace

void index_surfaces(SurfaceIds& ids) {
    constexpr int cap = surface_reach_cap;
    static_assert(cap == max_fused_radius + 1, "reach is only ever compared with a fused radius");
    const Rect s = ids.rect;
    const int w = std::max(0, s.w), h = std::max(0, s.h);
    ids.reach.assign(std::size_t(w) * h, std::uint8_t(cap));
    if (w == 0 || h == 0) return;
    // The reach is one more than the Chebyshev distance to the nearest edge
    // pixel (one with a neighbour of another surface, the outside counting
    // as the ground): per row, the distance along the row to its nearest
    // edge; then per pixel, the least over the rows up to cap - 1 away of
    // max(rows away, that row's distance). Capped, so the second step reads
    // a fixed number of rows, each a straight byte loop.
    ids.joins.assign(std::size_t(w) * h, std::uint8_t(0));
    std::vector<std::uint8_t> along(std::size_t(w) * h);
    std::vector<std::int32_t> framed(3 * (std::size_t(w) + 2), -1);  // rows y - 1, y, y + 1, a ground pixel each side
    std::vector<std::uint8_t> edge(static_cast<std::size_t>(w));
    auto frame_row = [&](int y, std::size_t slot) {
        std::int32_t* row = &framed[slot * (std::size_t(w) + 2)];
        if (y < 0 || y >= h) std::fill_n(row, w + 2, -1);
        else std::copy_n(&ids.id[std::size_t(y) * w], w, row + 1);
    };
    frame_row(-1, 0), frame_row(0, 1);
    for (int y = 0; y < h; ++y) {
        frame_row(y + 1, std::size_t(y + 2) % 3);
        const std::int32_t* up = &framed[std::size_t(y) % 3 * (std::size_t(w) + 2) + 1];
        const std::int32_t* at = &framed[std::size_t(y + 1) % 3 * (std::size_t(w) + 2) + 1];
        const std::int32_t* down = &framed[std::size_t(y + 2) % 3 * (std::size_t(w) + 2) + 1];
        std::uint8_t* joins = &ids.joins[std::size_t(y) * w];
        for (int x = 0; x < w; ++x) {
            const std::int32_t c = at[x];
            // (The frame's sides are -1, so the last column and row join
            // nothing only where they are not the ground: never read there.)
            joins[x] = std::uint8_t((x + 1 < w && at[x + 1] == c ? SurfaceIds::join_right : 0) |
                                    (y + 1 < h && down[x] == c ? SurfaceIds::join_down : 0));
            edge[std::size_t(x)] = std::uint8_t((up[x - 1] != c) | (up[x] != c) | (up[x + 1] != c) | (at[x - 1] != c) |
                                                (at[x + 1] != c) | (down[x - 1] != c) | (down[x] != c) | (down[x + 1] != c));
        }
        std::uint8_t* d = &along[std::size_t(y) * w];
        std::uint8_t run = cap;
        for (int x = 0; x < w; ++x) run = edge[std::size_t(x)] ? 0 : std::uint8_t(std::min(run + 1, cap)), d[x] = run;
        run = cap;
        for (int x = w - 1; x >= 0; --x)
            run = edge[std::size_t(x)] ? 0 : std::uint8_t(std::min(run + 1, cap)), d[x] = std::min(d[x], run);
    }
    for (int y = 0; y < h; ++y) {
        std::uint8_t* out = &ids.reach[std::size_t(y) * w];
        for (int k = -(cap - 1); k <= cap - 1; ++k) {
            if (y + k < 0 || y + k >= h) continue;
            const std::uint8_t away = std::uint8_t(std::abs(k) + 1);
            const std::uint8_t* d = &along[std::size_t(y + k) * w];
            for (int x = 0; x < w; ++x) out[x] = std::min(out[x], std::max(away, std::uint8_t(d[x] + 1)));
        }
    }
}

void box_blur_within_into(const LightTexture& tex, int radius, const SurfaceIds& ids, Rect region, LightTexture& out) {
    assert(radius >= 0 && well_formed(tex));
    assert(ids.id.size() == std::size_t(std::max(0, ids.rect.w)) * std::max(0, ids.rect.h));
    if (!(out.rect == tex.rect) || out.channels != tex.channels || !well_formed(out)) out = LightTexture(tex.rect, tex.channels);
    const Rect z = intersect(region, tex.rect);
    if (z.empty()) return;
    // A radius past the texture reaches no further than its size.
    const int r = std::min(radius, std::max(tex.rect.w, tex.rect.h));
    if (r <= max_fused_radius) {
        const SurfaceIds* indexed = &ids;
        SurfaceIds own;
        if (ids.reach.size() != ids.id.size()) {  // not indexed yet
            own.rect = ids.rect;
            own.id = ids.id;
            index_surfaces(own);
            indexed = &own;
        }
        using radii = std::integer_sequence<int, 1, 2, 3, 4, 5, 6, 7>;
        static_assert(max_fused_radius == 7);
        if (r == 0) return box_blur_into(tex, 0, z, out);
        tex.channels == 1 ? blur_within_fused<1>(r, tex, *indexed, z, out, radii{})
                          : blur_within_fused<3>(r, tex, *indexed, z, out, radii{});
        return;
    }
    // Past the plain blur's fused radii a window off its surface costs r^2:
    // the separable sums instead, over surfaces on the texture's rectangle.
    std::vector<std::int32_t> on_texture;
    const std::int32_t* id = ids.id.data();
    if (!(ids.rect == tex.rect)) {
        on_texture.resize(std::size_t(tex.rect.w) * tex.rect.h);
        for (int y = 0; y < tex.rect.h; ++y)
            for (int x = 0; x < tex.rect.w; ++x)
                on_texture[std::size_t(y) * tex.rect.w + x] = ids.at(tex.rect.x + x, tex.rect.y + y);
        id = on_texture.data();
    }
    tex.channels == 1 ? blur_within_separable<1>(tex, r, id, z, out) : blur_within_separable<3>(tex, r, id, z, out);
}

LightTexture box_blur_within(const LightTexture& tex, int radius, const SurfaceIds& ids) {
    assert(radius >= 0 && well_formed(tex));
    LightTexture out(tex.rect, tex.channels);
    box_blur_within_into(tex, radius, ids, tex.rect, out);
    return out;
}

LightTexture box_blur_within_reference(const LightTexture& tex, int radius, const SurfaceIds& ids) {
    assert(radius >= 0 && well_formed(tex));
    const Rect t = tex.rect;
    LightTexture out(t, tex.channels);
    // Whether (x, y + dy) is reached along the column from (x, y) without
    // leaving the texture or the surface; the same along a row.
    auto column_reaches = [&](int x, int y, int dy) {
        const int step = dy < 0 ? -1 : 1;
        for (int i = step; i != dy + step; i += step)
            if (!t.contains(x, y + i) || ids.at(x, y + i) != ids.at(x, y)) return false;
        return true;
    };
    auto row_reaches = [&](int x, int y, int dx) {
        const int step = dx < 0 ? -1 : 1;
        for (int i = step; i != dx + step; i += step)
            if (!t.contains(x + i, y) || ids.at(x + i, y) != ids.at(x, y)) return false;
        return true;
    };
    for (int y = t.y; y < t.y + t.h; ++y)
        for (int x = t.x; x < t.x + t.w; ++x)
            for (int k = 0; k < tex.channels; ++k) {
                std::uint64_t sum = 0, n = 0;
                for (int dy = -radius; dy <= radius; ++dy) {
                    if (dy != 0 && !column_reaches(x, y, dy)) continue;
                    for (int dx = -radius; dx <= radius; ++dx) {
                        if (dx != 0 && !row_reaches(x, y + dy, dx)) continue;
                        sum += tex.at(x + dx, y + dy)[k];
                        ++n;
                    }
                }
                out.texels[(std::size_t(y - t.y) * t.w + std::size_t(x - t.x)) * tex.channels + k] = std::uint8_t((sum + n / 2) / n);
            }
    return out;
}

}  // namespace isolux
