// Algorithm 3 on the CPU: composite held to composite_reference byte for
// byte, in both kernels' builds.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "isolux/accuracy.hpp"
#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "isolux/cpu.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/opacity_correction.hpp"
#include "test_util.hpp"

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
                for (double ac : clarities) {
                    Params p;
                    p.mode = mode;
                    p.light_mix = mix;
                    p.dark_unlit = dark;
                    p.ambient_clarity = ac;
                    const Image want = composite_reference(colour, view, light, p);
                    for (bool wide : both_widths()) {
                        set_wide_kernels(wide);
                        EXPECT_EQ(composite(colour, view, light, p).rgba, want.rgba)
                            << to_string(mode) << " mix " << int(mix) << " dark " << dark << " ac " << ac << " wide " << wide;
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
    EXPECT_EQ(expect_every_mode_is_reference(colour, view, light, {0.0, 0.16, 0.4, 0.5, 0.77, 1.0}), 72);
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
    EXPECT_EQ(expect_every_mode_is_reference(colour, view, light, {0.0, 0.6, 1.0}), 36);
}
