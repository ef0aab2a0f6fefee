// Paper Algorithm 3: the fragment shader. CPU reference of shaders/composite.frag.
#include "isolux/composite.hpp"

#include <cassert>
#include <algorithm>
#include <cmath>

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

Image composite(const Image& colour, Rect view, const LightTexture& light, const Params& p) {
    assert(colour.width == view.w && colour.height == view.h);
    assert(p.ambient_clarity >= 0 && p.ambient_clarity <= 1);
    Image out(view.w, view.h);
    for (int y = 0; y < view.h; ++y)
        for (int x = 0; x < view.w; ++x) {
            const std::uint8_t* s = colour.at(x, y);
            std::uint8_t* d = out.at(x, y);
            d[3] = s[3];
            if (s[3] == 0) continue;
            const int wx = view.x + x, wy = view.y + y;
            double c[3] = {s[0] / 255.0, s[1] / 255.0, s[2] / 255.0}, L[3] = {0, 0, 0}, r[3];
            if (light.rect.contains(wx, wy)) {
                const std::uint8_t* l = light.at(wx, wy);
                L[0] = l[0] / 255.0, L[1] = l[1] / 255.0, L[2] = l[2] / 255.0;
            }
            composite_pixel(c, L, p, r);
            for (int k = 0; k < 3; ++k) d[k] = std::uint8_t(r[k] * 255.0 + 0.5);
        }
    return out;
}

}  // namespace isolux
