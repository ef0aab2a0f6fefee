// Paper 3.2: drawing traced lights into the light texture, and the inverse
// translation that stands in for a retrace between every l-th frame.
#include "isolux/light_texture.hpp"

#include <algorithm>
#include <cmath>

namespace isolux {

int light_a(const Light& l, const Params& p) { return l.area_a.value_or(p.area_a); }
int light_b(const Light& l, const Params& p) { return l.area_b.value_or(p.area_b); }

Rect light_area(const Light& l, const Params& p) {
    const int a = light_a(l, p), b = light_b(l, p);
    // Centres far outside int range give an empty area (they meet no view).
    const double cx = std::floor(l.x), cy = std::floor(l.y);
    if (std::abs(cx) > 1e9 || std::abs(cy) > 1e9) return {0, 0, 0, 0};
    return {int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
}

void accumulate_light(LightTexture& tex, const LightMask& mask, const Light& light, const Params& p) {
    const Rect r = intersect(mask.clip, tex.rect);
    if (r.empty()) return;
    // The value a pixel at distance d receives, per channel: tabulated once.
    const std::int64_t dmax = std::max<std::int64_t>(
        {std::llabs(r.x - mask.cx), std::llabs(r.x + r.w - 1 - mask.cx), std::llabs(r.y - mask.cy),
         std::llabs(r.y + r.h - 1 - mask.cy)});
    const bool white = light.r == 255 && light.g == 255 && light.b == 255 && light.intensity == 1.0;
    std::vector<std::uint8_t> table(std::size_t(dmax + 1) * 3);
    for (std::int64_t d = 0; d <= dmax; ++d) {
        const std::uint8_t v = falloff(d, p.falloff_scale);
        const std::uint8_t c[3] = {light.r, light.g, light.b};
        for (int k = 0; k < 3; ++k)
            table[std::size_t(d) * 3 + k] =
                white ? v : std::uint8_t(std::min(255.0, std::floor(v * light.intensity * c[k] / 255.0 + 0.5)));
    }
    const bool shadow = p.mode == Mode::shadow;
    for (int y = r.y; y < r.y + r.h; ++y) {
        const std::size_t mrow = std::size_t(y - mask.clip.y) * mask.clip.w;
        std::uint8_t* out = &tex.rgb[(std::size_t(y - tex.rect.y) * tex.rect.w + (r.x - tex.rect.x)) * 3];
        const std::int64_t dy = std::llabs(y - mask.cy);
        for (int x = r.x; x < r.x + r.w; ++x, out += 3) {
            const std::size_t i = mrow + std::size_t(x - mask.clip.x);
            const bool on = shadow ? (mask.reached[i] && !mask.lit[i]) : mask.lit[i];
            if (!on) continue;
            const std::int64_t d = std::max<std::int64_t>(std::llabs(x - mask.cx), dy);
            const std::uint8_t* v = &table[std::size_t(d) * 3];
            for (int k = 0; k < 3; ++k) out[k] = std::uint8_t(std::min(255, out[k] + v[k]));
        }
    }
}

LightTexture shift_light_texture(const LightTexture& traced, Rect view) {
    LightTexture out(view);
    const Rect r = intersect(traced.rect, view);
    for (int y = r.y; y < r.y + r.h; ++y)
        std::copy_n(traced.at(r.x, y), std::size_t(r.w) * 3,
                    &out.rgb[(std::size_t(y - view.y) * view.w + (r.x - view.x)) * 3]);
    return out;
}

}  // namespace isolux
