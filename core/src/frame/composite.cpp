// Paper Algorithm 3: the fragment shader. CPU reference of shaders/composite.frag.
#include "isolux/composite.hpp"

#include <cassert>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>

#include "base/cpu_dispatch.hpp"
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__SSE2__) && ISOLUX_X86_DISPATCH
#include <immintrin.h>
#endif

#include "base/cpu.hpp"
#include "frame/oracles.hpp"

namespace isolux {

void tone_knee(const double base[3], const double add[3], double out[3]) {
    const double top = std::max({base[0], base[1], base[2]}), head = std::max(0.0, 1.0 - top);
    const double peak = std::max({base[0] + add[0], base[1] + add[1], base[2] + add[2]});
    const double knee = tone_knee_at * head, over = peak - top;
    double scale = 1;
    if (over > knee) {
        const double span = head - knee, x = span > 0 ? (over - knee) / span : 0;
        const double target = top + knee + span * x / (1 + x);
        for (int k = 0; k < 3; ++k)
            if (add[k] > 0) scale = std::min(scale, (target - base[k]) / add[k]);
    }
    for (int k = 0; k < 3; ++k) out[k] = std::clamp(base[k] + add[k] * scale, 0.0, 1.0);
}

void composite_pixel(const double c[3], const double L[3], const Params& p, double out[3]) {
    const double ac = p.ambient_clarity;
    const double luminance = c[0] * 0.349 + c[1] * 0.114 + c[2] * 0.537;
    const double denom = ac * ac + 0.1;
    const double tex_scale = std::sqrt(ac);
    const bool shadow = p.mode == Mode::shadow;
    const bool surface = p.light_mix == LightMix::surface;
    double tex[3], light[3];
    for (int k = 0; k < 3; ++k) {
        // surface (not in the paper): the sprite's own colour takes the light,
        // and a shadow darkens it by up to three quarters instead of subtracting.
        if (surface && shadow) {
            out[k] = std::clamp(c[k] * tex_scale * (1.0 - 0.75 * L[k] * p.exposure), 0.0, 1.0);
            continue;
        }
        // The exposure multiplies last, so exposure 1 is the paper's bytes.
        light[k] = (surface ? c[k] : luminance) * L[k] / denom * p.exposure;
        tex[k] = c[k] * tex_scale;
        // dark_unlit: "if the texFactor variable in Algorithm 3 is multiplied
        // by lightTexture, then what is not hit by the light ... would appear
        // completely dark". In shadow mode the texture holds shadow, so the
        // light is its complement.
        if (p.dark_unlit) tex[k] *= shadow ? (1.0 - L[k]) : L[k];
        out[k] = std::clamp(shadow ? tex[k] - light[k] : tex[k] + light[k], 0.0, 1.0);
    }
    if (!shadow && p.tone_map == ToneMap::reinhard_knee) tone_knee(tex, light, out);
}

namespace {

// One pixel exactly as composite_pixel rounds it (`l`: its texel, grey or
// r, g, b; none outside the texture).
void exact_pixel(const std::uint8_t* s, const std::uint8_t* l, bool grey, const Params& p, std::uint8_t* d) {
    double c[3] = {s[0] / 255.0, s[1] / 255.0, s[2] / 255.0}, L[3] = {0, 0, 0}, r[3];
    if (l) L[0] = l[0] / 255.0, L[1] = l[grey ? 0 : 1] / 255.0, L[2] = l[grey ? 0 : 2] / 255.0;
    composite_pixel(c, L, p, r);
    for (int k = 0; k < 3; ++k) d[k] = std::uint8_t(r[k] * 255.0 + 0.5);
}

// composite_pixel in float with the frame's constants hoisted, scaled to
// 0..255. Its error (about a dozen roundings of 6e-8 on terms of at most 1
// wherever the result is not clamped: under 2.5e-4 of a level) cannot change
// the rounding unless the value lies within 1/512 of a level's half (8 times
// that): those pixels, about 1 in 250, are redone exactly in double.
struct ShadeConstants {
    const Params* params;  // for the pixels redone exactly
    const std::uint8_t* light_end;  // the end of the light buffer the row reads (wide loads end 16 bytes before it)
    float tex_scale, inv_denom;  // inv_denom: the exposure over Algorithm 3's denominator
    float shadow_gain;           // light_mix surface in shadow mode: 0.75 times the exposure
    const float* unit;  // v / 255, v in 0..255
};

// shade_row's and shade_row_toned's shared steps over a run of up to
// shade_run pixels: the bytes spread into floats (table lookups, no
// conversions) with the paper's luminance, each channel's values (scaled
// and clamped to [0, 255]) moved to their rounding point with the pixels
// near a level's half flagged, and the bytes written back, the flagged
// pixels redone exactly in double.
constexpr int shade_run = 256;
using RunChannels = float[3][shade_run];

template <bool Grey>
void spread_run(const std::uint8_t* sp, const std::uint8_t* lp, int m, const float* unit, RunChannels& c, RunChannels& L,
                float* lum, std::int32_t* bad) {
    constexpr int texel = Grey ? 1 : 3;
    for (int i = 0; i < m; ++i)
        for (int ch = 0; ch < 3; ++ch) c[ch][i] = unit[sp[4 * i + ch]], L[ch][i] = unit[lp[texel * i + (Grey ? 0 : ch)]];
    for (int i = 0; i < m; ++i) lum[i] = c[0][i] * 0.349f + c[1][i] * 0.114f + c[2][i] * 0.537f, bad[i] = 0;
}

void flag_near_halves(float* tt, int m, std::int32_t* bad) {
    constexpr float near = 1.0f / 512.0f, round_magic = 8388608.0f;  // 2^23: adding it rounds to an integer
    for (int i = 0; i < m; ++i) {
        const float x = tt[i] + 0.5f;
        const float off = x - ((x + round_magic) - round_magic);  // distance to the nearest integer
        bad[i] |= std::int32_t(off < near) & std::int32_t(off > -near);
        tt[i] = x;
    }
}

template <bool Grey>
void write_run(const std::uint8_t* sp, const std::uint8_t* lp, int m, const RunChannels& t, const std::int32_t* bad,
               const Params& p, std::uint8_t* dp) {
    constexpr int texel = Grey ? 1 : 3;
    for (int i = 0; i < m; ++i) {
        const std::uint8_t alpha = sp[4 * i + 3];
        const std::uint8_t keep = alpha != 0 ? 0xFF : 0x00;  // transparent: all zero
        for (int ch = 0; ch < 3; ++ch) dp[4 * i + ch] = std::uint8_t(std::uint8_t(std::int32_t(t[ch][i])) & keep);
        dp[4 * i + 3] = alpha;
        if (bad[i] & keep & 1) exact_pixel(sp + 4 * i, lp + texel * i, Grey, p, dp + 4 * i);
    }
}

// Three passes over runs of up to 256 pixels, so the arithmetic is one
// loop over plain float arrays (vectorised): spread the bytes into floats
// (table lookups, no conversions), shade, gather the bytes back. Grey: the
// light's texels are one byte, the same in every channel.
template <bool Shadow, bool Surface, bool DarkUnlit, bool Grey>
void shade_row(const std::uint8_t* s, const std::uint8_t* l, int n, const ShadeConstants& k, std::uint8_t* d) {
    constexpr int run = shade_run, texel = Grey ? 1 : 3;
    alignas(16) RunChannels c, L, t;
    alignas(16) std::int32_t bad[run];
    alignas(16) float lum[run];
    const float ts = k.tex_scale, inv_denom = k.inv_denom;
    for (int i0 = 0; i0 < n; i0 += run) {
        const int m = std::min(run, n - i0);
        const std::uint8_t* sp = s + std::size_t(i0) * 4;
        const std::uint8_t* lp = l + std::size_t(i0) * texel;
        spread_run<Grey>(sp, lp, m, k.unit, c, L, lum, bad);
        for (int ch = 0; ch < 3; ++ch) {
            const float* cc = c[ch];
            const float* LL = L[ch];
            float* tt = t[ch];
            for (int i = 0; i < m; ++i) {
                float v;
                if constexpr (Surface && Shadow) {
                    v = cc[i] * ts * (1.0f - k.shadow_gain * LL[i]);
                } else {
                    const float light_factor = (Surface ? cc[i] : lum[i]) * LL[i] * inv_denom;
                    float tex_factor = cc[i] * ts;
                    if constexpr (DarkUnlit) tex_factor *= Shadow ? (1.0f - LL[i]) : LL[i];
                    v = Shadow ? tex_factor - light_factor : tex_factor + light_factor;
                }
                // Scaled, then clamped to [0, 255] (GCC 12 vectorises this form, not others).
                float x = v * 255.0f;
                x = x < 0.0f ? 0.0f : x;
                x = x > 255.0f ? 255.0f : x;
                tt[i] = x;
            }
            flag_near_halves(tt, m, bad);
        }
        write_run<Grey>(sp, lp, m, t, bad, *k.params, d + std::size_t(i0) * 4);
    }
}

// shade_row with tone_map reinhard_knee where light adds (light and flat
// modes; shadow mode's bytes are none's): the texture and light terms kept
// apart, then tone_knee in float. Rows' last n % 4 pixels after
// shade_row_sse2's toned lanes, and whole rows where there is no SSE2.
// No floating-point trap is ever enabled here, so GCC may if-convert the
// selects between two variables (it keeps them as branches otherwise):
// the values are IEEE's either way. (Clang has no such attribute.)
#if defined(__GNUC__) && !defined(__clang__)
#define ISOLUX_NO_TRAPPING_MATH [[gnu::optimize("no-trapping-math")]]
#else
#define ISOLUX_NO_TRAPPING_MATH
#endif
template <bool Surface, bool DarkUnlit, bool Grey>
ISOLUX_NO_TRAPPING_MATH
void shade_row_toned(const std::uint8_t* s, const std::uint8_t* l, int n, const ShadeConstants& k, std::uint8_t* d) {
    constexpr int run = shade_run, texel = Grey ? 1 : 3;
    constexpr float knee_at = float(tone_knee_at);
    alignas(16) RunChannels c, L, base, add;
    alignas(16) float lum[run], scale[run];
    alignas(16) std::int32_t bad[run];
    const float ts = k.tex_scale, inv_denom = k.inv_denom;
    for (int i0 = 0; i0 < n; i0 += run) {
        const int cnt = std::min(run, n - i0);
        const std::uint8_t* sp = s + std::size_t(i0) * 4;
        const std::uint8_t* lp = l + std::size_t(i0) * texel;
        spread_run<Grey>(sp, lp, cnt, k.unit, c, L, lum, bad);
        for (int ch = 0; ch < 3; ++ch)
            for (int i = 0; i < cnt; ++i) {
                add[ch][i] = (Surface ? c[ch][i] : lum[i]) * L[ch][i] * inv_denom;
                base[ch][i] = DarkUnlit ? c[ch][i] * ts * L[ch][i] : c[ch][i] * ts;
            }
        // The light rolled into the headroom the texture leaves (tone_knee),
        // in flat loops of plain selects (GCC 12 vectorises those, not
        // nested ones), the divisions unconditional with safe divisors.
        for (int i = 0; i < cnt; ++i) {
            const float b0 = base[0][i], b1 = base[1][i], b2 = base[2][i];
            const float p0 = b0 + add[0][i], p1 = b1 + add[1][i], p2 = b2 + add[2][i];
            float top = b0;
            top = top < b1 ? b1 : top;
            top = top < b2 ? b2 : top;
            float peak = p0;
            peak = peak < p1 ? p1 : peak;
            peak = peak < p2 ? p2 : peak;
            float head = 1.0f - top;
            head = head < 0.0f ? 0.0f : head;
            const float knee = knee_at * head, span = head - knee, over = peak - top;
            float safe_span = span;
            safe_span = safe_span > 0.0f ? safe_span : 1.0f;
            float x = (over - knee) / safe_span;
            x = x > 0.0f ? x : 0.0f;  // below the knee `target` is unused
            const float target = top + knee + span * x / (1.0f + x);
            // The light's scale: the least over the channels it lights (a
            // channel it leaves alone bounds nothing), 1 below the knee.
            float sc = 1.0f;
            for (int ch = 0; ch < 3; ++ch) {
                const float a = add[ch][i];
                float safe_a = a;
                safe_a = safe_a > 0.0f ? safe_a : 1.0f;
                float r = (target - base[ch][i]) / safe_a;
                r = a > 0.0f ? r : 1.0f;
                sc = r < sc ? r : sc;
            }
            scale[i] = over > knee ? sc : 1.0f;
        }
        for (int ch = 0; ch < 3; ++ch) {
            float* tt = base[ch];
            for (int i = 0; i < cnt; ++i) {
                float x = (tt[i] + add[ch][i] * scale[i]) * 255.0f;
                x = x < 0.0f ? 0.0f : x;
                x = x > 255.0f ? 255.0f : x;
                tt[i] = x;
            }
            flag_near_halves(tt, cnt, bad);
        }
        write_run<Grey>(sp, lp, cnt, base, bad, *k.params, d + std::size_t(i0) * 4);
    }
}

#if defined(__SSE2__)
// The same arithmetic four pixels at a time in SSE2 (every x86-64 has it):
// the bytes spread into lanes by shifts and masks, shaded, packed back. The
// last n % 4 pixels take shade_row.
// Toned: tone_map reinhard_knee where light adds (never with Shadow), in
// the same lanes: the texture and light terms kept apart, then tone_knee.
template <bool Shadow, bool Surface, bool DarkUnlit, bool Grey, bool Toned = false>
void shade_row_sse2(const std::uint8_t* s, const std::uint8_t* l, int n, const ShadeConstants& k, std::uint8_t* d) {
    static_assert(!(Toned && Shadow), "shadow mode's bytes are the clamp's");
    const __m128i bytes = _mm_set1_epi32(0xFF), rgb_bytes = _mm_set1_epi32(0xFFFFFF), zero = _mm_setzero_si128();
    const std::uint8_t* l_end = k.light_end ? k.light_end : l;
    const __m128 inv255 = _mm_set1_ps(1.0f / 255.0f), scale = _mm_set1_ps(255.0f), top = _mm_set1_ps(255.0f),
                 half = _mm_set1_ps(0.5f), magic = _mm_set1_ps(8388608.0f), near = _mm_set1_ps(1.0f / 512.0f),
                 minus_near = _mm_set1_ps(-1.0f / 512.0f), one = _mm_set1_ps(1.0f), three_quarters = _mm_set1_ps(k.shadow_gain),
                 ts = _mm_set1_ps(k.tex_scale), inv_denom = _mm_set1_ps(k.inv_denom), kr = _mm_set1_ps(0.349f),
                 kg = _mm_set1_ps(0.114f), kb = _mm_set1_ps(0.537f), fzero = _mm_setzero_ps(),
                 knee_at = _mm_set1_ps(float(tone_knee_at));
    constexpr int texel = Grey ? 1 : 3;
    int i = 0;
    for (; i + 4 <= n; i += 4) {
        const __m128i sp = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + std::size_t(i) * 4));
        const std::uint8_t* lp = l + std::size_t(i) * texel;
        // Four RGB texels into four lanes: one 16-byte load where the
        // buffer has 4 bytes to spare past them, byte shifts and unpacks.
        // Four grey ones: one 4-byte load, widened.
        __m128i lv;
        if constexpr (Grey) {
            std::int32_t four;
            std::memcpy(&four, lp, 4);
            lv = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(four), zero), zero);
        } else if (lp + 16 <= l_end) {
            const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lp));
            const __m128i t01 = _mm_unpacklo_epi32(v, _mm_srli_si128(v, 3));
            const __m128i t23 = _mm_unpacklo_epi32(_mm_srli_si128(v, 6), _mm_srli_si128(v, 9));
            lv = _mm_and_si128(_mm_unpacklo_epi64(t01, t23), rgb_bytes);
        } else {
            auto texel = [&](int q) {
                return int(std::uint32_t(lp[3 * q]) | std::uint32_t(lp[3 * q + 1]) << 8 | std::uint32_t(lp[3 * q + 2]) << 16);
            };
            lv = _mm_set_epi32(texel(3), texel(2), texel(1), texel(0));
        }
        __m128 c[3], L[3];
        for (int ch = 0; ch < 3; ++ch) {
            c[ch] = _mm_mul_ps(_mm_cvtepi32_ps(_mm_and_si128(_mm_srli_epi32(sp, 8 * ch), bytes)), inv255);
            L[ch] = Grey && ch > 0 ? L[0] : _mm_mul_ps(_mm_cvtepi32_ps(_mm_and_si128(_mm_srli_epi32(lv, 8 * ch), bytes)), inv255);
        }
        const __m128i alpha = _mm_srli_epi32(sp, 24);
        const __m128 luminance = _mm_add_ps(_mm_add_ps(_mm_mul_ps(c[0], kr), _mm_mul_ps(c[1], kg)), _mm_mul_ps(c[2], kb));
        __m128 bad = fzero;
        __m128i packed = _mm_slli_epi32(alpha, 24);
        __m128 toned[3];
        if constexpr (Toned) {
            // tone_knee four pixels at a time; select(m, a, b): a where m, else b.
            auto select = [](__m128 m, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b)); };
            __m128 base[3], add[3];
            for (int ch = 0; ch < 3; ++ch) {
                add[ch] = _mm_mul_ps(_mm_mul_ps(Surface ? c[ch] : luminance, L[ch]), inv_denom);
                base[ch] = _mm_mul_ps(c[ch], ts);
                if constexpr (DarkUnlit) base[ch] = _mm_mul_ps(base[ch], L[ch]);
            }
            const __m128 highest = _mm_max_ps(_mm_max_ps(base[0], base[1]), base[2]);
            const __m128 peak = _mm_max_ps(_mm_max_ps(_mm_add_ps(base[0], add[0]), _mm_add_ps(base[1], add[1])),
                                           _mm_add_ps(base[2], add[2]));
            const __m128 head = _mm_max_ps(_mm_sub_ps(one, highest), fzero), knee = _mm_mul_ps(knee_at, head);
            const __m128 span = _mm_sub_ps(head, knee), over = _mm_sub_ps(peak, highest);
            const __m128 rolled = _mm_cmpgt_ps(over, knee);
            __m128 sc = one;
            if (_mm_movemask_ps(rolled)) {  // else all four are below the knee: the light as it is
                const __m128 safe_span = select(_mm_cmpgt_ps(span, fzero), span, one);
                const __m128 x = _mm_max_ps(_mm_div_ps(_mm_sub_ps(over, knee), safe_span), fzero);
                const __m128 target =
                    _mm_add_ps(_mm_add_ps(highest, knee), _mm_div_ps(_mm_mul_ps(span, x), _mm_add_ps(one, x)));
                for (int ch = 0; ch < 3; ++ch) {
                    const __m128 lit = _mm_cmpgt_ps(add[ch], fzero);
                    const __m128 r = _mm_div_ps(_mm_sub_ps(target, base[ch]), select(lit, add[ch], one));
                    sc = _mm_min_ps(sc, select(lit, r, one));
                }
                sc = select(rolled, sc, one);
            }
            for (int ch = 0; ch < 3; ++ch) toned[ch] = _mm_add_ps(base[ch], _mm_mul_ps(add[ch], sc));
        }
        for (int ch = 0; ch < 3; ++ch) {
            __m128 v;
            if constexpr (Toned) {
                v = toned[ch];
            } else if constexpr (Surface && Shadow) {
                v = _mm_mul_ps(_mm_mul_ps(c[ch], ts), _mm_sub_ps(one, _mm_mul_ps(three_quarters, L[ch])));
            } else {
                const __m128 light_factor = _mm_mul_ps(_mm_mul_ps(Surface ? c[ch] : luminance, L[ch]), inv_denom);
                __m128 tex_factor = _mm_mul_ps(c[ch], ts);
                if constexpr (DarkUnlit) tex_factor = _mm_mul_ps(tex_factor, Shadow ? _mm_sub_ps(one, L[ch]) : L[ch]);
                v = Shadow ? _mm_sub_ps(tex_factor, light_factor) : _mm_add_ps(tex_factor, light_factor);
            }
            const __m128 x = _mm_add_ps(_mm_min_ps(_mm_max_ps(_mm_mul_ps(v, scale), fzero), top), half);
            const __m128 off = _mm_sub_ps(x, _mm_sub_ps(_mm_add_ps(x, magic), magic));
            bad = _mm_or_ps(bad, _mm_and_ps(_mm_cmplt_ps(off, near), _mm_cmpgt_ps(off, minus_near)));
            packed = _mm_or_si128(packed, _mm_slli_epi32(_mm_cvttps_epi32(x), 8 * ch));
        }
        // Transparent pixels: all zero, and never redone.
        const __m128i transparent = _mm_cmpeq_epi32(alpha, zero);
        packed = _mm_andnot_si128(transparent, packed);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(d + std::size_t(i) * 4), packed);
        const int redo = _mm_movemask_ps(_mm_andnot_ps(_mm_castsi128_ps(transparent), bad));
        if (redo)
            for (int q = 0; q < 4; ++q)
                if ((redo >> q) & 1) exact_pixel(s + std::size_t(i + q) * 4, lp + texel * q, Grey, *k.params, d + std::size_t(i + q) * 4);
    }
    if (i >= n) return;
    if constexpr (Toned)
        shade_row_toned<Surface, DarkUnlit, Grey>(s + std::size_t(i) * 4, l + std::size_t(i) * texel, n - i, k,
                                                  d + std::size_t(i) * 4);
    else
        shade_row<Shadow, Surface, DarkUnlit, Grey>(s + std::size_t(i) * 4, l + std::size_t(i) * texel, n - i, k,
                                                    d + std::size_t(i) * 4);
}
#endif

#if defined(__SSE2__) && ISOLUX_X86_DISPATCH
// shade_row_sse2 eight pixels at a time (AVX2, base/cpu.hpp), in 0..255
// units with its constants folded. Wherever the result is not clamped each
// term is at most 255 (the light term too: it is below the result in light
// mode and below the texture term in shadow mode), and about eight float
// roundings of 6e-8 relative (constants included) bound the error by 2e-4
// of a level: a value within 1/2048 of a level's half (2.4 times that) is
// redone exactly, a quarter as many pixels as shade_row_sse2's 1/512. The
// light's eight texels come from two of shade_row_sse2's four-texel loads.
template <bool Shadow, bool Surface, bool DarkUnlit, bool Grey>
ISOLUX_AVX2_FMA void shade_row_avx2(const std::uint8_t* s, const std::uint8_t* l, int n, const ShadeConstants& k,
                                std::uint8_t* d) {
    const __m256i zero = _mm256_setzero_si256();
    const __m256i by_pixel = _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15,  //
                                              0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
    const __m128i rgb_bytes = _mm_set1_epi32(0xFFFFFF);
    const __m256i up_a_lane = _mm256_setr_epi32(0, 1, 2, 3, 3, 4, 5, 6);
    const __m256i spread_rgb = _mm256_setr_epi8(0, 1, 2, -128, 3, 4, 5, -128, 6, 7, 8, -128, 9, 10, 11, -128,  //
                                                0, 1, 2, -128, 3, 4, 5, -128, 6, 7, 8, -128, 9, 10, 11, -128);
    // Byte ch of each pixel alone in its 32-bit lane (-128: a zero byte).
    const __m256i channel[3] = {
        _mm256_setr_epi8(0, -128, -128, -128, 4, -128, -128, -128, 8, -128, -128, -128, 12, -128, -128, -128, 0, -128, -128, -128, 4, -128, -128, -128, 8, -128, -128, -128, 12, -128, -128, -128),
        _mm256_setr_epi8(1, -128, -128, -128, 5, -128, -128, -128, 9, -128, -128, -128, 13, -128, -128, -128, 1, -128, -128, -128, 5, -128, -128, -128, 9, -128, -128, -128, 13, -128, -128, -128),
        _mm256_setr_epi8(2, -128, -128, -128, 6, -128, -128, -128, 10, -128, -128, -128, 14, -128, -128, -128, 2, -128, -128, -128, 6, -128, -128, -128, 10, -128, -128, -128, 14, -128, -128, -128)};
    const std::uint8_t* l_end = k.light_end ? k.light_end : l;
    const __m256 inv255 = _mm256_set1_ps(1.0f / 255.0f),
                 half_less_near = _mm256_set1_ps(0.5f - 1.0f / 2048.0f),
                 no_sign = _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF)), one = _mm256_set1_ps(1.0f),
                 three_quarters = _mm256_set1_ps(k.shadow_gain), ts = _mm256_set1_ps(k.tex_scale),
                 light_scale = _mm256_set1_ps(k.inv_denom / 255.0f), fzero = _mm256_setzero_ps();
    // The luminance weights with the light's scale in them (one rounding each, in double).
    const double scale = double(k.inv_denom) / 255.0;
    const __m256 kr = _mm256_set1_ps(float(0.349 * scale)), kg = _mm256_set1_ps(float(0.114 * scale)),
                 kb = _mm256_set1_ps(float(0.537 * scale));
    auto four_texels = [&](const std::uint8_t* lp) {
        if (lp + 16 <= l_end) {
            const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lp));
            const __m128i t01 = _mm_unpacklo_epi32(v, _mm_srli_si128(v, 3));
            const __m128i t23 = _mm_unpacklo_epi32(_mm_srli_si128(v, 6), _mm_srli_si128(v, 9));
            return _mm_and_si128(_mm_unpacklo_epi64(t01, t23), rgb_bytes);
        }
        auto texel = [&](int q) {
            return int(std::uint32_t(lp[3 * q]) | std::uint32_t(lp[3 * q + 1]) << 8 | std::uint32_t(lp[3 * q + 2]) << 16);
        };
        return _mm_set_epi32(texel(3), texel(2), texel(1), texel(0));
    };
    constexpr int texel = Grey ? 1 : 3;
    if (n < 8) return shade_row_sse2<Shadow, Surface, DarkUnlit, Grey>(s, l, n, k, d);
    // The last step ends at the row's end, over pixels the step before may
    // have written: each pixel's bytes depend on its texel and light alone.
    for (int i0 = 0; i0 < n; i0 += 8) {
        const int i = std::min(i0, n - 8);
        const __m256i sp = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + std::size_t(i) * 4));
        const std::uint8_t* lp = l + std::size_t(i) * texel;
        // Eight RGB texels into eight lanes: one 32-byte load, the second
        // half's bytes moved up a lane (dwords 3-6) and spread by a shuffle.
        // Eight grey ones: one 8-byte load, widened.
        const __m256i lv = Grey ? _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(lp)))
                           : lp + 32 <= l_end
                               ? _mm256_shuffle_epi8(_mm256_permutevar8x32_epi32(
                                                         _mm256_loadu_si256(reinterpret_cast<const __m256i*>(lp)), up_a_lane),
                                                     spread_rgb)
                               : _mm256_inserti128_si256(_mm256_castsi128_si256(four_texels(lp)), four_texels(lp + 12), 1);
        // In 0..255 units: composite_pixel's terms times 255, its constants
        // folded (fewer roundings than shade_row_sse2, the same bound).
        __m256 c[3], L[3];
        for (int ch = 0; ch < 3; ++ch) {  // byte ch of each pixel into its lane: one shuffle
            c[ch] = _mm256_cvtepi32_ps(_mm256_shuffle_epi8(sp, channel[ch]));
            L[ch] = Grey ? (ch == 0 ? _mm256_cvtepi32_ps(lv) : L[0]) : _mm256_cvtepi32_ps(_mm256_shuffle_epi8(lv, channel[ch]));
        }
        const __m256i alpha = _mm256_srli_epi32(sp, 24);
        // The luminance with the light's scale in it (luminance mix): one multiply per channel below.
        const __m256 luminance = _mm256_fmadd_ps(c[2], kb, _mm256_fmadd_ps(c[1], kg, _mm256_mul_ps(c[0], kr)));
        __m256 bad = fzero;
        __m256i level[3];
        for (int ch = 0; ch < 3; ++ch) {
            __m256 v;
            if constexpr (Surface && Shadow) {
                v = _mm256_mul_ps(_mm256_mul_ps(c[ch], ts),
                                  _mm256_sub_ps(one, _mm256_mul_ps(three_quarters, _mm256_mul_ps(L[ch], inv255))));
            } else {
                const __m256 light_factor =
                    Surface ? _mm256_mul_ps(_mm256_mul_ps(c[ch], L[ch]), light_scale) : _mm256_mul_ps(luminance, L[ch]);
                if constexpr (DarkUnlit) {
                    const __m256 lu = _mm256_mul_ps(L[ch], inv255);
                    const __m256 tex_factor = _mm256_mul_ps(_mm256_mul_ps(c[ch], ts), Shadow ? _mm256_sub_ps(one, lu) : lu);
                    v = Shadow ? _mm256_sub_ps(tex_factor, light_factor) : _mm256_add_ps(tex_factor, light_factor);
                } else {
                    v = Shadow ? _mm256_fmsub_ps(c[ch], ts, light_factor) : _mm256_fmadd_ps(c[ch], ts, light_factor);
                }
            }
            // Rounded to the nearest level: floor(x + 1/2) unless x lies
            // within 1/2048 of a level's half, where the pixel is redone
            // (ties included, so the rounding's tie rule never shows). Not
            // clamped here: the packs below saturate to 0..255, and a value
            // beyond those bounds by more than the error bound saturates the
            // same whichever way it rounds (one nearer is checked as any).
            const __m256 rounded = _mm256_round_ps(v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
            const __m256 off = _mm256_and_ps(_mm256_sub_ps(v, rounded), no_sign);
            bad = _mm256_or_ps(bad, _mm256_cmp_ps(off, half_less_near, _CMP_GT_OQ));
            level[ch] = _mm256_cvttps_epi32(rounded);
        }
        // r, g, b, alpha as 32-bit lanes to bytes, saturating: per 16-byte
        // lane r0-3 g0-3 b0-3 a0-3, then each pixel's four bytes together.
        const __m256i bytes = _mm256_packus_epi16(_mm256_packus_epi32(level[0], level[1]), _mm256_packus_epi32(level[2], alpha));
        const __m256i transparent = _mm256_cmpeq_epi32(alpha, zero);
        const __m256i packed = _mm256_andnot_si256(transparent, _mm256_shuffle_epi8(bytes, by_pixel));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + std::size_t(i) * 4), packed);
        const int redo = _mm256_movemask_ps(_mm256_andnot_ps(_mm256_castsi256_ps(transparent), bad));
        if (redo)
            for (int q = 0; q < 8; ++q)
                if ((redo >> q) & 1) exact_pixel(s + std::size_t(i + q) * 4, lp + texel * q, Grey, *k.params, d + std::size_t(i + q) * 4);
    }
}
#define ISOLUX_HAS_SHADE_AVX2 1
#endif

using ShadeRow = void (*)(const std::uint8_t*, const std::uint8_t*, int, const ShadeConstants&, std::uint8_t*);

// Every variant's function, indexed by shadow, surface, dark_unlit, grey (bits 3 to 0).
template <template <bool, bool, bool, bool> class Variant, std::size_t... I>
constexpr std::array<ShadeRow, sizeof...(I)> variants(std::index_sequence<I...>) {
    return {Variant<bool(I & 8), bool(I & 4), bool(I & 2), bool(I & 1)>::shade...};
}
#if defined(__SSE2__)
template <bool A, bool B, bool C, bool D> struct Sse2 { static constexpr ShadeRow shade = shade_row_sse2<A, B, C, D>; };
#else
template <bool A, bool B, bool C, bool D> struct Sse2 { static constexpr ShadeRow shade = shade_row<A, B, C, D>; };
#endif
#if defined(ISOLUX_HAS_SHADE_AVX2)
template <bool A, bool B, bool C, bool D> struct Avx2 { static constexpr ShadeRow shade = shade_row_avx2<A, B, C, D>; };
#endif

ShadeRow shade_row_for(const Params& p, bool grey) {
    if (p.tone_map == ToneMap::reinhard_knee && p.mode != Mode::shadow) {
#if defined(__SSE2__)
        static constexpr std::array<ShadeRow, 8> toned = {
            shade_row_sse2<false, false, false, false, true>, shade_row_sse2<false, false, false, true, true>,
            shade_row_sse2<false, false, true, false, true>,  shade_row_sse2<false, false, true, true, true>,
            shade_row_sse2<false, true, false, false, true>,  shade_row_sse2<false, true, false, true, true>,
            shade_row_sse2<false, true, true, false, true>,   shade_row_sse2<false, true, true, true, true>};
#else
        static constexpr std::array<ShadeRow, 8> toned = {
            shade_row_toned<false, false, false>, shade_row_toned<false, false, true>,
            shade_row_toned<false, true, false>,  shade_row_toned<false, true, true>,
            shade_row_toned<true, false, false>,  shade_row_toned<true, false, true>,
            shade_row_toned<true, true, false>,   shade_row_toned<true, true, true>};
#endif
        return toned[std::size_t(p.light_mix == LightMix::surface) * 4 + std::size_t(p.dark_unlit) * 2 + std::size_t(grey)];
    }
    const std::size_t at = std::size_t(p.mode == Mode::shadow) * 8 + std::size_t(p.light_mix == LightMix::surface) * 4 +
                           std::size_t(p.dark_unlit) * 2 + std::size_t(grey);
    static constexpr auto table = variants<Sse2>(std::make_index_sequence<16>());
#if defined(ISOLUX_HAS_SHADE_AVX2)
    static constexpr auto wide = variants<Avx2>(std::make_index_sequence<16>());
    if (wide_kernels()) return wide[at];
#endif
    return table[at];
}

}  // namespace

void composite_into(const Image& colour, Rect view, const LightTexture& light, const Params& p, Rect region, Image& out) {
    assert(colour.width == view.w && colour.height == view.h);
    assert(p.ambient_clarity >= 0 && p.ambient_clarity <= 1);
    assert(&colour != &out);  // a row's last step re-reads texels the step before it wrote over
    if (out.width != view.w || out.height != view.h) out = Image(view.w, view.h);
    const Rect z = intersect(region, view);
    if (z.empty()) return;
    const double ac = p.ambient_clarity;
    // Built once: a frame composites several parts, each a call.
    static const std::array<float, 256> unit = [] {
        std::array<float, 256> u{};
        for (int v = 0; v < 256; ++v) u[std::size_t(v)] = float(v / 255.0);
        return u;
    }();
    ShadeConstants k{&p,       nullptr, float(std::sqrt(ac)), float(p.exposure / (ac * ac + 0.1)), float(0.75 * p.exposure),
                     unit.data()};
    const bool grey = light.channels == 1;
    const ShadeRow shade = shade_row_for(p, grey);
    thread_local std::vector<std::uint8_t> unlit;  // zeros: light outside the texture
    unlit.assign(std::size_t(z.w) * 3 + 16, 0);
    const std::uint8_t* light_end = light.texels.data() + light.texels.size();
    assert(light.channels == 1 || light.channels == 3);
    // Where the light texture covers each row (the rest reads 0, unlit).
    const int lx0 = std::clamp(light.rect.x, z.x, z.x + z.w), lx1 = std::clamp(light.rect.x + light.rect.w, lx0, z.x + z.w);
    for (int wy = z.y; wy < z.y + z.h; ++wy) {
        const std::uint8_t* s = colour.at(z.x - view.x, wy - view.y);
        std::uint8_t* d = out.at(z.x - view.x, wy - view.y);
        const bool row_lit = wy >= light.rect.y && wy < light.rect.y + light.rect.h && lx0 < lx1;
        // Three runs: unlit left of the texture, over it, unlit right of it.
        const int cut0 = row_lit ? lx0 - z.x : z.w, cut1 = row_lit ? lx1 - z.x : z.w;
        k.light_end = unlit.data() + unlit.size();
        if (cut0 > 0) shade(s, unlit.data(), cut0, k, d);
        if (z.w > cut1) shade(s + std::size_t(cut1) * 4, unlit.data(), z.w - cut1, k, d + std::size_t(cut1) * 4);
        k.light_end = light_end;
        if (cut1 > cut0) shade(s + std::size_t(cut0) * 4, light.at(lx0, wy), cut1 - cut0, k, d + std::size_t(cut0) * 4);
    }
}

Image composite(const Image& colour, Rect view, const LightTexture& light, const Params& p) {
    Image out;
    composite_into(colour, view, light, p, view, out);
    return out;
}

Image composite_reference(const Image& colour, Rect view, const LightTexture& light, const Params& p) {
    assert(colour.width == view.w && colour.height == view.h);
    Image out(view.w, view.h);
    for (int y = 0; y < view.h; ++y)
        for (int x = 0; x < view.w; ++x) {
            const std::uint8_t* s = colour.at(x, y);
            std::uint8_t* d = out.at(x, y);
            d[3] = s[3];
            if (s[3] == 0) continue;
            const int wx = view.x + x, wy = view.y + y;
            exact_pixel(s, light.rect.contains(wx, wy) ? light.at(wx, wy) : nullptr, light.channels == 1, p, d);
        }
    return out;
}

}  // namespace isolux
