// The light texture: a white light's values and saturation (paper 3.2), and a
// grey texture (LightTexture::channels 1, used when every light is grey)
// giving the bytes of its r, g, b texture at every stage: the blur, the
// composite, the accumulation, and whole frames against frames with the grey
// texture turned off (FrameOptions::grey_when_lights_are).
#include <gtest/gtest.h>

#include <cstdio>

#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "base/cpu.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "test_util.hpp"
#include "frame/oracles.hpp"
#include "isolux/light_trace.hpp"

using namespace isolux;
using isolux::test::both_widths;
using isolux::test::random_texture;

namespace {

// Texels mostly dark with bright patches and full-white runs (every rounding
// case of the blur and the sums' maximum).
LightTexture random_grey(Rect r, std::uint64_t seed) {
    LightTexture t(r, 1);
    Pcg32 rng(seed);
    for (std::uint8_t& v : t.texels) {
        const std::uint32_t k = rng.below(10);
        v = k < 4 ? 0 : k < 6 ? 255 : std::uint8_t(rng.below(256));
    }
    return t;
}

// Channel 0 of an r, g, b texture whose three channels are equal, as a grey one.
LightTexture first_channel(const LightTexture& rgb) {
    LightTexture out(rgb.rect, 1);
    for (std::size_t i = 0; i < out.texels.size(); ++i) {
        EXPECT_EQ(rgb.texels[i * 3], rgb.texels[i * 3 + 1]);
        EXPECT_EQ(rgb.texels[i * 3], rgb.texels[i * 3 + 2]);
        out.texels[i] = rgb.texels[i * 3];
    }
    return out;
}

std::vector<bool> widths() {
    set_wide_kernels(true);
    if (!wide_kernels()) std::printf("note: this CPU has no AVX2: only the baseline kernels are tested\n");
    return wide_kernels() ? std::vector<bool>{false, true} : std::vector<bool>{false};
}

}  // namespace

TEST(GreyTexture, BlursAsEachChannelOfItsRgbTexture) {
    int checked = 0;
    for (const Rect r : {Rect{0, 0, 1, 1}, Rect{-3, 5, 2, 7}, Rect{10, -4, 37, 5}, Rect{-9, 2, 301, 23}})
        for (int radius : {0, 1, 2, 3, 4, 7, 8, 20}) {
            const LightTexture grey = random_grey(r, std::uint64_t(r.w * 31 + radius));
            const LightTexture want = first_channel(box_blur_reference(rgb_texture(grey), radius));
            for (bool wide : widths()) {
                set_wide_kernels(wide);
                const LightTexture got = box_blur(grey, radius);
                EXPECT_EQ(got.channels, 1);
                EXPECT_EQ(got.texels, want.texels) << r.w << "x" << r.h << " r " << radius << " wide " << wide;
                // And a part of it, into a texture already holding other values.
                LightTexture part(r, 1);
                const Rect z{r.x + r.w / 3, r.y + r.h / 4, std::max(1, r.w / 2), std::max(1, r.h / 2)};
                box_blur_into(grey, radius, z, part);
                for (int y = r.y; y < r.y + r.h; ++y)
                    for (int x = r.x; x < r.x + r.w; ++x)
                        ASSERT_EQ(part.value(x, y, 0), z.contains(x, y) ? want.value(x, y, 0) : 0) << x << "," << y;
            }
            set_wide_kernels(true);
            ++checked;
        }
    EXPECT_EQ(checked, 32);
}

TEST(GreyTexture, DarkStretchesBlurToTheReferenceInBothLayouts) {
    // Mostly unlit textures with lit patches: the AVX2 blur's dark steps
    // (zeros in, zeros out, nothing else touched) start, stop and resume,
    // and a region's dark steps overwrite what the output held before.
    for (int channels : {1, 3})
        for (int radius : {1, 2, 3})
            for (std::uint64_t seed : {1u, 2u, 3u}) {
                const Rect r{-5, 3, 333, 61};
                LightTexture t(r, channels);
                Pcg32 rng(seed * 7 + std::uint64_t(radius));
                for (int patch = 0; patch < 6; ++patch) {
                    const int px = int(rng.below(std::uint32_t(r.w))), py = int(rng.below(std::uint32_t(r.h)));
                    const int pw = 1 + int(rng.below(70)), ph = 1 + int(rng.below(20));
                    for (int y = py; y < std::min(r.h, py + ph); ++y)
                        for (int x = px; x < std::min(r.w, px + pw); ++x)
                            for (int c = 0; c < channels; ++c)
                                t.texels[(std::size_t(y) * r.w + x) * channels + c] = std::uint8_t(1 + rng.below(255));
                }
                const LightTexture want = box_blur_reference(t, radius);
                for (bool wide : widths()) {
                    set_wide_kernels(wide);
                    LightTexture out(r, channels);
                    std::fill(out.texels.begin(), out.texels.end(), std::uint8_t(77));
                    box_blur_into(t, radius, r, out);
                    EXPECT_EQ(out.texels, want.texels) << channels << " channels, r " << radius << " seed " << seed << " wide " << wide;
                    const Rect part{r.x + 40, r.y + 9, 250, 30};
                    std::fill(out.texels.begin(), out.texels.end(), std::uint8_t(77));
                    box_blur_into(t, radius, part, out);
                    for (int y = r.y; y < r.y + r.h; ++y)
                        for (int x = r.x; x < r.x + r.w; ++x)
                            for (int c = 0; c < channels; ++c)
                                ASSERT_EQ(out.value(x, y, c), part.contains(x, y) ? want.value(x, y, c) : 77)
                                    << x << "," << y << " " << channels << " channels, r " << radius << " wide " << wide;
                }
                set_wide_kernels(true);
            }
}

TEST(GreyTexture, ComposesAsItsRgbTextureInEveryVariant) {
    // Every light value against varied colours, in a texture covering part
    // of the view (the rest reads unlit), rows of every length mod 8.
    const Rect view{-7, 3, 259, 37};
    Image colour(view.w, view.h);
    Pcg32 rng(4);
    for (std::uint8_t& v : colour.rgba) v = std::uint8_t(rng.below(256));
    for (int i = 0; i < view.w * view.h; i += 5) colour.rgba[std::size_t(i) * 4 + 3] = 0;  // some transparent
    LightTexture grey({view.x + 3, view.y - 4, 256 + 1, 40}, 1);
    for (std::size_t i = 0; i < grey.texels.size(); ++i) grey.texels[i] = std::uint8_t((i * 7 + i / 257) & 255);
    const LightTexture rgb = rgb_texture(grey);
    int variants = 0;
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
        for (LightMix mix : {LightMix::luminance, LightMix::surface})
            for (bool dark : {false, true})
                for (double ac : {0.0, 0.4, 1.0}) {
                    Params p;
                    p.mode = mode, p.light_mix = mix, p.dark_unlit = dark, p.ambient_clarity = ac;
                    const Image want = composite_reference(colour, view, rgb, p);
                    EXPECT_EQ(composite_reference(colour, view, grey, p).rgba, want.rgba);
                    for (bool wide : widths()) {
                        set_wide_kernels(wide);
                        EXPECT_EQ(composite(colour, view, grey, p).rgba, want.rgba)
                            << to_string(mode) << " mix " << int(mix) << " dark " << dark << " ac " << ac << " wide " << wide;
                    }
                    set_wide_kernels(true);
                    ++variants;
                }
    EXPECT_EQ(variants, 36);
}

TEST(GreyTexture, AccumulatesAsItsRgbTexture) {
    for (Mode mode : {Mode::light, Mode::shadow})
        for (const Light& light : {Light{0, 0}, Light{0, 0, {}, {}, 128, 128, 128, 0.7}})
            for (int width : {1, 31, 32, 33, 257}) {
                const Rect area{-3, 2, width, 5};
                LightMask m;
                m.clip = area;
                m.cx = area.x + width / 2, m.cy = area.y + 2;
                Pcg32 rng(std::uint64_t(12 + width));
                m.value.resize(std::size_t(area.w) * area.h);
                for (std::uint8_t& v : m.value) v = rng.below(3) ? std::uint8_t(rng.below(256)) : 0;
                if (mode == Mode::shadow) {
                    m.reached.resize(m.value.size());
                    for (std::uint8_t& r : m.reached) r = std::uint8_t(rng.below(2));
                }
                Params p;
                p.mode = mode;
                const LightTexture before = random_grey({area.x - 2, area.y - 1, area.w + 5, area.h + 2}, 13);
                LightTexture want = rgb_texture(before);
                accumulate_light(want, m, light, p);
                for (bool wide : widths()) {
                    set_wide_kernels(wide);
                    LightTexture got = before;
                    accumulate_light(got, m, light, p);
                    EXPECT_EQ(got.texels, first_channel(want).texels) << width << " " << to_string(mode) << " wide " << wide;
                }
                set_wide_kernels(true);
            }
}

TEST(GreyTexture, FramesOfGreyLightsEqualFramesInRgbAndSwitchWhenALightTakesColour) {
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 700, 400};
    for (Mode mode : {Mode::light, Mode::shadow})
        for (int threads : {1, 2}) {
            Scene s;
            s.params.mode = mode;
            s.params.area_a = s.params.area_b = 90;
            s.params.blur_radius = 2;
            s.params.trace_every = 2;
            for (int i = 0; i < 6; ++i) s.lights.push_back(Light{cam.x + 60 + 110.0 * i, cam.y + 80 + 45.0 * i});
            s.lights[1].r = s.lights[1].g = s.lights[1].b = 90;  // grey, not white
            s.lights[2].intensity = 0.6;
            FrameState grey, rgb;
            grey.options.threads = rgb.options.threads = threads;
            rgb.options.grey_when_lights_are = false;
            for (long f = 0; f < 10; ++f) {
                SCOPED_TRACE("frame " + std::to_string(f) + ", " + std::string(to_string(mode)) + ", " + std::to_string(threads) + " threads");
                if (f > 0) s.lights[std::size_t(f % 6)].x += 9;
                if (f == 4) s.lights[3].g = 40;  // a coloured light: r, g, b from here
                if (f == 6) s.lights[3].g = 255;  // grey again (on trace frames: trace_every 2)
                if (f == 8) s.params.blur_radius = 0;
                render_frame(grey, w, s, cam, f);
                render_frame(rgb, w, s, cam, f);
                const bool all_grey = f < 4 || f >= 6;
                ASSERT_EQ(grey.traced.channels, all_grey ? 1 : 3);
                ASSERT_EQ(rgb.traced.channels, 3);
                ASSERT_EQ(rgb_texture(grey.traced).texels, rgb.traced.texels);
                ASSERT_EQ(rgb_texture(grey.light).texels, rgb.light.texels);
                ASSERT_EQ(grey.final.rgba, rgb.final.rgba);
            }
            std::size_t lit = 0;
            for (std::uint8_t v : grey.traced.texels) lit += v > 0;
            EXPECT_GT(lit, 10000u);  // the scene is lit: the comparison means something
        }
}

TEST(LightTexture, whiteLightGivesThePapersValuesAndLightsSaturate) {
    const Rect area{-4, -4, 9, 9};  // a light of half-extents 4 at the origin
    LightMask m = trace_light(Mask(area), 0, 0, 4, 4, Params{}, area);
    LightTexture tex(area);
    Light white;
    accumulate_light(tex, m, white, Params{});
    EXPECT_EQ(tex.at(0, 0)[0], 255);
    EXPECT_EQ(tex.at(3, -2)[1], 255 / 4);
    EXPECT_EQ(tex.at(-4, 4)[2], 255 / 5);
    accumulate_light(tex, m, white, Params{});  // a second light on the same spot
    EXPECT_EQ(tex.at(0, 0)[0], 255);            // saturates, never wraps
    EXPECT_EQ(tex.at(3, -2)[0], 2 * (255 / 4));
    Light red;
    red.g = red.b = 0;
    LightTexture t2(area);
    accumulate_light(t2, m, red, Params{});
    EXPECT_EQ(t2.at(1, 1)[0], 127);
    EXPECT_EQ(t2.at(1, 1)[1], 0);
    Light dim;
    dim.intensity = 0.5;
    LightTexture t3(area);
    accumulate_light(t3, m, dim, Params{});
    EXPECT_EQ(t3.at(0, 0)[0], 128);  // round(255 * 0.5)
}

TEST(Accumulate, WhiteLightsAddTheirValueToEveryChannelSaturating) {
    LightMask m;
    m.clip = {0, 0, 4, 1};
    m.value = {0, 100, 200, 255};
    LightTexture tex({0, 0, 4, 1});
    Params p;
    const Light white{0, 0};
    accumulate_light(tex, m, white, p);
    accumulate_light(tex, m, white, p);
    const std::vector<std::uint8_t> want = {0, 0, 0, 200, 200, 200, 255, 255, 255, 255, 255, 255};
    EXPECT_EQ(tex.texels, want);
}

TEST(Accumulate, WhiteRowsWiderThanAVectorSaturateInBothBuilds) {
    // Rows of every kind of width (under, at and over 16 and 32 texels, a
    // light's 257), over a texture with values already in it.
    for (int width : {1, 15, 16, 17, 31, 32, 33, 37, 63, 64, 65, 100, 257}) {
        SCOPED_TRACE(width);
        const Rect area{-3, 2, width, 5};
        LightMask m;
        m.clip = area;
        Pcg32 rng(std::uint64_t(12 + width));
        m.value.resize(std::size_t(area.w) * area.h);
        for (std::uint8_t& v : m.value) v = std::uint8_t(rng.below(256));
        const LightTexture before = random_texture({area.x - 2, area.y - 1, area.w + 5, area.h + 2}, 13);
        for (bool wide : both_widths()) {
            set_wide_kernels(wide);
            LightTexture tex = before;
            accumulate_light(tex, m, Light{0, 0}, Params{});
            for (int y = tex.rect.y; y < tex.rect.y + tex.rect.h; ++y)
                for (int x = tex.rect.x; x < tex.rect.x + tex.rect.w; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const int add = area.contains(x, y) ? m.value[std::size_t(y - area.y) * area.w + (x - area.x)] : 0;
                        ASSERT_EQ(tex.at(x, y)[c], std::min(255, before.at(x, y)[c] + add)) << x << "," << y << " wide " << wide;
                    }
        }
        set_wide_kernels(true);
    }
}
