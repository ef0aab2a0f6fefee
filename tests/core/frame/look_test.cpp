// The look a game ships (docs/guide.md, "Exposure and tone"): exposure sets
// the lamps apart from the night, and tone_map reinhard_knee rolls bright
// pools off toward their colour instead of clipping each channel to white.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "isolux/composite.hpp"
#include "isolux/frame.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/world.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {

Image render_final(const World& w, const Scene& s) {
    FrameState st;
    const Rect v = camera_view(s.camera, w);
    render_frame(st, w, s, Camera{double(v.x), double(v.y), v.w, v.h}, 0);
    return st.final;
}

// Of the pixels the lights brighten (a channel at least 8 levels over the
// same scene without lights): the share with a channel at 255 where the
// unlit pixel has none above 200 (burnt by the light), and their mean
// Rec. 709 luminance.
struct Pools {
    long brightened = 0;
    double burnt = 0, luminance = 0;
};

Pools pools(const Image& lit, const Image& unlit) {
    Pools p;
    long burnt = 0;
    for (std::size_t i = 0; i + 3 < lit.rgba.size(); i += 4) {
        bool brighter = false, at_top = false, was_bright = false;
        for (int k = 0; k < 3; ++k) {
            brighter |= int(lit.rgba[i + k]) - int(unlit.rgba[i + k]) >= 8;
            at_top |= lit.rgba[i + k] == 255;
            was_bright |= unlit.rgba[i + k] > 200;
        }
        if (!brighter) continue;
        ++p.brightened;
        burnt += at_top && !was_bright;
        p.luminance += 0.2126 * lit.rgba[i] + 0.7152 * lit.rgba[i + 1] + 0.0722 * lit.rgba[i + 2];
    }
    if (p.brightened) p.burnt = double(burnt) / double(p.brightened), p.luminance /= double(p.brightened);
    return p;
}

// HSV hue (degrees) and saturation of an RGB colour.
void hue_saturation(double r, double g, double b, double& hue, double& sat) {
    const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), d = mx - mn;
    sat = mx > 0 ? d / mx : 0;
    if (d <= 0) {
        hue = 0;
        return;
    }
    if (mx == r) hue = 60 * std::fmod((g - b) / d + 6, 6.0);
    else if (mx == g) hue = 60 * ((b - r) / d + 2);
    else hue = 60 * ((r - g) / d + 4);
}

double hue_distance(double a, double b) {
    const double d = std::fmod(std::abs(a - b), 360.0);
    return std::min(d, 360 - d);
}

}  // namespace

// The showcase (the README's first picture) with its exposure and curve
// against the same scene under Algorithm 3's clamp: no pool burns to white,
// and the pools stay about as bright.
TEST(Look, theShowcasesPoolsNeverBurnToWhite) {
    const Scene shipped = load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/showcase.json");
    ASSERT_EQ(shipped.params.tone_map, ToneMap::reinhard_knee);
    const World w = make_world(test::default_tileset(), shipped);
    Scene dark = shipped;
    dark.lights.clear();
    Scene clamped = shipped;
    clamped.params.tone_map = ToneMap::none;
    clamped.params.exposure = 1;
    const Image unlit = render_final(w, dark);
    const Pools now = pools(render_final(w, shipped), unlit), clip = pools(render_final(w, clamped), unlit);
    std::printf("showcase: burnt %.2f %% of %ld brightened pixels, mean luminance %.1f; clamped at exposure 1: "
                "burnt %.2f %% of %ld, mean luminance %.1f\n",
                100 * now.burnt, now.brightened, now.luminance, 100 * clip.burnt, clip.brightened, clip.luminance);
    EXPECT_GT(clip.burnt, 0.2) << "the clamp burns a quarter of the pools (the measure can fail)";
    EXPECT_LE(now.burnt, 0.01);
    EXPECT_GE(now.luminance, 0.8 * clip.luminance) << "the pools are not simply darker";
    EXPECT_GT(now.brightened, clip.brightened / 2);
}

// A saturated blue lamp on the default tileset's stone floor (the game
// preset at night): at the pool's centre and at half its radius the lit
// stone keeps the lamp's hue within 5 degrees and at least half its
// saturation. The clamp turns the centre cyan-white.
TEST(Look, aSaturatedLampKeepsItsHueOnStone) {
    Scene s;
    s.width = s.height = 8;
    for (std::int64_t r = 0; r < 8; ++r)
        for (std::int64_t c = 0; c < 8; ++c) s.edits.push_back(TileEdit{c, r, "stone", std::vector<std::string>{}});
    s.params = builtin_preset("game");
    s.params.ambient_clarity = 0.1;
    s.params.exposure = 1.5;
    s.params.area_a = s.params.area_b = 160;
    s.params.falloff_scale = 40;
    const World w = make_world(test::default_tileset(), s);
    const Rect v = camera_view(s.camera, w);
    Light lamp{v.x + v.w / 2.0, v.y + v.h / 2.0};
    lamp.r = 0x30, lamp.g = 0x50, lamp.b = 0xff;
    lamp.height = 40;
    s.lights = {lamp};
    double lamp_hue = 0, lamp_sat = 0;
    hue_saturation(lamp.r, lamp.g, lamp.b, lamp_hue, lamp_sat);
    // The mean colour of a 9 x 9 box (the stone's joints are darker).
    auto mean_hue = [&](const Image& im, int cx, int cy, double& hue, double& sat) {
        double sum[3] = {0, 0, 0};
        for (int y = cy - 4; y <= cy + 4; ++y)
            for (int x = cx - 4; x <= cx + 4; ++x)
                for (int k = 0; k < 3; ++k) sum[k] += im.at(x - v.x, y - v.y)[k];
        hue_saturation(sum[0], sum[1], sum[2], hue, sat);
    };
    const int cx = int(lamp.x), cy = int(lamp.y);
    const Image toned = render_final(w, s);
    for (const auto& [name, dx] : {std::pair{"centre", 0}, std::pair{"half radius", 80}}) {
        double hue = 0, sat = 0;
        mean_hue(toned, cx + dx, cy, hue, sat);
        std::printf("%s: hue %.1f (the lamp's %.1f), saturation %.2f (the lamp's %.2f)\n", name, hue, lamp_hue, sat, lamp_sat);
        EXPECT_LE(hue_distance(hue, lamp_hue), 5) << name;
        EXPECT_GE(sat, lamp_sat / 2) << name;
    }
    Scene clamped = s;
    clamped.params.tone_map = ToneMap::none;
    double hue = 0, sat = 0;
    mean_hue(render_final(w, clamped), cx, cy, hue, sat);
    std::printf("clamped centre: hue %.1f, saturation %.2f\n", hue, sat);
    EXPECT_GT(hue_distance(hue, lamp_hue), 5) << "the clamp shifts the hue (the measure can fail)";
}

// tone_knee on its own: an unlit pixel and a dim light are the clamp's,
// no channel reaches 1, the slope is continuous at the knee, the output
// only grows with the light, and the light keeps its ratios.
TEST(Look, theKneeKeepsDimLightAndNeverClips) {
    const double base[3] = {0.2, 0.3, 0.1};
    double out[3];
    const double none[3] = {0, 0, 0};
    tone_knee(base, none, out);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(out[k], base[k]);
    const double dim[3] = {0.1, 0.05, 0.2};  // the sum's top 0.4: under the knee (0.3 + 0.5 * 0.7)
    tone_knee(base, dim, out);
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(out[k], base[k] + dim[k]);
    // A blue light: the sum's blue channel is its highest from t = 0.4, and
    // passes the knee (0.3 + 0.5 * 0.7) at t = 0.55.
    const double colour[3] = {0.3, 0.5, 1.0};
    const double step = 0.001;
    double previous = base[2], slope_before = 1;
    for (int i = 1; i <= 20000; ++i) {
        const double t = i * step;  // the light from 0.001 to 20 times the colour
        const double add[3] = {colour[0] * t, colour[1] * t, colour[2] * t};
        tone_knee(base, add, out);
        EXPECT_LT(std::max({out[0], out[1], out[2]}), 1.0) << t;
        EXPECT_GT(out[2], previous) << t;
        // Its slope changes by little from one step to the next: no kink.
        const double slope = (out[2] - previous) / step;
        EXPECT_NEAR(slope, slope_before, 0.02) << t;
        slope_before = slope, previous = out[2];
        // The light's own ratios are kept: what it adds is the colour, scaled.
        EXPECT_NEAR((out[1] - base[1]) / colour[1], (out[2] - base[2]) / colour[2], 1e-9) << t;
    }
    EXPECT_GT(previous, 0.99) << "its highest channel nears 1 as the light grows";
}

// falloff_space ground: a light's distances are measured on the ground, a
// pixel's dy scaled by the tileset's tile width over its height r, so a
// round light's pool on screen is r times as wide as it is tall, for the
// default tileset's 128 x 64 diamonds, 64 x 32, 96 x 48 and a flatter 120 x 40.
// Measured on the traced texture of a whole frame (render_frame reads r from
// the world's tileset), as the half-widths where the light is at least 64.
TEST(Look, aGroundLightsPoolIsRTimesAsWideAsTall) {
    for (const auto& [tw, th] : {std::pair{128, 64}, std::pair{64, 32}, std::pair{96, 48}, std::pair{120, 40}}) {
        Tileset ts = test::default_tileset();
        ts.tile_width = tw;
        ts.tile_height = th;
        Scene s;
        s.width = s.height = 12;
        s.params.mode = Mode::flat;  // the pool's shape alone, nothing in its way
        s.params.falloff_shape = FalloffShape::euclidean;
        s.params.falloff_scale = 40;
        s.params.area_a = s.params.area_b = 200;
        const World w = make_world(ts, s);
        const Rect v = camera_view(s.camera, w);
        const std::int64_t cx = v.x + v.w / 2, cy = v.y + v.h / 2;
        s.lights = {Light{double(cx) + 0.5, double(cy) + 0.5}};
        auto half_extents = [&](FalloffSpace space, int& half_w, int& half_h) {
            Scene t = s;
            t.params.falloff_space = space;
            FrameState st;
            render_frame(st, w, t, Camera{double(cx - 250), double(cy - 250), 501, 501}, 0);
            auto at = [&](std::int64_t x, std::int64_t y) {
                return st.traced.texels[(std::size_t(y - st.traced.rect.y) * st.traced.rect.w + std::size_t(x - st.traced.rect.x)) *
                                        std::size_t(st.traced.channels)];
            };
            half_w = half_h = 0;
            while (at(cx + half_w + 1, cy) >= 64) ++half_w;
            while (at(cx, cy + half_h + 1) >= 64) ++half_h;
        };
        int sw = 0, sh = 0, gw = 0, gh = 0;
        half_extents(FalloffSpace::screen, sw, sh);
        half_extents(FalloffSpace::ground, gw, gh);
        const double r = double(tw) / th;
        std::printf("%dx%d: screen %d x %d, ground %d x %d (r %.2f)\n", tw, th, sw, sh, gw, gh, r);
        EXPECT_EQ(sw, sh) << "on the screen a round light is a circle";
        EXPECT_EQ(gw, sw) << "across, the ground's distance is the screen's";
        EXPECT_NEAR(double(gw) / gh, r, 0.05 * r) << tw << "x" << th;
    }
    // The game preset's lights: a round pool that fades out in an a x a/r box.
    const Params game = builtin_preset("game");
    EXPECT_EQ(game.falloff_space, FalloffSpace::ground);
    EXPECT_EQ(game.area_b * 2, game.area_a) << "b = a / r for the default tileset's r = 2";
}
