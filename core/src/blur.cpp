// Paper 3.2: "Once the light texture is in the GPU, a simple box-blur
// algorithm is applied to the same." CPU reference of shaders/blur.frag.
#include "isolux/blur.hpp"

#include <cassert>
#include <algorithm>

namespace isolux {

LightTexture box_blur(const LightTexture& tex, int radius) {
    assert(radius >= 0 && tex.rgb.size() == std::size_t(std::max(0, tex.rect.w)) * std::max(0, tex.rect.h) * 3);
    if (radius <= 0 || tex.rect.empty()) return tex;
    const int w = tex.rect.w, h = tex.rect.h;
    const std::int64_t n = std::int64_t(2 * radius + 1) * (2 * radius + 1);
    auto clampi = [](std::int64_t v, int hi) { return int(std::clamp<std::int64_t>(v, 0, hi - 1)); };
    // Horizontal window sums (not divided), then vertical sums of those, then
    // one rounded division: the exact mean of the clamped 2D window.
    std::vector<std::uint32_t> rows(std::size_t(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int c = 0; c < 3; ++c) {
            const std::uint8_t* src = &tex.rgb[std::size_t(y) * w * 3 + c];
            std::uint32_t sum = 0;
            for (std::int64_t i = -radius; i <= radius; ++i) sum += src[std::size_t(clampi(i, w)) * 3];
            for (int x = 0; x < w; ++x) {
                rows[(std::size_t(y) * w + x) * 3 + c] = sum;
                sum += src[std::size_t(clampi(std::int64_t(x) + radius + 1, w)) * 3];
                sum -= src[std::size_t(clampi(std::int64_t(x) - radius, w)) * 3];
            }
        }
    LightTexture out(tex.rect);
    for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
            auto at = [&](std::int64_t y) { return std::uint64_t(rows[(std::size_t(clampi(y, h)) * w + x) * 3 + c]); };
            std::uint64_t sum = 0;
            for (std::int64_t i = -radius; i <= radius; ++i) sum += at(i);
            for (int y = 0; y < h; ++y) {
                out.rgb[(std::size_t(y) * w + x) * 3 + c] = std::uint8_t((sum + std::uint64_t(n / 2)) / std::uint64_t(n));
                sum += at(std::int64_t(y) + radius + 1);
                sum -= at(std::int64_t(y) - radius);
            }
        }
    return out;
}

}  // namespace isolux
