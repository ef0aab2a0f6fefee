// The lighting pipeline (paper 3.2 and Algorithm 3), pixel-exact where the
// paper is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/opacity_map.hpp"
#include "test_util.hpp"

using namespace isolux;
using P = std::pair<long, long>;

namespace {

std::vector<P> line(long x0, long y0, long x1, long y1) {
    std::vector<P> out;
    for (BresenhamRay r(x0, y0, x1, y1); !r.done(); r.step()) out.push_back({r.x, r.y});
    return out;
}

std::vector<P> flip(std::vector<P> v, int sx, int sy, bool swap_xy = false) {
    for (P& p : v) {
        if (swap_xy) std::swap(p.first, p.second);
        p.first *= sx;
        p.second *= sy;
    }
    return v;
}

Rect area_rect(int cx, int cy, int a, int b) { return {cx - a, cy - b, 2 * a + 1, 2 * b + 1}; }

Mask random_obstacles(Rect r, int percent, std::uint64_t seed) {
    Mask m(r);
    Pcg32 rng(seed);
    for (auto& b : m.bits) b = int(rng.below(100)) < percent;
    return m;
}

Params with(Mode mode, Rays rays = Rays::border, int k = 1) {
    Params p;
    p.mode = mode;
    p.rays = rays;
    p.ray_skip = k;
    return p;
}

}  // namespace

TEST(Bresenham, matchesHandWorkedLinesInEveryOctant) {
    // (0,0) -> (5,2): numerator starts at 5>>1 = 2 and gains 2 a step; a
    // diagonal step whenever it reaches 5 (then loses 5).
    const std::vector<P> shallow = {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}};
    // (0,0) -> (2,5): the steep case swaps the roles (dx2 = 0, dy2 = 1).
    const std::vector<P> steep = {{0, 0}, {0, 1}, {1, 2}, {1, 3}, {2, 4}, {2, 5}};
    EXPECT_EQ(line(0, 0, 5, 2), shallow);
    EXPECT_EQ(line(0, 0, -5, 2), flip(shallow, -1, 1));
    EXPECT_EQ(line(0, 0, 5, -2), flip(shallow, 1, -1));
    EXPECT_EQ(line(0, 0, -5, -2), flip(shallow, -1, -1));
    EXPECT_EQ(line(0, 0, 2, 5), steep);
    EXPECT_EQ(line(0, 0, -2, 5), flip(steep, -1, 1));
    EXPECT_EQ(line(0, 0, 2, -5), flip(steep, 1, -1));
    EXPECT_EQ(line(0, 0, -2, -5), flip(steep, -1, -1));
    EXPECT_EQ(line(10, 20, 13, 23), (std::vector<P>{{10, 20}, {11, 21}, {12, 22}, {13, 23}}));  // diagonal
    EXPECT_EQ(line(0, 0, 3, 0), (std::vector<P>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
    EXPECT_EQ(line(0, 0, 0, -2), (std::vector<P>{{0, 0}, {0, -1}, {0, -2}}));
    EXPECT_EQ(line(4, 4, 4, 4), (std::vector<P>{{4, 4}}));  // zero length: the centre alone
}

TEST(Falloff, isThePapersIntegerFunction) {
    EXPECT_EQ(falloff(0, 1.0), 255);
    EXPECT_EQ(falloff(1, 1.0), 127);
    EXPECT_EQ(falloff(2, 1.0), 85);
    EXPECT_EQ(falloff(254, 1.0), 1);
    EXPECT_EQ(falloff(255, 1.0), 0);
    EXPECT_EQ(falloff(2, 2.0), 127);   // 255 / (1 + 2/2)
    EXPECT_EQ(falloff(8, 8.0), 127);
    EXPECT_EQ(falloff(0, 0.5), 255);
}

TEST(Border, visitsEachBorderPixelOnce) {
    for (auto [a, b] : {std::pair{3, 2}, {0, 0}, {0, 4}, {5, 0}, {1, 1}, {10, 10}}) {
        auto border = border_offsets(a, b);
        std::set<std::pair<int, int>> unique(border.begin(), border.end());
        EXPECT_EQ(unique.size(), border.size()) << a << "x" << b << ": a corner counted twice";
        long expected = (a == 0 || b == 0) ? long(2 * a + 1) * (2 * b + 1) : 2L * (2 * a + 1) + 2L * (2 * b + 1) - 4;
        EXPECT_EQ(long(border.size()), expected) << a << "x" << b;
        for (auto [x, y] : border) EXPECT_TRUE(std::abs(x) == a || std::abs(y) == b);
    }
}

TEST(Trace, aWallStopsTheLight) {
    Rect area = area_rect(0, 0, 10, 10);
    Mask wall(area);
    for (int y = -10; y <= 10; ++y) wall.set(5, y);
    for (Rays rays : {Rays::border, Rays::every_pixel}) {
        LightMask m = trace_light(wall, 0, 0, 10, 10, with(Mode::light, rays), area);
        for (int y = -10; y <= 10; ++y)
            for (int x = -10; x <= 10; ++x)
                EXPECT_EQ(m.value[(y + 10) * 21 + (x + 10)] > 0, x < 5) << x << "," << y;
    }
}

TEST(Trace, equalsTheUnionOfThePapersRays) {
    // The tracer against a literal transcription of Algorithm 2, ray by ray:
    // nothing behind an obstacle along a traced ray is lit, and nothing else.
    for (int trial = 0; trial < 12; ++trial) {
        const int a = 3 + trial, b = 2 + (trial * 7) % 11, k = 1 + trial % 3;
        Rect area = area_rect(40, -7, a, b);
        Mask obstacles = random_obstacles(area, 8 + trial, trial);
        obstacles.set(40, -7, false);
        Params p = with(Mode::light, Rays::border, k);
        LightMask m = trace_light(obstacles, 40, -7, a, b, p, area);
        std::vector<std::uint8_t> ref(m.value.size(), 0);
        auto border = border_offsets(a, b);
        for (std::size_t i = 0; i < border.size(); i += k)
            trace_light_ray_paper(obstacles, 40, -7, 40 + border[i].first, -7 + border[i].second, area, ref);
        // The transcription writes the intensity: the same pixels, valued 255/(1+d).
        LightTexture tex(area);
        accumulate_light(tex, m, Light{}, p);
        for (std::size_t i = 0; i < ref.size(); ++i) {
            EXPECT_EQ(m.value[i], ref[i]) << "trial " << trial;  // the same intensities
            EXPECT_EQ(tex.texels[i * 3], ref[i]) << "trial " << trial;
        }
        for (std::size_t i = 0; i < m.value.size(); ++i)
            if (obstacles.bits[i]) {
                EXPECT_EQ(m.value[i], 0) << "an obstacle pixel is lit";
            }
    }
}

TEST(Trace, lightAndShadowAreComplementaryInsideTheArea) {
    for (Rays rays : {Rays::border, Rays::every_pixel}) {
        for (auto [a, b] : {std::pair{12, 12}, {20, 6}, {4, 17}}) {
            Rect area = area_rect(0, 0, a, b);
            Mask obstacles = random_obstacles(area, 6, a * 31 + b);
            obstacles.set(0, 0, false);
            LightMask lit = trace_light(obstacles, 0, 0, a, b, with(Mode::light, rays), area);
            LightMask shadow = trace_light(obstacles, 0, 0, a, b, with(Mode::shadow, rays), area);
            LightTexture tl(area), ts(area), tf(area);
            Light white;
            accumulate_light(tl, lit, white, with(Mode::light));
            accumulate_light(ts, shadow, white, with(Mode::shadow));
            LightMask flat = trace_light(obstacles, 0, 0, a, b, with(Mode::flat, rays), area);
            accumulate_light(tf, flat, white, with(Mode::flat));
            for (std::size_t i = 0; i < lit.value.size(); ++i) {
                const bool in_shadow = shadow.reached[i] && !shadow.lit(i);
                ASSERT_NE(lit.lit(i), in_shadow) << "pixel " << i << " is in both or neither";
                ASSERT_EQ(tl.texels[i * 3] + ts.texels[i * 3], tf.texels[i * 3]);
            }
        }
    }
}

TEST(Trace, flatModeIgnoresObstacles) {
    Rect area = area_rect(3, 3, 15, 9);
    Mask obstacles = random_obstacles(area, 30, 9);
    LightMask flat = trace_light(obstacles, 3, 3, 15, 9, with(Mode::flat), area);
    LightMask open = trace_light(Mask(area), 3, 3, 15, 9, with(Mode::light), area);
    EXPECT_EQ(flat.value, open.value);
}

TEST(Trace, borderRaysEqualTheEveryPixelReferenceOnAnEmptyMap) {
    for (auto [a, b] : {std::pair{128, 128}, {7, 3}, {3, 7}, {40, 1}, {0, 5}, {5, 0}, {0, 0}, {1, 1}, {64, 33}}) {
        Rect area = area_rect(0, 0, a, b);
        Mask empty(area);
        LightMask border = trace_light(empty, 0, 0, a, b, with(Mode::light, Rays::border, 1), area);
        LightMask every = trace_light(empty, 0, 0, a, b, with(Mode::light, Rays::every_pixel), area);
        EXPECT_EQ(border.value, every.value) << a << "x" << b;
        const auto lit = test::lit_of(every);
        EXPECT_EQ(std::count(lit.begin(), lit.end(), 1), long(area.w) * area.h);
    }
}

TEST(Trace, skippingRaysLightsASubset) {
    Rect area = area_rect(0, 0, 30, 30);
    Mask empty(area);
    LightMask all = trace_light(empty, 0, 0, 30, 30, with(Mode::light, Rays::border, 1), area);
    LightMask some = trace_light(empty, 0, 0, 30, 30, with(Mode::light, Rays::border, 4), area);
    long n_all = 0, n_some = 0;
    const auto all_lit = test::lit_of(all), some_lit = test::lit_of(some);
    for (std::size_t i = 0; i < all_lit.size(); ++i) {
        EXPECT_LE(some_lit[i], all_lit[i]);
        n_all += all_lit[i];
        n_some += some_lit[i];
    }
    EXPECT_LT(n_some, n_all);
    EXPECT_GT(n_some, n_all / 4);
}

TEST(Trace, aLightInsideAnObstacleLightsNothing) {
    Rect area = area_rect(0, 0, 5, 5);
    Mask m(area);
    m.set(0, 0);
    LightMask t = trace_light(m, 0, 0, 5, 5, with(Mode::light), area);
    EXPECT_EQ(std::count(t.value.begin(), t.value.end(), 0), long(t.value.size()));
}

TEST(LightTexture, whiteLightGivesThePapersValuesAndLightsSaturate) {
    Rect area = area_rect(0, 0, 4, 4);
    LightMask m = trace_light(Mask(area), 0, 0, 4, 4, with(Mode::light), area);
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

TEST(OpacityCorrection, addsSpritesAboveTheCentreAndSubtractsThoseBelow) {
    // Two 3x3 opaque sprites: one standing above the light's centre (its
    // ground y < the centre's), one below it.
    Tileset ts;
    Sprite s;
    s.kind = SpriteKind::overlay;
    s.image = test::sprite_from({"###", "###", "###"});
    s.anchor_x = 1;
    s.anchor_y = 2;
    ts.sprites.push_back(s);
    PlacedMap placed;
    placed.first_overlay = 0;
    placed.instances.push_back({0, -6, -6, -5, -4, 0, 3, 3});  // ground y -4 < 0: above
    placed.instances.push_back({0, 2, 1, 3, 3, 1, 3, 3});      // ground y 3 >= 0: below
    std::vector<Mask> opacity = {opacity_map(ts.sprites[0].image, 0.5)};
    Rect area = area_rect(0, 0, 8, 8);
    Mask wall(area);
    for (int x = -8; x <= 8; ++x) wall.set(x, -2);  // shadows everything above row -2
    LightMask m = trace_light(wall, 0, 0, 8, 8, with(Mode::light), area);
    auto lit = [&](int x, int y) { return m.value[(y + 8) * 17 + (x + 8)] > 0 ? 1 : 0; };
    ASSERT_EQ(lit(-5, -5), 0);
    ASSERT_EQ(lit(3, 2), 1);
    EXPECT_EQ(correct_with_opacity_maps(m, placed, opacity), 2);
    for (int y = -6; y <= -4; ++y)
        for (int x = -6; x <= -4; ++x) EXPECT_EQ(lit(x, y), 1) << "added " << x << "," << y;
    for (int y = 1; y <= 3; ++y)
        for (int x = 2; x <= 4; ++x) EXPECT_EQ(lit(x, y), 0) << "subtracted " << x << "," << y;
    EXPECT_EQ(lit(0, 1), 1);    // untouched floor stays lit
    EXPECT_EQ(lit(0, -5), 0);   // untouched shadow stays dark
    // The added pixels get the light's intensity at their distance.
    LightTexture tex(area);
    accumulate_light(tex, m, Light{}, Params{});
    EXPECT_EQ(tex.at(-5, -5)[0], 255 / 6);
}

TEST(Blur, isTheClampedBoxMean) {
    LightTexture t(Rect{0, 0, 3, 1});
    const std::uint8_t v[3] = {0, 90, 180};
    for (int x = 0; x < 3; ++x)
        for (int k = 0; k < 3; ++k) t.texels[x * 3 + k] = v[x];
    LightTexture b = box_blur(t, 1);
    // Clamped at the edges: x=0 sees 0,0,90; x=1 sees 0,90,180; x=2 sees 90,180,180.
    EXPECT_EQ(b.texels[0], 30);
    EXPECT_EQ(b.texels[3], 90);
    EXPECT_EQ(b.texels[6], 150);
    // A radius far larger than the texture: the clamp weights the edges.
    LightTexture big = box_blur(t, 50);
    // Window of 101 over x in [-50, 50+x]: 51 - x texels of 0 ... exact mean.
    const int n = 101;
    const int sum0 = 0 * 51 + 90 * 1 + 180 * 49;
    EXPECT_EQ(big.texels[0], (sum0 + n / 2) / n);
    EXPECT_EQ(box_blur(t, 0).texels, t.texels);
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

namespace {
const World& test_world() {
    static World w = [] {
        Scene s;
        s.width = s.height = 8;
        return make_world(test::default_tileset(), s);
    }();
    return w;
}
}  // namespace

TEST(Frame, retracesOnFrames0LAnd2LWhenLightsMove) {
    Scene s;
    s.params.trace_every = 3;
    s.params.area_a = s.params.area_b = 40;
    FrameState st;
    std::vector<long> traced;
    for (long f = 0; f < 10; ++f) {
        s.lights = {Light{500.0 + 2 * f, 300.0}};  // a light carried by a walking character
        FrameReport r = render_frame(st, test_world(), s, Camera{0, 0, 0, 0}, f);
        if (r.ran_stage(Stage::trace)) traced.push_back(f);
        EXPECT_TRUE(r.ran_stage(Stage::composite) || !r.ran_stage(Stage::trace));
    }
    EXPECT_EQ(traced, (std::vector<long>{0, 3, 6, 9}));
}

TEST(Frame, theShiftedTextureEqualsAFreshTraceOfTheMovedView) {
    for (int blur : {0, 2}) {
        Scene s;
        s.params.trace_every = 4;
        s.params.blur_radius = blur;
        s.params.area_a = s.params.area_b = 60;
        s.lights = {Light{520, 310}, Light{700, 380}};
        FrameState moving;
        Camera cam{300, 150, 400, 300};
        render_frame(moving, test_world(), s, cam, 0);
        ASSERT_GT(*std::max_element(moving.light.texels.begin(), moving.light.texels.end()), 100);
        for (long f = 1; f < 4; ++f) {
            cam.x += 7;
            cam.y += 4.5;  // sub-pixel steps too
            FrameReport r = render_frame(moving, test_world(), s, cam, f);
            EXPECT_FALSE(r.ran_stage(Stage::trace)) << f;
            EXPECT_TRUE(r.ran_stage(Stage::shift)) << f;
            FrameState fresh;
            render_frame(fresh, test_world(), s, cam, 0);
            EXPECT_EQ(moving.light.rect, fresh.light.rect);
            EXPECT_EQ(moving.light.texels, fresh.light.texels) << "blur " << blur << " frame " << f;
            EXPECT_EQ(moving.final.rgba, fresh.final.rgba);
        }
    }
}

TEST(Frame, aStillFrameRunsNoStage) {
    Scene s;
    s.lights = {Light{520, 310}};
    FrameState st;
    render_frame(st, test_world(), s, Camera{}, 0);
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 1);
    for (int k = 0; k < stage_count; ++k) EXPECT_FALSE(r.ran[k]) << to_string(Stage(k));
    s.params.ambient_clarity = 0.8;  // ambient clarity only re-composites
    r = render_frame(st, test_world(), s, Camera{}, 2);
    EXPECT_TRUE(r.ran_stage(Stage::composite));
    EXPECT_FALSE(r.ran_stage(Stage::trace));
    EXPECT_FALSE(r.ran_stage(Stage::obstacle_map));
    s.params.delta_y = 10;  // Δy rebuilds the obstacle map and retraces
    r = render_frame(st, test_world(), s, Camera{}, 3);
    EXPECT_TRUE(r.ran_stage(Stage::obstacle_map));
    EXPECT_TRUE(r.ran_stage(Stage::trace));
}

TEST(Frame, everyParameterChangesTheOutput) {
    Scene base;
    base.params.falloff_scale = 6;
    base.params.area_a = base.params.area_b = 100;
    base.lights = {Light{520, 330}, Light{760, 420}};
    auto render = [](const Scene& s) {
        FrameState st;
        render_frame(st, test_world(), s, Camera{}, 0);
        return st.final.rgba;
    };
    const auto reference = render(base);
    auto changed = [&](auto edit) {
        Scene s = base;
        edit(s.params);
        return render(s) != reference;
    };
    EXPECT_TRUE(changed([](Params& p) { p.delta_y = 6; }));
    EXPECT_TRUE(changed([](Params& p) { p.noise_window = 9; }));
    EXPECT_TRUE(changed([](Params& p) { p.ray_skip = 7; }));
    EXPECT_TRUE(changed([](Params& p) { p.area_a = 40; }));
    EXPECT_TRUE(changed([](Params& p) { p.area_b = 40; }));
    EXPECT_TRUE(changed([](Params& p) { p.ambient_clarity = 0.8; }));
    EXPECT_TRUE(changed([](Params& p) { p.opacity_threshold = 0.95; }));
    EXPECT_TRUE(changed([](Params& p) { p.blur_radius = 0; }));
    EXPECT_TRUE(changed([](Params& p) { p.falloff_scale = 1; }));
    EXPECT_TRUE(changed([](Params& p) { p.mode = Mode::shadow; }));
    EXPECT_TRUE(changed([](Params& p) { p.mode = Mode::flat; }));
    EXPECT_TRUE(changed([](Params& p) { p.dark_unlit = true; }));
    EXPECT_TRUE(changed([](Params& p) { p.rays = Rays::every_pixel; }));
}

TEST(Frame, lightsOutsideTheMapLightWhatTheyReach) {
    Scene s;
    s.params.area_a = s.params.area_b = 200;
    s.params.falloff_scale = 20;
    const Rect b = test_world().placed.bounds;
    s.lights = {Light{double(b.w + 50), double(b.h / 2)}};
    FrameState st;
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 0);
    EXPECT_EQ(r.lights_traced, 1);
    long lit = 0;
    for (std::uint8_t v : st.light.texels) lit += v > 0;
    EXPECT_GT(lit, 0);
    s.lights = {Light{1e8, 1e8}};  // far away: nothing to trace
    FrameState st2;
    r = render_frame(st2, test_world(), s, Camera{}, 0);
    EXPECT_EQ(r.lights_traced, 0);
}

TEST(Frame, anUnchangedLightIsNotTracedAgain) {
    Scene s;
    s.params.area_a = s.params.area_b = 50;
    s.params.falloff_scale = 6;
    s.lights = {Light{420, 260}, Light{600, 330}, Light{500, 300}};
    FrameState st;
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 0);
    EXPECT_EQ(r.lights_traced, 3);
    s.lights[1].x += 9;          // one light moves
    s.lights[2].r = 10;          // one changes colour only: no new rays needed
    r = render_frame(st, test_world(), s, Camera{}, 1);
    EXPECT_EQ(r.lights_traced, 1);
    EXPECT_EQ(r.lights_reused, 2);
    FrameState fresh;
    render_frame(fresh, test_world(), s, Camera{}, 0);
    EXPECT_EQ(st.final.rgba, fresh.final.rgba);
    s.params.ray_skip = 2;       // a tracing parameter: everything again
    r = render_frame(st, test_world(), s, Camera{}, 2);
    EXPECT_EQ(r.lights_traced, 3);
}

TEST(Frame, noLightsMeansNoTracingAndNoUpload) {
    Scene s;
    FrameState st;
    st.options.cpu_blur_and_composite = false;  // as the app runs it
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 0);
    EXPECT_FALSE(r.ran_stage(Stage::trace));
    EXPECT_FALSE(r.retraced);
    s.lights = {Light{400, 250}};
    r = render_frame(st, test_world(), s, Camera{}, 1);
    EXPECT_TRUE(r.retraced);
    EXPECT_EQ(r.dirty, st.traced.rect);  // a new texture: all of it
    s.lights.push_back(Light{600, 300});
    r = render_frame(st, test_world(), s, Camera{}, 2);
    EXPECT_EQ(r.lights_traced, 1);
    // Only the new light's area changed: the upload can be that small.
    EXPECT_EQ(r.dirty, intersect(light_area(s.lights[1], s.params), st.traced.rect));
    s.lights.clear();
    r = render_frame(st, test_world(), s, Camera{}, 3);
    EXPECT_TRUE(r.retraced);  // the lights' areas go dark
    EXPECT_FALSE(r.dirty.empty());
    r = render_frame(st, test_world(), s, Camera{}, 4);
    EXPECT_FALSE(r.retraced);
}

// ---------------------------------------------------------------- lights that look right (not in the paper)

TEST(LightLook, euclideanFalloffMakesRoundLightsAndEdgeFadeReachesZeroAtTheBorder) {
    Params p;
    p.falloff_scale = 8;
    const Mask clear(Rect{-40, -40, 81, 81});
    const Rect area{-20, -20, 41, 41};
    p.falloff_shape = FalloffShape::euclidean;
    LightMask m = trace_light(clear, 0, 0, 20, 20, p, area, true);
    shape_light(m, p);
    auto at = [&](const LightMask& l, int x, int y) { return int(l.value[std::size_t(y + 20) * 41 + (x + 20)]); };
    EXPECT_EQ(at(m, 0, 0), 255);
    EXPECT_EQ(at(m, 10, 10), int(255.0 / (1.0 + std::sqrt(200.0) / 8)));  // round: by the straight-line distance
    EXPECT_EQ(at(m, 14, 0), int(255.0 / (1.0 + 14.0 / 8)));
    EXPECT_LT(at(m, 10, 10), at(m, 10, 0));  // round: the diagonal is further
    Params square;
    square.falloff_scale = 8;
    const LightMask sq = trace_light(clear, 0, 0, 20, 20, square, area, true);
    EXPECT_EQ(at(sq, 10, 10), at(sq, 10, 0));  // the paper's square lights: the same
    p.edge_fade = true;
    LightMask f = trace_light(clear, 0, 0, 20, 20, p, area, true);
    shape_light(f, p);
    EXPECT_EQ(at(f, 0, 0), 255);
    EXPECT_LE(at(f, 20, 0), 255.0 / (1 + 20.0 / 8) / 21 + 1);  // 1/21 of the way left at the border
    EXPECT_EQ(at(f, 20, 20), 0);                               // the corner lies outside the ellipse
    // The paper's settings leave the traced values as they are.
    Params paper;
    LightMask q = trace_light(clear, 0, 0, 20, 20, paper, area, true), q2 = q;
    shape_light(q2, paper);
    EXPECT_EQ(q.value, q2.value);
}

TEST(LightLook, surfaceLightMixKeepsTheSpritesHue) {
    const double red[3] = {0.8, 0.0, 0.0}, white[3] = {1, 1, 1};
    double lum[3], surf[3];
    Params p;
    composite_pixel(red, white, p, lum);
    p.light_mix = LightMix::surface;
    composite_pixel(red, white, p, surf);
    EXPECT_GT(lum[1], 0.1);   // Algorithm 3 adds the light's white over a red sprite
    EXPECT_EQ(surf[1], 0.0);  // the sprite's own colour takes the light
    EXPECT_GT(surf[0], red[0] * std::sqrt(p.ambient_clarity));
    // In shadow mode a full shadow darkens by three quarters, never to black.
    p.mode = Mode::shadow;
    composite_pixel(red, white, p, surf);
    EXPECT_NEAR(surf[0], 0.8 * std::sqrt(p.ambient_clarity) * 0.25, 1e-12);
}
