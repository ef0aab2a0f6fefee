// Paper 3.2: drawing traced lights into the light texture, and the inverse
// translation that stands in for a retrace between every l-th frame.
#include "isolux/light_texture.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "base/cpu_dispatch.hpp"
#include "base/cpu.hpp"
#include "isolux/sprite_shading.hpp"
#if ISOLUX_X86_DISPATCH
#include <immintrin.h>
#endif

namespace isolux {

namespace {

// out[3x + c] += v[x] for every channel c, saturating: a white light's row.
// The AVX2 build (base/cpu.hpp) spreads 32 values over 96 bytes with three
// byte shuffles; the baseline writes the spread row, then adds it.
void add_white_row(std::uint8_t* out, const std::uint8_t* v, int w, std::vector<std::uint8_t>& rgb) {
    for (int x = 0; x < w; ++x) rgb[std::size_t(x) * 3 + 0] = rgb[std::size_t(x) * 3 + 1] = rgb[std::size_t(x) * 3 + 2] = v[x];
    for (std::size_t i = 0, n = std::size_t(w) * 3; i < n; ++i) {
        const std::uint8_t s = std::uint8_t(out[i] + rgb[i]);
        out[i] = s < out[i] ? std::uint8_t(255) : s;
    }
}

#if ISOLUX_X86_DISPATCH
// 32 values spread over 96 bytes of three 32-byte vectors: byte shuffles
// work within 16-byte lanes, so each vector's lanes are first filled with
// the values they take theirs from (the first 16 values in both lanes, the
// 32 as loaded, the last 16 in both).
struct WhiteSpread32 {
    __m256i lo, mid, hi;
};

ISOLUX_AVX2 inline WhiteSpread32 white_spread32(const std::uint8_t* v) {
    const __m256i s0 = _mm256_setr_epi8(0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5,  //
                                        5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 10, 10);
    const __m256i s1 = _mm256_setr_epi8(10, 11, 11, 11, 12, 12, 12, 13, 13, 13, 14, 14, 14, 15, 15, 15,  //
                                        0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5);
    const __m256i s2 = _mm256_setr_epi8(5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 10, 10,  //
                                        10, 11, 11, 11, 12, 12, 12, 13, 13, 13, 14, 14, 14, 15, 15, 15);
    const __m128i first = _mm_loadu_si128(reinterpret_cast<const __m128i*>(v));
    const __m128i last = _mm_loadu_si128(reinterpret_cast<const __m128i*>(v + 16));
    return {_mm256_shuffle_epi8(_mm256_set_m128i(first, first), s0),
            _mm256_shuffle_epi8(_mm256_set_m128i(last, first), s1),
            _mm256_shuffle_epi8(_mm256_set_m128i(last, last), s2)};
}

ISOLUX_AVX2 void add_white_row_avx2(std::uint8_t* out, const std::uint8_t* v, int w) {
    auto at = [&](int x, int k) { return reinterpret_cast<__m256i*>(out + std::size_t(x) * 3 + std::size_t(k) * 32); };
    if (w >= 32) {
        // The row's last 32 texels summed from the bytes there before any
        // store, and stored last: where they overlap the loop's last step
        // the loop wrote the same sums (a saturating add is not idempotent,
        // so they must not be read back after it).
        const int x_last = w - 32;
        const WhiteSpread32 t = white_spread32(v + x_last);
        const __m256i last0 = _mm256_adds_epu8(_mm256_loadu_si256(at(x_last, 0)), t.lo);
        const __m256i last1 = _mm256_adds_epu8(_mm256_loadu_si256(at(x_last, 1)), t.mid);
        const __m256i last2 = _mm256_adds_epu8(_mm256_loadu_si256(at(x_last, 2)), t.hi);
        for (int x = 0; x + 32 <= w; x += 32) {
            const WhiteSpread32 s = white_spread32(v + x);
            _mm256_storeu_si256(at(x, 0), _mm256_adds_epu8(_mm256_loadu_si256(at(x, 0)), s.lo));
            _mm256_storeu_si256(at(x, 1), _mm256_adds_epu8(_mm256_loadu_si256(at(x, 1)), s.mid));
            _mm256_storeu_si256(at(x, 2), _mm256_adds_epu8(_mm256_loadu_si256(at(x, 2)), s.hi));
        }
        _mm256_storeu_si256(at(x_last, 0), last0);
        _mm256_storeu_si256(at(x_last, 1), last1);
        _mm256_storeu_si256(at(x_last, 2), last2);
        return;
    }
    // Rows narrower than a step (a light cut by the view's edge): one by one.
    for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
            std::uint8_t& d = out[std::size_t(x) * 3 + std::size_t(c)];
            d = std::uint8_t(std::min(255, d + v[x]));
        }
}
#endif

// out[x] += v[x], saturating: a grey texture's row (the compiler vectorises
// it, at both widths).
[[gnu::always_inline]] inline void add_grey_row_any(std::uint8_t* __restrict out, const std::uint8_t* __restrict v, int w) {
    for (int x = 0; x < w; ++x) {
        const std::uint8_t s = std::uint8_t(out[x] + v[x]);
        out[x] = s < out[x] ? std::uint8_t(255) : s;
    }
}
void add_grey_row(std::uint8_t* out, const std::uint8_t* v, int w) { add_grey_row_any(out, v, w); }
#if ISOLUX_X86_DISPATCH
ISOLUX_AVX2 void add_grey_row_avx2(std::uint8_t* out, const std::uint8_t* v, int w) { add_grey_row_any(out, v, w); }
#endif

}  // namespace

LightTexture rgb_texture(const LightTexture& tex) {
    if (tex.channels == 3) return tex;
    LightTexture out(tex.rect);
    for (std::size_t i = 0; i < tex.texels.size(); ++i)
        out.texels[i * 3] = out.texels[i * 3 + 1] = out.texels[i * 3 + 2] = tex.texels[i];
    return out;
}

int light_a(const Light& l, const Params& p) { return l.area_a.value_or(p.area_a); }
int light_b(const Light& l, const Params& p) { return l.area_b.value_or(p.area_b); }

Rect light_area(const Light& l, const Params& p) {
    const int a = light_a(l, p), b = light_b(l, p);
    // Centres far outside int range give an empty area (they meet no view).
    const double cx = std::floor(l.x), cy = std::floor(l.y);
    if (std::abs(cx) > 1e9 || std::abs(cy) > 1e9) return {0, 0, 0, 0};
    return {int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
}

void accumulate_light(LightTexture& tex, const LightMask& mask, const Light& light, const Params& p, int row_begin,
                      int row_end, const Rect* within) {
    Rect r = intersect(mask.clip, tex.rect);
    if (within) r = intersect(r, *within);
    const int y0 = std::max(r.y, row_begin), y1 = std::min(r.y + r.h, row_end);
    r.y = y0;
    r.h = y1 - y0;
    if (r.empty()) return;
    assert(tex.channels == 3 || grey_light(light));
    const bool grey = tex.channels == 1;
    const bool white = light.r == 255 && light.g == 255 && light.b == 255 && light.intensity == 1.0;
    // A white light's value v becomes round(v * intensity * colour / 255) per channel.
    std::uint8_t lut[3][256];
    const std::uint8_t colour[3] = {light.r, light.g, light.b};
    if (!white)
        for (int v = 0; v < 256; ++v)
            for (int k = 0; k < 3; ++k)
                lut[k][v] = std::uint8_t(std::min(255.0, std::floor(v * light.intensity * colour[k] / 255.0 + 0.5)));
    const bool shadow = p.mode == Mode::shadow;
    // With sprite shading a lit sprite pixel may hold less than its light:
    // what it lacks is the shadow its own surface casts (sprite_shading.hpp).
    const bool shaded = shades_sprites(p);
    std::vector<std::uint8_t> by_x;
    if (shadow) {
        // Shadow pixels are not lit: their falloff comes from their distance,
        // min(falloff(|dx|), falloff(|dy|)) as falloff never increases.
        by_x.resize(std::size_t(r.w));
        for (int x = 0; x < r.w; ++x) by_x[std::size_t(x)] = falloff(std::llabs(r.x + x - mask.cx), mask.falloff_scale);
    }
    std::vector<std::uint8_t> row(std::size_t(r.w)), rgb(std::size_t(r.w) * 3);
    for (int y = r.y; y < r.y + r.h; ++y) {
        const std::size_t mrow = std::size_t(y - mask.clip.y) * mask.clip.w + std::size_t(r.x - mask.clip.x);
        const std::uint8_t* v = &mask.value[mrow];
        if (shadow) {
            const std::uint8_t* reached = &mask.reached[mrow];
            const std::uint8_t vy = falloff(std::llabs(y - mask.cy), mask.falloff_scale);
            for (int x = 0; x < r.w; ++x) {
                if (!reached[x] || (v[x] != 0 && !shaded)) {
                    row[std::size_t(x)] = 0;
                    continue;
                }
                const std::uint8_t full = shaped(p) ? shaped_falloff(r.x + x - mask.cx, y - mask.cy, mask.a, mask.b, p, mask.dy_scale)
                                                    : std::min(by_x[std::size_t(x)], vy);
                row[std::size_t(x)] = v[x] < full ? std::uint8_t(full - v[x]) : 0;
            }
            v = row.data();
        }
        std::uint8_t* out = &tex.texels[(std::size_t(y - tex.rect.y) * tex.rect.w + (r.x - tex.rect.x)) * std::size_t(tex.channels)];
        if (grey) {  // one channel: the value itself, or its one table
            if (!white) {
                for (int x = 0; x < r.w; ++x) rgb[std::size_t(x)] = lut[0][v[x]];
                v = rgb.data();
            }
#if ISOLUX_X86_DISPATCH
            if (wide_kernels()) {
                add_grey_row_avx2(out, v, r.w);
                continue;
            }
#endif
            add_grey_row(out, v, r.w);
            continue;
        }
        if (white) {  // the value itself in all three channels: no lookups
#if ISOLUX_X86_DISPATCH
            if (wide_kernels()) {
                add_white_row_avx2(out, v, r.w);
                continue;
            }
#endif
            add_white_row(out, v, r.w, rgb);
            continue;
        }
        // A coloured light: the row's RGB contributions, then one contiguous
        // saturating add (the compiler vectorises it).
        for (int x = 0; x < r.w; ++x) {
            const std::uint8_t val = v[x];
            rgb[std::size_t(x) * 3 + 0] = lut[0][val];
            rgb[std::size_t(x) * 3 + 1] = lut[1][val];
            rgb[std::size_t(x) * 3 + 2] = lut[2][val];
        }
        const std::uint8_t* add = rgb.data();
        const std::size_t n = std::size_t(r.w) * 3;
        for (std::size_t i = 0; i < n; ++i) {  // saturating: never wraps
            const std::uint8_t s = std::uint8_t(out[i] + add[i]);
            out[i] = s < out[i] ? std::uint8_t(255) : s;
        }
    }
}

LightTexture shift_light_texture(const LightTexture& traced, Rect view) {
    LightTexture out(view, traced.channels);
    const Rect r = intersect(traced.rect, view);
    const std::size_t c = std::size_t(traced.channels);
    for (int y = r.y; y < r.y + r.h; ++y)
        std::copy_n(traced.at(r.x, y), std::size_t(r.w) * c,
                    &out.texels[(std::size_t(y - view.y) * view.w + (r.x - view.x)) * c]);
    return out;
}

Image light_texture_image(const LightTexture& tex) {
    Image out(tex.rect.w, tex.rect.h);
    for (std::size_t i = 0, n = std::size_t(out.width) * out.height; i < n; ++i) {
        for (int k = 0; k < 3; ++k) out.rgba[i * 4 + k] = tex.texels[i * std::size_t(tex.channels) + (tex.channels == 3 ? k : 0)];
        out.rgba[i * 4 + 3] = 255;
    }
    return out;
}

}  // namespace isolux
