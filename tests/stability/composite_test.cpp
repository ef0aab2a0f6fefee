// Hard cases: Algorithm 3 at the ends of its ranges.
#include "isolux/composite.hpp"
#include "stability.hpp"

using namespace isolux;

TEST(StabilityComposite, ambientZeroAndOneWithColoursZeroAndFull) {
    for (double ambient : {0.0, 1.0, 1e-9, 0.999999}) {
        for (int colour : {0, 255}) {
            for (int light : {0, 1, 128, 255}) {
                for (bool dark : {false, true}) {
                    Image c(1, 1);
                    c.rgba = {std::uint8_t(colour), std::uint8_t(colour), std::uint8_t(colour), 255};
                    LightTexture l(Rect{0, 0, 1, 1});
                    l.texels = {std::uint8_t(light), std::uint8_t(light), std::uint8_t(light)};
                    Params p;
                    p.ambient_clarity = ambient;
                    p.dark_unlit = dark;
                    Image out = composite(c, Rect{0, 0, 1, 1}, l, p);
                    const double cc = colour / 255.0, L = light / 255.0;
                    const double lum = cc * (0.349 + 0.114 + 0.537);
                    const double tex = cc * std::sqrt(ambient) * (dark ? L : 1.0);
                    const double want = std::clamp(tex + lum * L / (ambient * ambient + 0.1), 0.0, 1.0);
                    EXPECT_NEAR(out.rgba[0] / 255.0, want, 1.0 / 255) << ambient << " " << colour << " " << light;
                    double in_c[3] = {cc, cc, cc}, in_l[3] = {L, L, L}, r[3];
                    composite_pixel(in_c, in_l, p, r);
                    for (double v : r) EXPECT_TRUE(std::isfinite(v) && v >= 0 && v <= 1);
                }
            }
        }
    }
}

TEST(StabilityComposite, shadowModeNeverGoesBelowZero) {
    Params p;
    p.mode = Mode::shadow;
    p.ambient_clarity = 0;
    double c[3] = {1, 1, 1}, L[3] = {1, 1, 1}, r[3];
    composite_pixel(c, L, p, r);
    for (double v : r) EXPECT_EQ(v, 0.0);
}
