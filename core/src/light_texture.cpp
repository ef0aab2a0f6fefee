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
    // The value at distance d per channel, tabulated once. falloff is
    // non-increasing in d, so the value at max(|dx|, |dy|) is the smaller of
    // the values at |dx| and at |dy|: a row is min(by_x[x], by_y) per texel.
    const std::int64_t dmax = std::max<std::int64_t>(
        {std::llabs(r.x - mask.cx), std::llabs(r.x + r.w - 1 - mask.cx), std::llabs(r.y - mask.cy),
         std::llabs(r.y + r.h - 1 - mask.cy)});
    const bool white = light.r == 255 && light.g == 255 && light.b == 255 && light.intensity == 1.0;
    const std::uint8_t colour[3] = {light.r, light.g, light.b};
    std::vector<std::uint8_t> table(std::size_t(dmax + 1) * 3);
    for (std::int64_t d = 0; d <= dmax; ++d) {
        const std::uint8_t v = falloff(d, p.falloff_scale);
        for (int k = 0; k < 3; ++k)
            table[std::size_t(d) * 3 + k] =
                white ? v : std::uint8_t(std::min(255.0, std::floor(v * light.intensity * colour[k] / 255.0 + 0.5)));
    }
    std::vector<std::uint8_t> by_x(std::size_t(r.w) * 3), row(std::size_t(r.w) * 3);
    for (int x = 0; x < r.w; ++x)
        for (int k = 0; k < 3; ++k) by_x[std::size_t(x) * 3 + k] = table[std::size_t(std::llabs(r.x + x - mask.cx)) * 3 + k];
    const bool shadow = p.mode == Mode::shadow;
    for (int y = r.y; y < r.y + r.h; ++y) {
        const std::size_t mrow = std::size_t(y - mask.clip.y) * mask.clip.w + std::size_t(r.x - mask.clip.x);
        const std::uint8_t* lit = &mask.lit[mrow];
        const std::uint8_t* reached = shadow ? &mask.reached[mrow] : nullptr;
        const std::uint8_t* by_y = &table[std::size_t(std::llabs(y - mask.cy)) * 3];
        for (int x = 0; x < r.w; ++x) {
            // 0xFF where this light adds, 0 elsewhere: no branch.
            const std::uint8_t on = shadow ? std::uint8_t(-(reached[x] & (lit[x] ^ 1))) : std::uint8_t(-lit[x]);
            for (int k = 0; k < 3; ++k)
                row[std::size_t(x) * 3 + k] = std::uint8_t(std::min(by_x[std::size_t(x) * 3 + k], by_y[k]) & on);
        }
        std::uint8_t* out = &tex.rgb[(std::size_t(y - tex.rect.y) * tex.rect.w + (r.x - tex.rect.x)) * 3];
        const std::size_t n = std::size_t(r.w) * 3;
        for (std::size_t i = 0; i < n; ++i) {  // saturating: never wraps
            const unsigned s = unsigned(out[i]) + row[i];
            out[i] = std::uint8_t(s > 255 ? 255 : s);
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
