// Paper Algorithm 3: the fragment shader. CPU reference of shaders/composite.frag.
#include "isolux/composite.hpp"

#include <cassert>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace isolux {

void composite_pixel(const double c[3], const double L[3], const Params& p, double out[3]) {
    const double ac = p.ambient_clarity;
    const double luminance = c[0] * 0.349 + c[1] * 0.114 + c[2] * 0.537;
    const double denom = ac * ac + 0.1;
    const double tex_scale = std::sqrt(ac);
    const bool shadow = p.mode == Mode::shadow;
    const bool surface = p.light_mix == LightMix::surface;
    for (int k = 0; k < 3; ++k) {
        // surface (not in the paper): the sprite's own colour takes the light,
        // and a shadow darkens it by up to three quarters instead of subtracting.
        if (surface && shadow) {
            out[k] = std::clamp(c[k] * tex_scale * (1.0 - 0.75 * L[k]), 0.0, 1.0);
            continue;
        }
        const double light_factor = (surface ? c[k] : luminance) * L[k] / denom;
        double tex_factor = c[k] * tex_scale;
        // dark_unlit: "if the texFactor variable in Algorithm 3 is multiplied
        // by lightTexture, then what is not hit by the light ... would appear
        // completely dark". In shadow mode the texture holds shadow, so the
        // light is its complement.
        if (p.dark_unlit) tex_factor *= shadow ? (1.0 - L[k]) : L[k];
        out[k] = std::clamp(shadow ? tex_factor - light_factor : tex_factor + light_factor, 0.0, 1.0);
    }
}

namespace {

// One pixel exactly as composite_pixel rounds it.
void exact_pixel(const std::uint8_t* s, const std::uint8_t* l, const Params& p, std::uint8_t* d) {
    double c[3] = {s[0] / 255.0, s[1] / 255.0, s[2] / 255.0}, L[3] = {0, 0, 0}, r[3];
    if (l) L[0] = l[0] / 255.0, L[1] = l[1] / 255.0, L[2] = l[2] / 255.0;
    composite_pixel(c, L, p, r);
    for (int k = 0; k < 3; ++k) d[k] = std::uint8_t(r[k] * 255.0 + 0.5);
}

// composite_pixel in float with the frame's constants hoisted, scaled to
// 0..255. Its error (under 2e-4 of a level wherever the result is not
// clamped) cannot change the rounding unless the exact value lies within
// 1/256 of a level's half: those pixels, under 1 in 100, are marked and
// redone exactly. One branch-free loop per mode, which the compiler
// vectorises.
struct ShadeConstants {
    float tex_scale, inv_denom;
    float unit[256];  // v / 255
};

// Three passes over runs of up to 256 pixels, so the arithmetic is one
// loop over plain float arrays (vectorised): spread the bytes into floats
// (table lookups, no conversions), shade, gather the bytes back.
template <bool Shadow, bool Surface, bool DarkUnlit>
void shade_row(const std::uint8_t* s, const std::uint8_t* l, int n, const ShadeConstants& k, std::uint8_t* d,
               std::uint8_t* unsure) {
    constexpr int run = 256;
    constexpr float near = 1.0f / 256.0f, round_magic = 8388608.0f;  // 2^23: adding it rounds to an integer
    alignas(16) float c[3][run], L[3][run], t[3][run];
    alignas(16) std::int32_t bad[run];
    alignas(16) float lum[run];
    const float ts = k.tex_scale, inv_denom = k.inv_denom;
    for (int i0 = 0; i0 < n; i0 += run) {
        const int m = std::min(run, n - i0);
        const std::uint8_t* sp = s + std::size_t(i0) * 4;
        const std::uint8_t* lp = l + std::size_t(i0) * 3;
        for (int i = 0; i < m; ++i)
            for (int ch = 0; ch < 3; ++ch) c[ch][i] = k.unit[sp[4 * i + ch]], L[ch][i] = k.unit[lp[3 * i + ch]];
        for (int i = 0; i < m; ++i) lum[i] = c[0][i] * 0.349f + c[1][i] * 0.114f + c[2][i] * 0.537f, bad[i] = 0;
        for (int ch = 0; ch < 3; ++ch) {
            const float* cc = c[ch];
            const float* LL = L[ch];
            float* tt = t[ch];
            for (int i = 0; i < m; ++i) {
                float v;
                if constexpr (Surface && Shadow) {
                    v = cc[i] * ts * (1.0f - 0.75f * LL[i]);
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
            for (int i = 0; i < m; ++i) {
                const float x = tt[i] + 0.5f;
                const float off = x - ((x + round_magic) - round_magic);  // distance to the nearest integer
                bad[i] |= std::int32_t(off < near) & std::int32_t(off > -near);
                tt[i] = x;
            }
        }
        std::uint8_t* dp = d + std::size_t(i0) * 4;
        for (int i = 0; i < m; ++i) {
            const std::uint8_t alpha = sp[4 * i + 3];
            const std::uint8_t keep = alpha != 0 ? 0xFF : 0x00;  // transparent: all zero
            for (int ch = 0; ch < 3; ++ch) dp[4 * i + ch] = std::uint8_t(std::uint8_t(std::int32_t(t[ch][i])) & keep);
            dp[4 * i + 3] = alpha;
            unsure[i0 + i] = std::uint8_t(bad[i] & keep & 1);
        }
    }
}

using ShadeRow = void (*)(const std::uint8_t*, const std::uint8_t*, int, const ShadeConstants&, std::uint8_t*,
                          std::uint8_t*);

ShadeRow shade_row_for(const Params& p) {
    const bool shadow = p.mode == Mode::shadow, surface = p.light_mix == LightMix::surface;
    static constexpr ShadeRow table[2][2][2] = {
        {{shade_row<false, false, false>, shade_row<false, false, true>},
         {shade_row<false, true, false>, shade_row<false, true, true>}},
        {{shade_row<true, false, false>, shade_row<true, false, true>},
         {shade_row<true, true, false>, shade_row<true, true, true>}}};
    return table[shadow][surface][p.dark_unlit];
}

}  // namespace

void composite_into(const Image& colour, Rect view, const LightTexture& light, const Params& p, Rect region, Image& out) {
    assert(colour.width == view.w && colour.height == view.h);
    assert(p.ambient_clarity >= 0 && p.ambient_clarity <= 1);
    if (out.width != view.w || out.height != view.h) out = Image(view.w, view.h);
    const Rect z = intersect(region, view);
    if (z.empty()) return;
    const double ac = p.ambient_clarity;
    ShadeConstants k{float(std::sqrt(ac)), float(1.0 / (ac * ac + 0.1)), {}};
    for (int v = 0; v < 256; ++v) k.unit[v] = float(v / 255.0);
    const ShadeRow shade = shade_row_for(p);
    std::vector<std::uint8_t> unlit(std::size_t(z.w) * 3, 0), unsure(std::size_t(z.w));
    // Where the light texture covers each row (the rest reads 0, unlit).
    const int lx0 = std::clamp(light.rect.x, z.x, z.x + z.w), lx1 = std::clamp(light.rect.x + light.rect.w, lx0, z.x + z.w);
    for (int wy = z.y; wy < z.y + z.h; ++wy) {
        const std::uint8_t* s = colour.at(z.x - view.x, wy - view.y);
        std::uint8_t* d = out.at(z.x - view.x, wy - view.y);
        const bool row_lit = wy >= light.rect.y && wy < light.rect.y + light.rect.h && lx0 < lx1;
        // Three runs: unlit left of the texture, over it, unlit right of it.
        const int cut0 = row_lit ? lx0 - z.x : z.w, cut1 = row_lit ? lx1 - z.x : z.w;
        if (cut0 > 0) shade(s, unlit.data(), cut0, k, d, unsure.data());
        if (cut1 > cut0) shade(s + std::size_t(cut0) * 4, light.at(lx0, wy), cut1 - cut0, k, d + std::size_t(cut0) * 4, unsure.data() + cut0);
        if (z.w > cut1) shade(s + std::size_t(cut1) * 4, unlit.data(), z.w - cut1, k, d + std::size_t(cut1) * 4, unsure.data() + cut1);
        for (int i = 0; i < z.w; ++i)
            if (unsure[std::size_t(i)]) {
                const int wx = z.x + i;
                const bool lit = row_lit && wx >= lx0 && wx < lx1;
                exact_pixel(s + std::size_t(i) * 4, lit ? light.at(wx, wy) : nullptr, p, d + std::size_t(i) * 4);
            }
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
            exact_pixel(s, light.rect.contains(wx, wy) ? light.at(wx, wy) : nullptr, p, d);
        }
    return out;
}

}  // namespace isolux
