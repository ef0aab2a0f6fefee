// Paper 3.2: "Once the light texture is in the GPU, a simple box-blur
// algorithm is applied to the same." CPU reference of shaders/blur.frag.
#include "isolux/blur.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>
#include <utility>
#include <vector>

#include "base/cpu_dispatch.hpp"
#include "frame/fused_radius.hpp"
#include "base/cpu.hpp"
#include "frame/oracles.hpp"
#if ISOLUX_X86_DISPATCH
#include <immintrin.h>
#endif

namespace isolux {

namespace {

// round(v / n) for the window sums v <= 255 n, n odd: floor(v / n + 1/2).
// The exact quotient's fraction is a multiple of 1/n, so after adding 1/2 it
// stays 1/(2n) away from an integer; float's error (< 4e-5 at 256) is below
// that while n < 16000 (radius <= 62), double's for every radius.
template <class Real, class Sum>
void divide_row(const Sum* sum, std::size_t count, std::uint32_t n, std::uint8_t* out) {
    const Real inv = Real(1) / Real(n), half = Real(n) * Real(0.5);
    for (std::size_t j = 0; j < count; ++j) out[j] = std::uint8_t(std::int32_t((Real(std::int32_t(sum[j])) + half) * inv));
}

// round(v / n) in 16-bit integers, for the fused pass's 16-bit sums (radius
// <= 7): the high half of (v + (n-1)/2) * M, shifted right by `shift` (a
// multiply-high per lane). M and the shift are chosen per n and checked
// against the division for every sum that can occur, once; a radius they
// failed for would take blur_region (none of 1 to 7 does).
struct Reciprocal {
    std::uint16_t m = 0;
    int shift = 0;
    bool exact = false;
};


const Reciprocal& reciprocal_for(int radius) {
    static const auto table = [] {
        std::array<Reciprocal, max_fused_radius + 1> t{};
        for (int r = 1; r <= max_fused_radius; ++r) {
            const std::uint32_t n = std::uint32_t(2 * r + 1) * std::uint32_t(2 * r + 1);
            Reciprocal& c = t[std::size_t(r)];
            for (c.shift = 0; (1u << (c.shift + 1)) < n; ++c.shift) {
            }
            const std::uint64_t m = ((std::uint64_t(1) << (16 + c.shift)) + n - 1) / n;
            if (m > 0xFFFF) continue;
            c.m = std::uint16_t(m);
            c.exact = true;
            for (std::uint32_t v = 0; v <= 255 * n && c.exact; ++v) {
                const std::uint32_t x = v + (n - 1) / 2;
                c.exact = ((x * c.m) >> 16 >> c.shift) == x / n;
            }
        }
        return t;
    }();
    return table[std::size_t(std::clamp(radius, 0, max_fused_radius))];
}

// One row's horizontal window sums over local columns [x0, x0 + w) of a
// texture `width` wide: each the sum of 2r+1 texels, clamped at the edges.
// C: the texture's channels (a texel's bytes), here and below.
template <int C>
struct RowSums {
    int r, width, x0, w;
    std::vector<std::uint32_t> pad, prefix;  // prefix[0, C) stay 0

    RowSums(int radius, int tex_width, int col0, int cols)
        : r(radius), width(tex_width), x0(col0), w(cols), pad(std::size_t(cols + 2 * radius) * C), prefix(pad.size() + C, 0) {}

    void operator()(const std::uint8_t* row, std::uint32_t* out) {
        // The row with its clamped border: pad[i] is texel x0 - r + i.
        const int n = w + 2 * r;
        const int inner0 = std::clamp(r - x0, 0, n), inner1 = std::clamp(width + r - x0, inner0, n);
        for (int i = 0; i < inner0; ++i)
            for (int c = 0; c < C; ++c) pad[std::size_t(i) * C + c] = row[c];
        const std::uint8_t* src = row + std::size_t(x0 - r + inner0) * C;
        for (std::size_t j = 0, m = std::size_t(inner1 - inner0) * C; j < m; ++j) pad[std::size_t(inner0) * C + j] = src[j];
        for (int i = inner1; i < n; ++i)
            for (int c = 0; c < C; ++c) pad[std::size_t(i) * C + c] = row[std::size_t(width - 1) * C + c];
        // Differences of running sums: prefix[k + C] = sum of pad[<= k] of
        // k's channel, kept in registers as it is stored, so no load waits on
        // the store of a value C places before it; exact modulo 2^32 since a
        // window's sum fits.
        std::array<std::uint32_t, C> sum{};
        for (std::size_t k = 0; k < pad.size(); k += C)
            for (int c = 0; c < C; ++c) prefix[k + C + std::size_t(c)] = sum[std::size_t(c)] += pad[k + std::size_t(c)];
        const std::size_t span = std::size_t(2 * r + 1) * C, m = std::size_t(w) * C;
        for (std::size_t j = 0; j < m; ++j) out[j] = prefix[j + span] - prefix[j];
    }
};

// Radius 8 and beyond (and any radius the fused pass cannot divide exactly):
// 32-bit window sums, rows visited top to bottom.
template <int C>
void blur_region(const LightTexture& tex, int radius, Rect z, LightTexture& out) {
    const int w = tex.rect.w, h = tex.rect.h;
    const int x0 = z.x - tex.rect.x, y0 = z.y - tex.rect.y;
    const std::size_t m = std::size_t(z.w) * C;
    // The 2r+1 rows of horizontal sums in the window live in a ring (slot of
    // window row i: i mod 2r+1) and their column sums are updated as the
    // window slides: new row in, old row out.
    const int span = 2 * radius + 1;
    const std::uint32_t n = std::uint32_t(span) * std::uint32_t(span);
    RowSums<C> row_sums(radius, w, x0, z.w);
    std::vector<std::uint32_t> ring(std::size_t(span) * m), column(m, 0), incoming(m);
    auto slot = [&](int i) { return &ring[std::size_t(((i % span) + span) % span) * m]; };
    auto texel_row = [&](int i) { return &tex.texels[std::size_t(std::clamp(i, 0, h - 1)) * w * C]; };
    for (int i = y0 - radius; i <= y0 + radius; ++i) {
        std::uint32_t* s = slot(i);
        row_sums(texel_row(i), s);
        for (std::size_t j = 0; j < m; ++j) column[j] += s[j];
    }
    for (int y = y0; y < y0 + z.h; ++y) {
        std::uint8_t* dst = &out.texels[(std::size_t(y) * w + x0) * C];
        if (n < 16000) divide_row<float>(column.data(), m, n, dst);
        else divide_row<double>(column.data(), m, n, dst);
        if (y + 1 == y0 + z.h) break;
        std::uint32_t* s = slot(y - radius);  // leaves the window; y + r + 1 takes its slot
        row_sums(texel_row(y + radius + 1), incoming.data());
        for (std::size_t j = 0; j < m; ++j) {
            column[j] = column[j] + incoming[j] - s[j];
            s[j] = incoming[j];
        }
    }
}

// The fused row's layout (blur_row_avx2): its first `lo_values` values come
// from `lo`'s bytes where the row starts at the texture's left edge (every
// value whose window may be clamped there: C R of them), its last
// `hi_values` from `hi`'s where it ends at the right edge.
template <int R, int C>
struct FusedEdges {
    static constexpr std::size_t CR = std::size_t(C) * R;
    static constexpr std::size_t lo_values = CR <= 16 ? 16 : 32;
    static constexpr std::size_t hi_values = 32 + CR;
    static constexpr std::size_t lo_bytes = lo_values + 2 * CR, hi_bytes = hi_values + 2 * CR;
    static constexpr std::size_t min_width = lo_values + 32;  // m, for one 32-value step
};

#if ISOLUX_X86_DISPATCH
// Sixteen bytes as 16-bit lanes; 32 bytes as they are.
ISOLUX_AVX2 inline __m256i widened(const std::uint8_t* at) {
    return _mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at)));
}
ISOLUX_AVX2 inline __m256i bytes_at(const std::uint8_t* at) {
    return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(at));
}

// The divide of blur_region_small's loop in 16-bit lanes: the column sums
// (which carry the half), times the reciprocal's multiplier, high half, shifted.
struct Quotients {
    __m256i muls;
    __m128i shifts;
};

// A step's column sums slid by its new row sums `v` (the leaving row's in
// slot `s`, replaced by v), and their quotients.
[[gnu::always_inline]] ISOLUX_AVX2 inline __m256i slid_column(std::uint16_t* col, std::uint16_t* s, __m256i v) {
    __m256i* c = reinterpret_cast<__m256i*>(col);
    __m256i* o = reinterpret_cast<__m256i*>(s);
    const __m256i sums = _mm256_sub_epi16(_mm256_add_epi16(_mm256_loadu_si256(c), v), _mm256_loadu_si256(o));
    _mm256_storeu_si256(c, sums), _mm256_storeu_si256(o, v);
    return sums;
}
[[gnu::always_inline]] ISOLUX_AVX2 inline __m256i quotients(__m256i sums, const Quotients& k) {
    return _mm256_srl_epi16(_mm256_mulhi_epu16(sums, k.muls), k.shifts);
}

// One 32-value step at src + j of blur_row_avx2 below (its comment
// says the layout); with Write, `dark` is the step's history byte, `before`
// what it held.
template <int R, int C, bool Write>
[[gnu::always_inline]] ISOLUX_AVX2 inline void blur_step_32(const std::uint8_t* p, std::uint16_t* col, std::uint16_t* s,
                                                            std::uint8_t* dst, std::uint8_t* dark, unsigned before,
                                                            const Quotients& k) {
    __m256i v0, v1;
    if constexpr (C == 1) {
        const __m256i ones = _mm256_set1_epi8(1), evens = _mm256_set1_epi16(1);
        v0 = _mm256_maddubs_epi16(bytes_at(p + R), evens);
        v1 = _mm256_maddubs_epi16(bytes_at(p + R + 1), evens);
        for (int t = 0; t < R; ++t) {
            v0 = _mm256_add_epi16(v0, _mm256_maddubs_epi16(bytes_at(p - R + 2 * t), ones));
            v1 = _mm256_add_epi16(v1, _mm256_maddubs_epi16(bytes_at(p - R + 1 + 2 * t), ones));
        }
    } else {
        v0 = widened(p - C * R), v1 = widened(p + 16 - C * R);
        for (int t = 1 - R; t <= R; ++t)
            v0 = _mm256_add_epi16(v0, widened(p + C * t)), v1 = _mm256_add_epi16(v1, widened(p + 16 + C * t));
    }
    const __m256i c0 = slid_column(col, s, v0), c1 = slid_column(col + 16, s + 16, v1);
    if constexpr (!Write) return;
    const __m256i any = _mm256_or_si256(v0, v1);
    const unsigned zero = unsigned(_mm256_testz_si256(any, any));
    *dark = std::uint8_t((before + 1) & (0u - zero));
    const __m256i q0 = quotients(c0, k), q1 = quotients(c1, k);
    const __m256i out = C == 1 ? _mm256_or_si256(q0, _mm256_slli_epi16(q1, 8))
                               : _mm256_permute4x64_epi64(_mm256_packus_epi16(q0, q1), 0xD8);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst), out);
}

// Sixteen values at src + j in the order of the bytes.
template <int R, int C, bool Write>
[[gnu::always_inline]] ISOLUX_AVX2 inline void blur_step_16(const std::uint8_t* p, std::uint16_t* col, std::uint16_t* s,
                                                            std::uint8_t* dst, const Quotients& k) {
    __m256i v = widened(p - C * R);
    for (int t = 1 - R; t <= R; ++t) v = _mm256_add_epi16(v, widened(p + C * t));
    const __m256i c0 = slid_column(col, s, v);
    if constexpr (Write) {
        const __m256i q = quotients(c0, k);
        const __m256i bytes = _mm256_permute4x64_epi64(_mm256_packus_epi16(q, q), 0xD8);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm256_castsi256_si128(bytes));
    }
}

// An output row, values [0, m) (m >= FusedEdges' min_width), as
// blur_region_small's loop computes them (the same integer steps), mostly 32
// values per step: written out by hand because GCC loads each 32-byte
// window twice to widen its two halves and masks the quotients before
// packing them (they are at most 255, the reciprocal having been checked for
// every sum).
//
// src[v] is the row's byte v for v in [-CR, b + CR): the window reads no
// clamped texel for values [0, b) but those of [0, L) when `lo` is given
// (L = lo_values: `lo` holds bytes [-CR, L + CR) as the window sees them,
// clamped) nor those of [b, m), whose bytes, [m - H - CR, m + CR) with H =
// hi_values, `hi` holds. The first L values go first, 16 at a time in the
// order of the bytes, then 32 at a time while the bytes are src's, then 16
// at a time, the last 16 ending at m even if they
// overlap values done already: those ring slots already hold their new sums,
// so their column sums and quotients come out unchanged. (A grey texture's
// 32-value steps stop early enough that the overlap stays in byte order.)
//
// A grey texture's sums come from byte pairs (vpmaddubsw against ones:
// each 16-bit lane the sum of two neighbours), the even and the odd texels
// of a step apart: x even takes the pairs from x - R, x - R + 2, ... and
// the byte at x + R; odd x the same one further. 2R + 2 loads for 32 sums,
// not 4R + 2 widened ones; the column sums and ring keep that order (the warm-up
// rows come here too, without writing), and the even and odd quotients
// interleave into bytes by a shift and an or.
//
// Dark steps cost a load and a store: `dark` counts, per step of the row,
// the rows in a row whose horizontal sums at the step were all zero (a byte:
// after 255 it starts again at 0, which only costs 2R+1 steps done in full).
// From 2R+1 on its ring slots hold zeros and its column sums their start,
// so while its new sums are zero too (the bytes they read all zero) the
// step stores zeros and touches nothing else. A light texture is
// dark wherever no light reaches, in runs as long as the gaps between
// lights: a run of dark steps (found 32 at a time in `dark`) tests all its
// bytes at once while it stores its zeros, and only if some are lit goes
// again step by step.
template <int R, int C, bool Write>
ISOLUX_AVX2 void blur_row_avx2(const std::uint8_t* src, const std::uint8_t* lo, const std::uint8_t* hi,
                               std::uint16_t* col, std::uint16_t* s, std::uint8_t* dst, std::uint8_t* dark,
                               std::size_t m, std::size_t b, std::uint16_t mul, int shift) {
    using E = FusedEdges<R, C>;
    constexpr std::size_t CR = E::CR, L = E::lo_values;
    static_assert(2 * CR <= 64, "a window's bytes past a step: at most two more loads");
    const Quotients k{_mm256_set1_epi16(std::int16_t(mul)), _mm_cvtsi32_si128(shift)};
    for (std::size_t v = 0; v < L; v += 16) blur_step_16<R, C, Write>((lo ? lo + CR : src) + v, col + v, s + v, dst + v, k);
    std::size_t j = L;
    std::size_t steps = b >= L + 32 ? (b - L) / 32 : 0;
    if (C == 1 && steps > 0 && m - L - 32 * steps < 16) --steps;
    auto lit = [&](std::size_t step) ISOLUX_AVX2 __attribute__((always_inline)) {
        blur_step_32<R, C, Write>(src + j, col + j, s + j, dst + j, dark + step, Write ? dark[step] : 0, k);
    };
    if constexpr (!Write) {
        for (std::size_t step = 0; step < steps; ++step, j += 32) lit(step);
    } else {
        const __m256i full = _mm256_set1_epi8(char(2 * R + 1));
        for (std::size_t step = 0; step < steps;) {
            const std::size_t left = steps - step;
            const __m256i d = bytes_at(dark + step);
            std::uint32_t runs = std::uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(_mm256_max_epu8(d, full), d)));
            if (left < 32) runs &= (1u << left) - 1;
            if (!(runs & 1)) {
                // Lit steps up to the next dark one.
                const std::size_t count = std::min<std::size_t>(left, runs ? std::size_t(__builtin_ctz(runs)) : 32);
                for (std::size_t e = step + count; step < e; ++step, j += 32) lit(step);
                continue;
            }
            // A run of dark steps: zeros out, and its bytes [p - CR, p + 32 count + CR) tested
            // (the loop's loads reach p + 32 count - CR, the last 2 CR bytes come from one or two more).
            const std::size_t count = std::min<std::size_t>(left, ~runs ? std::size_t(__builtin_ctz(~runs)) : 32);
            const std::uint8_t* p = src + j;
            __m256i in = bytes_at(p + 32 * (count - 1) + CR);
            if constexpr (2 * CR > 32) in = _mm256_or_si256(in, bytes_at(p + 32 * count - CR));
            for (std::size_t t = 0; t < count; ++t) {
                in = _mm256_or_si256(in, bytes_at(p + 32 * t - CR));
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + j + 32 * t), _mm256_setzero_si256());
            }
            if (_mm256_testz_si256(in, in)) {
                step += count, j += 32 * count;
                continue;
            }
            // Some lit: step by step, each dark while its own bytes, [j - CR, j + 32 + CR), are zero.
            for (std::size_t e = step + count; step < e; ++step, j += 32) {
                __m256i own = _mm256_or_si256(bytes_at(src + j - CR), bytes_at(src + j + CR));
                if constexpr (2 * CR > 32) own = _mm256_or_si256(own, bytes_at(src + j + 32 - CR));
                if (!_mm256_testz_si256(own, own)) lit(step);
            }
        }
    }
    // The rest 16 at a time, the bytes of values past b from `hi`.
    auto bytes_for = [&](std::size_t v) { return v + 16 <= b ? src + v : hi + CR + (v + E::hi_values - m); };
    for (; j + 16 <= m; j += 16) blur_step_16<R, C, Write>(bytes_for(j), col + j, s + j, dst + j, k);
    if (j < m) blur_step_16<R, C, Write>(bytes_for(m - 16), col + m - 16, s + m - 16, dst + m - 16, k);
}
#endif

// Radius 1 to 7, the common case: each row one fused pass (the new row's
// horizontal sums from its bytes, the column sums slid, the divide, the
// store), the few clamped edge texels one by one.
template <int R, int C, bool Avx2>
[[gnu::always_inline]] inline void blur_region_small(const LightTexture& tex, Rect z, LightTexture& out) {
    constexpr int span = 2 * R + 1;
    const int w = tex.rect.w, h = tex.rect.h;
    const int x0 = z.x - tex.rect.x, y0 = z.y - tex.rect.y;
    const std::size_t m = std::size_t(z.w) * C;
    const Reciprocal& k = reciprocal_for(R);
    const std::uint16_t half = std::uint16_t((span * span - 1) / 2), mul = k.m;
    const int shift = k.shift;
    // The column sums start at half the divisor, so that each carries the
    // rounding's half (the divide is then a multiply-high and a shift).
    std::vector<std::uint16_t> ring(std::size_t(span) * m), column(m, half);
    std::vector<std::uint8_t> dark(Avx2 ? m / 32 + 32 : 0, 0);  // blur_row_avx2's dark steps, read 32 at a time
    auto slot = [&](int i) { return &ring[std::size_t(((i % span) + span) % span) * m]; };
    auto texel_row = [&](int i) { return &tex.texels[std::size_t(std::clamp(i, 0, h - 1)) * w * C]; };
    // Columns [a, b) of the region read no clamped texel: x - R >= 0, x + R < w.
    const std::size_t a = std::size_t(std::clamp(R - x0, 0, z.w)) * C;
    const std::size_t b = std::max(a, std::size_t(std::clamp(w - R - x0, 0, z.w)) * C);
    // Bytes [v0, v0 + count) of the region's row as its windows see them:
    // byte v is channel v mod C of texel x0 + floor(v / C), clamped into the
    // row (blur_row_avx2's `lo` and `hi`).
    using E = FusedEdges<R, C>;
    std::array<std::uint8_t, E::lo_bytes> lo{};
    std::array<std::uint8_t, E::hi_bytes> hi{};
    auto window_bytes = [&](const std::uint8_t* row, std::ptrdiff_t v0, std::ptrdiff_t count, std::uint8_t* to) {
        const std::ptrdiff_t first = -std::ptrdiff_t(x0) * C, last = std::ptrdiff_t(w - x0) * C, end = v0 + count;
        auto channel = [](std::ptrdiff_t v) { return std::size_t((v % C + C) % C); };
        for (std::ptrdiff_t v = v0; v < std::min(first, end); ++v) to[v - v0] = row[channel(v)];
        const std::ptrdiff_t in0 = std::max(v0, first), in1 = std::min(end, last);
        if (in1 > in0) std::memcpy(to + (in0 - v0), row + (in0 - first), std::size_t(in1 - in0));
        for (std::ptrdiff_t v = std::max(v0, last); v < end; ++v) to[v - v0] = row[std::size_t(w - 1) * C + channel(v)];
    };
    // Texel row i comes in: its horizontal sums replace those in slot `s`
    // (the row leaving the window, or zeros) and the column sums move by the
    // difference; with Write, the column then gives output row `dst`.
    auto row_in = [&]<bool Write>(int i, std::uint16_t* __restrict s, std::uint8_t* __restrict dst) __attribute__((always_inline)) {
        const std::uint8_t* __restrict src = texel_row(i) + std::size_t(x0) * C;
        std::uint16_t* __restrict col = column.data();
        auto put = [&](std::size_t j, std::uint16_t v) {
            const std::uint16_t c = std::uint16_t(col[j] + v - s[j]);
            col[j] = c;
            s[j] = v;
            if constexpr (Write) dst[j] = std::uint8_t(std::uint16_t((std::uint32_t(c) * mul) >> 16) >> shift);
        };
        // The few edge values whose window is clamped, one by one.
        auto clamped = [&](std::size_t j) {
            const std::uint8_t* row = texel_row(i);
            const int x = x0 + int(j / C), c = int(j % C);
            std::uint16_t v = 0;
            for (int t = -R; t <= R; ++t) v = std::uint16_t(v + row[std::size_t(std::clamp(x + t, 0, w - 1)) * C + c]);
            return v;
        };
#if ISOLUX_X86_DISPATCH
        if constexpr (Avx2) {
            if (m >= E::min_width) {
                const std::uint8_t* row = texel_row(i);
                if (a > 0) window_bytes(row, -C * R, E::lo_bytes, lo.data());
                if (b < m) window_bytes(row, std::ptrdiff_t(m - E::hi_values) - C * R, E::hi_bytes, hi.data());
                blur_row_avx2<R, C, Write>(src, a > 0 ? lo.data() : nullptr, hi.data(), col, s, dst, dark.data(), m, b, mul, shift);
                return;
            }
        }
#endif
        // Left to right, as the row's bytes arrive (its right end read
        // first would wait for memory on every row).
        for (std::size_t j = 0; j < a; ++j) put(j, clamped(j));
        for (std::size_t j = a; j < b; ++j) {
            std::uint16_t v = 0;
            for (int t = -R; t <= R; ++t) v = std::uint16_t(v + src[std::ptrdiff_t(j) + C * t]);
            put(j, v);
        }
        for (std::size_t j = b; j < m; ++j) put(j, clamped(j));
    };
    // The window's first rows come in unwritten. Their `dst` is the first
    // output row all the same, never written: the row code offsets it as it
    // does a written one, and an offset from a null pointer is undefined.
    std::uint8_t* const first_row = &out.texels[(std::size_t(y0) * w + x0) * C];
    for (int i = y0 - R; i < y0 + R; ++i) row_in.template operator()<false>(i, slot(i), first_row);
    // Row y + R comes in (into the slot of row y - R - 1, which leaves), and row y is written.
    for (int y = y0; y < y0 + z.h; ++y)
        row_in.template operator()<true>(y + R, slot(y + R), &out.texels[(std::size_t(y) * w + x0) * C]);
}

// Radius 1 to 7 at two widths (base/cpu.hpp): the same code, vectorised
// twice, the AVX2 build's rows written by hand (blur_row_avx2).
template <bool Avx2, int C, int... R>
[[gnu::always_inline]] inline void blur_small_channels(int radius, const LightTexture& tex, Rect z, LightTexture& out,
                                                       std::integer_sequence<int, R...>) {
    ((radius == R + 1 ? blur_region_small<R + 1, C, Avx2>(tex, z, out) : void()), ...);
}
template <bool Avx2>
[[gnu::always_inline]] inline void blur_small_any(int radius, const LightTexture& tex, Rect z, LightTexture& out) {
    constexpr auto radii = std::make_integer_sequence<int, max_fused_radius>{};
    if (tex.channels == 1) blur_small_channels<Avx2, 1>(radius, tex, z, out, radii);
    else blur_small_channels<Avx2, 3>(radius, tex, z, out, radii);
}
void blur_small(int radius, const LightTexture& tex, Rect z, LightTexture& out) { blur_small_any<false>(radius, tex, z, out); }
ISOLUX_AVX2 void blur_small_avx2(int radius, const LightTexture& tex, Rect z, LightTexture& out) {
    blur_small_any<true>(radius, tex, z, out);
}

}  // namespace

void box_blur_into(const LightTexture& tex, int radius, Rect region, LightTexture& out) {
    assert(radius >= 0 && well_formed(tex));
    if (!(out.rect == tex.rect) || out.channels != tex.channels || !well_formed(out)) out = LightTexture(tex.rect, tex.channels);
    const Rect z = intersect(region, tex.rect);
    if (z.empty()) return;
    const int w = tex.rect.w;
    const int x0 = z.x - tex.rect.x, y0 = z.y - tex.rect.y;
    const std::size_t c = std::size_t(tex.channels);
    if (radius == 0) {
        for (int y = y0; y < y0 + z.h; ++y)
            std::memcpy(&out.texels[(std::size_t(y) * w + x0) * c], &tex.texels[(std::size_t(y) * w + x0) * c], std::size_t(z.w) * c);
        return;
    }
    if (radius <= max_fused_radius && reciprocal_for(radius).exact) {
        if (wide_kernels()) blur_small_avx2(radius, tex, z, out);
        else blur_small(radius, tex, z, out);
    } else
        c == 1 ? blur_region<1>(tex, radius, z, out) : blur_region<3>(tex, radius, z, out);
}

LightTexture box_blur(const LightTexture& tex, int radius) {
    assert(radius >= 0 && well_formed(tex));
    if (radius <= 0 || tex.rect.empty()) return tex;
    LightTexture out(tex.rect, tex.channels);
    box_blur_into(tex, radius, tex.rect, out);
    return out;
}

LightTexture box_blur_reference(const LightTexture& tex, int radius) {
    assert(radius >= 0 && well_formed(tex));
    if (radius <= 0 || tex.rect.empty()) return tex;
    const int w = tex.rect.w, h = tex.rect.h;
    const std::uint64_t n = std::uint64_t(2 * radius + 1) * (2 * radius + 1);
    const int channels = tex.channels;
    LightTexture out(tex.rect, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) {
                std::uint64_t sum = 0;
                for (int dy = -radius; dy <= radius; ++dy)
                    for (int dx = -radius; dx <= radius; ++dx)
                        sum += tex.texels[(std::size_t(std::clamp(y + dy, 0, h - 1)) * w + std::clamp(x + dx, 0, w - 1)) * channels + c];
                out.texels[(std::size_t(y) * w + x) * channels + c] = std::uint8_t((sum + n / 2) / n);
            }
    return out;
}

}  // namespace isolux
