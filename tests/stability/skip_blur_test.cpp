// Hard cases: ray skip and the blur.
#include "isolux/blur.hpp"
#include "isolux/hash.hpp"
#include "stability.hpp"

using namespace isolux;
using namespace isolux::stability;

TEST(StabilitySkipBlur, aSkipLargerThanTheBorderTracesOneRay) {
    Mask empty(Rect{-10, -10, 21, 21});
    Params p;
    p.ray_skip = 1 << 20;
    LightMask m = trace_light(empty, 0, 0, 10, 10, p, empty.rect());
    // Only the first border ray (to the top-left corner): the diagonal.
    const auto lit = test::lit_of(m);
    EXPECT_EQ(std::count(lit.begin(), lit.end(), 1), 11);
    const Rect b = world().placed.bounds;
    Scene s = with_light(b.w / 2.0, b.h / 2.0);
    s.params.ray_skip = 1 << 20;
    stable_frame(s);
}

TEST(StabilitySkipBlur, blurRadiusLargerThanTheTexture) {
    LightTexture t(Rect{3, 4, 5, 2});
    Pcg32 rng(3);
    for (auto& v : t.texels) v = std::uint8_t(rng.below(256));
    for (int r : {6, 50, 255}) {
        LightTexture b = box_blur(t, r);
        EXPECT_EQ(b.rect, t.rect);
        // Still the clamped mean: far larger radii converge to edge weighting,
        // and every value stays within the input's range.
        for (int k = 0; k < 3; ++k) {
            int lo = 255, hi = 0;
            for (std::size_t i = k; i < t.texels.size(); i += 3) lo = std::min<int>(lo, t.texels[i]), hi = std::max<int>(hi, t.texels[i]);
            for (std::size_t i = k; i < b.texels.size(); i += 3) {
                EXPECT_GE(b.texels[i], lo);
                EXPECT_LE(b.texels[i], hi);
            }
        }
        EXPECT_EQ(box_blur(t, r).texels, b.texels);
    }
    Scene s = with_light(200, 150);
    s.params.blur_radius = 255;
    stable_frame(s, Camera{100, 100, 40, 30});
}

TEST(StabilitySkipBlur, theBlursEdgeRuleIsTheShadersClampToEdge) {
    // The shader samples with coordinates clamped to [0, size-1] (texelFetch
    // on clamp(p + i, 0, size - 1)): a literal 2D transcription of that rule.
    LightTexture t(Rect{0, 0, 9, 6});
    Pcg32 rng(8);
    for (auto& v : t.texels) v = std::uint8_t(rng.below(256));
    for (int r : {1, 2, 4, 11}) {
        LightTexture b = box_blur(t, r);
        const int n = (2 * r + 1) * (2 * r + 1);
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 9; ++x)
                for (int k = 0; k < 3; ++k) {
                    int sum = 0;
                    for (int j = -r; j <= r; ++j)
                        for (int i = -r; i <= r; ++i)
                            sum += t.texels[(std::clamp(y + j, 0, 5) * 9 + std::clamp(x + i, 0, 8)) * 3 + k];
                    EXPECT_EQ(b.texels[(y * 9 + x) * 3 + k], (sum + n / 2) / n) << x << "," << y << " r " << r;
                }
    }
}
