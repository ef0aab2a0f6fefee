// Algorithm 3 on the CPU: composite held to composite_reference byte for
// byte in both kernels' builds, to the paper at chosen pixels, and at the
// ends of its ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <cmath>

#include "isolux/accuracy.hpp"
#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "base/cpu.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/opacity_correction.hpp"
#include "test_util.hpp"
#include "frame/oracles.hpp"

using namespace isolux;
using isolux::test::both_widths;
using isolux::test::random_texture;

namespace {

// composite in both kernels' builds must equal composite_reference in every
// mode, light mix and dark-unlit, at each of `clarities`; returns the
// settings compared.
int expect_every_mode_is_reference(const Image& colour, Rect view, const LightTexture& light,
                                   std::initializer_list<double> clarities) {
    int configs = 0;
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
        for (LightMix mix : {LightMix::luminance, LightMix::surface})
            for (bool dark : {false, true})
                for (double ac : clarities)
                    for (ToneMap tone : {ToneMap::none, ToneMap::reinhard_knee})
                        for (double exposure : {1.0, 3.7}) {
                            Params p;
                            p.mode = mode;
                            p.light_mix = mix;
                            p.dark_unlit = dark;
                            p.ambient_clarity = ac;
                            p.tone_map = tone;
                            p.exposure = exposure;
                            const Image want = composite_reference(colour, view, light, p);
                            for (bool wide : both_widths()) {
                                set_wide_kernels(wide);
                                EXPECT_EQ(composite(colour, view, light, p).rgba, want.rgba)
                                    << to_string(mode) << " mix " << int(mix) << " dark " << dark << " ac " << ac
                                    << " tone " << int(tone) << " exposure " << exposure << " wide " << wide;
                            }
                            set_wide_kernels(true);
                            ++configs;
                        }
    return configs;
}

}  // namespace

TEST(FastComposite, EqualsTheReferenceInEveryModeAndClarity) {
    const Rect view{-7, 3, 97, 61};
    Image colour(view.w, view.h);
    Pcg32 rng(4);
    for (std::uint8_t& v : colour.rgba) v = std::uint8_t(rng.below(256));
    for (int i = 0; i < view.w * view.h; i += 5) colour.rgba[std::size_t(i) * 4 + 3] = 0;  // some transparent
    // A light texture covering part of the view only: the rest reads unlit.
    const LightTexture light = random_texture({view.x + 20, view.y - 10, 60, 50}, 5);
    EXPECT_EQ(expect_every_mode_is_reference(colour, view, light, {0.0, 0.16, 0.4, 0.5, 0.77, 1.0}), 288);
}

TEST(FastComposite, EveryColourAndLightPairAtTheDefaults) {
    // All 256 x 256 (colour, light) values in each channel, with the other
    // channels varied: every rounding boundary of the default settings.
    const Rect view{0, 0, 256, 256};
    Image colour(256, 256);
    LightTexture light(view);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            std::uint8_t* c = colour.at(x, y);
            c[0] = std::uint8_t(x), c[1] = std::uint8_t(255 - x), c[2] = std::uint8_t((x * 7 + y) & 255), c[3] = 255;
            std::uint8_t* l = &light.texels[(std::size_t(y) * 256 + x) * 3];
            l[0] = std::uint8_t(y), l[1] = std::uint8_t((y * 3) & 255), l[2] = std::uint8_t(255 - y);
        }
    for (double ac : {0.4, 0.25, 0.9}) {
        Params p;
        p.ambient_clarity = ac;
        const Image want = composite_reference(colour, view, light, p);
        for (bool wide : both_widths()) {
            set_wide_kernels(wide);
            EXPECT_EQ(composite(colour, view, light, p).rgba, want.rgba) << ac << " wide " << wide;
        }
        set_wide_kernels(true);
    }
    // And every mode, light mix and dark-unlit at the extreme clarities (0:
    // the light term ten times the colour's) and one between.
    EXPECT_EQ(expect_every_mode_is_reference(colour, view, light, {0.0, 0.6, 1.0}), 144);
}

TEST(Composite, equalsAlgorithm3AtChosenPixels) {
    struct Case {
        std::uint8_t c[3], l;
        double ambient;
        bool dark;
    } cases[] = {{{200, 100, 50}, 0, 0.4, false},   {{200, 100, 50}, 128, 0.4, false}, {{10, 240, 90}, 255, 0.4, false},
                 {{255, 255, 255}, 255, 1.0, false}, {{0, 0, 0}, 255, 0.0, false},       {{120, 60, 200}, 60, 0.0, false},
                 {{120, 60, 200}, 60, 1.0, true},    {{255, 0, 0}, 30, 0.7, true}};
    for (const Case& k : cases) {
        Image colour(1, 1);
        std::copy(k.c, k.c + 3, colour.at(0, 0));
        colour.at(0, 0)[3] = 255;
        LightTexture light(Rect{0, 0, 1, 1});
        light.texels = {k.l, k.l, k.l};
        Params p;
        p.ambient_clarity = k.ambient;
        p.dark_unlit = k.dark;
        Image out = composite(colour, Rect{0, 0, 1, 1}, light, p);
        const double r = k.c[0] / 255.0, g = k.c[1] / 255.0, b = k.c[2] / 255.0, L = k.l / 255.0;
        const double lum = r * 0.349 + g * 0.114 + b * 0.537;
        for (int ch = 0; ch < 3; ++ch) {
            double tex = k.c[ch] / 255.0 * std::sqrt(k.ambient) * (k.dark ? L : 1.0);
            double want = std::clamp(tex + lum * L / (k.ambient * k.ambient + 0.1), 0.0, 1.0);
            EXPECT_NEAR(out.at(0, 0)[ch] / 255.0, want, 1.0 / 255) << int(k.c[0]) << " L " << int(k.l);
        }
        EXPECT_EQ(out.at(0, 0)[3], 255);
    }
}

// ---------------------------------------------------------------- frames

// Hard cases: Algorithm 3 at the ends of its ranges.

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
