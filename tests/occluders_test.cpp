// Tracing against solids with height (core/src/occluder_map.cpp,
// sprite_solids.cpp, occluders.cpp, occluders_tree.cpp): shadows of spans
// worked out by hand, and the model measured against the 3D reference.
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "isolux/accuracy.hpp"
#include "isolux/error.hpp"
#include "isolux/hash.hpp"
#include "isolux/frame.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/occluders.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/solid.hpp"
#include "isolux/solid_estimate.hpp"
#include "test_util.hpp"

using namespace isolux;
using isolux::test::error_of;

namespace {

// Bare ground over `r`, with the span [lo, hi) over the pixels of `where`.
OccluderMap ground_with(Rect r, Rect where, float lo, float hi) {
    OccluderMap m;
    m.rect = r;
    m.spans.assign(std::size_t(r.w) * r.h, Spans{});
    for (int y = where.y; y < where.y + where.h; ++y)
        for (int x = where.x; x < where.x + where.w; ++x) m.spans[std::size_t(y - r.y) * r.w + (x - r.x)] = Spans{{lo, hi}, {}};
    m.surface.rect = r;
    m.surface.instance.assign(m.spans.size(), -1);
    m.surface.height.assign(m.spans.size(), 0.f);
    index_occluders(m);
    return m;
}

bool lit(const LightMask& m, int x, int y) { return m.value[std::size_t(y - m.clip.y) * m.clip.w + (x - m.clip.x)] != 0; }

Params wide() {
    Params p;
    p.falloff_scale = 1e6;  // no pixel of the area falls to 0 by distance
    return p;
}

const Rect area{-150, -10, 301, 21};

}  // namespace

// A canopy [20, 40) px high, 28 to 32 px out, under a light 60 px high: the
// ground beneath it is lit (the rays pass under it), its shadow falls from
// 28 * 60 / 40 = 42 to 32 * 60 / 20 = 96 px, and beyond it is lit again.
TEST(Occluders, aCanopyShadesTheGroundBetweenItsTwoProjections) {
    const OccluderMap m = ground_with(area, Rect{28, -4, 5, 9}, 20, 40);
    const LightMask l = trace_light_solids(m, 0, 0, 150, 10, 60, wide(), area);
    for (int x : {10, 30, 40, 100, 120, 149}) EXPECT_TRUE(lit(l, x, 0)) << x;
    for (int x : {45, 60, 80, 95}) EXPECT_FALSE(lit(l, x, 0)) << x;
    // On the other side of the light nothing is shaded.
    for (int x : {-30, -60, -90}) EXPECT_TRUE(lit(l, x, 0)) << x;
}

// A ground pixel keeps two spans with the gap between them; a third closes
// the narrowest gap; spans that meet are one.
TEST(Occluders, aGroundPixelKeepsTwoSpansAndClosesTheNarrowestGap) {
    Spans s;
    s.add(30, 80);  // a crown
    s.add(0, 10);   // a bush under it
    EXPECT_EQ(s.lower, (Span{0, 10}));
    EXPECT_EQ(s.upper, (Span{30, 80}));
    EXPECT_FALSE(s.holds(20));  // the gap
    EXPECT_TRUE(s.holds(5));
    EXPECT_TRUE(s.holds(50));
    s.add(8, 12);  // meets the bush
    EXPECT_EQ(s.lower, (Span{0, 12}));
    s.add(90, 95);  // a third: the gap 80..90 is narrower than 12..30
    EXPECT_EQ(s.lower, (Span{0, 12}));
    EXPECT_EQ(s.upper, (Span{30, 95}));
    s.add(14, 16);  // 12..14 is the narrowest now
    EXPECT_EQ(s.lower, (Span{0, 16}));
    EXPECT_EQ(s.upper, (Span{30, 95}));
    Spans one;
    one.add(5, 6);
    EXPECT_TRUE(one.any());
    EXPECT_FALSE(one.upper.any());
}

// A crown [40, 80) over a bush [0, 10) on the same ground pixels, 28 to 32
// px out, a light 30 px high: the bush shades the ground from 28 to
// 32 * 30 / 20 = 48 px out, the crown (above the light) nothing, so beyond
// 48 px the ground is lit through the gap, where one span holding both,
// [0, 80), would shade it to the border.
TEST(Occluders, raysPassThroughTheGapBetweenTwoSpans) {
    OccluderMap m = ground_with(area, Rect{28, -4, 5, 9}, 40, 80);
    for (int y = -4; y < 5; ++y)
        for (int x = 28; x < 33; ++x) m.spans[std::size_t(y - area.y) * area.w + std::size_t(x - area.x)].add(0, 10);
    index_occluders(m);
    const LightMask l = trace_light_solids(m, 0, 0, 150, 10, 30, wide(), area);
    EXPECT_FALSE(lit(l, 40, 0));
    EXPECT_TRUE(lit(l, 60, 0));
    EXPECT_TRUE(lit(l, 120, 0));
    // A single span holding both shades everything beyond it (its top is above the light).
    const LightMask hull = trace_light_solids(ground_with(area, Rect{28, -4, 5, 9}, 0, 80), 0, 0, 150, 10, 30, wide(), area);
    EXPECT_FALSE(lit(hull, 60, 0));
    EXPECT_FALSE(lit(hull, 120, 0));
}

// A trunk standing on the ground: its shadow ends at s H / (H - top), shorter
// for a higher light; one as tall as the light shades to the area's border.
TEST(Occluders, aHigherLightCastsAShorterShadowAndATallSolidShadesToTheBorder) {
    const OccluderMap trunk = ground_with(area, Rect{28, -4, 5, 9}, 0, 20);
    const LightMask low = trace_light_solids(trunk, 0, 0, 150, 10, 40, wide(), area);   // to 30 * 40 / 20 = 60
    const LightMask high = trace_light_solids(trunk, 0, 0, 150, 10, 80, wide(), area);  // to 30 * 80 / 60 = 40
    EXPECT_FALSE(lit(low, 30, 0));  // the trunk's own ground
    EXPECT_FALSE(lit(low, 50, 0));
    EXPECT_TRUE(lit(high, 50, 0));
    EXPECT_FALSE(lit(high, 36, 0));
    EXPECT_TRUE(lit(low, 70, 0));
    const OccluderMap wall = ground_with(area, Rect{28, -4, 5, 9}, 0, 80);
    const LightMask under = trace_light_solids(wall, 0, 0, 150, 10, 60, wide(), area);
    for (int x : {40, 90, 149}) EXPECT_FALSE(lit(under, x, 0)) << x;
}

// A sprite pixel shows a point 20 px up over the ground 60 px out, behind a
// wall 30 px high 30 px out: a light 25 px high is hidden from it (the
// segment passes the wall at 22.5 px), one 100 px high is not (at 60 px).
TEST(Occluders, aSpritePixelIsLitByThePointItShows) {
    const Rect r{-150, -30, 301, 41};
    OccluderMap m = ground_with(r, Rect{28, -4, 5, 9}, 0, 30);
    // Screen pixel (60, -20) shows a sprite's point 20 px up: its ground point is (60, 0).
    const std::size_t sprite = std::size_t(-20 - r.y) * r.w + (60 - r.x);
    m.surface.instance[sprite] = 0;
    m.surface.height[sprite] = 20;
    index_occluders(m);
    LightMask low = trace_light_solids(m, 0, 0, 150, 30, 25, wide(), r);
    LightMask high = trace_light_solids(m, 0, 0, 150, 30, 100, wide(), r);
    EXPECT_TRUE(lit(high, 60, -20));  // the ground pass takes every pixel for ground
    light_sprite_points(low, m, 25, wide());
    light_sprite_points(high, m, 100, wide());
    EXPECT_FALSE(lit(low, 60, -20));
    EXPECT_TRUE(lit(high, 60, -20));
    // The ground at (60, 0): in the wall's shadow under the low light (a wall
    // as tall as the light shades to the border), lit under the high one
    // (its shadow ends at 30 * 100 / 70 = 43 px).
    EXPECT_FALSE(lit(low, 60, 0));
    EXPECT_TRUE(lit(high, 60, 0));
    // In shadow mode every pixel of the area is reached.
    Params shadow = wide();
    shadow.mode = Mode::shadow;
    LightMask s = trace_light_solids(m, 0, 0, 150, 30, 25, shadow, r);
    light_sprite_points(s, m, 25, shadow);
    ASSERT_EQ(s.reached.size(), s.value.size());
    EXPECT_EQ(std::count(s.reached.begin(), s.reached.end(), 1), long(s.value.size()));
    EXPECT_EQ(s.value, low.value);
}

// A tileset without shapes cannot be traced by its shapes: refused naming the sprite.
TEST(Occluders, shapesAreRefusedByNameWhereASpriteHasNone) {
    Tileset ts = test::default_tileset();
    for (Sprite& s : ts.sprites)
        if (s.name == "oak") s.shape.clear();
    Scene sc;
    sc.width = sc.height = 6;
    const World w = make_world(ts, sc);
    Params p;
    p.occluders = Occluders::shapes;
    try {
        build_occluders(w, p, w.placed.bounds);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("oak"), std::string::npos) << e.what();
    }
    p.occluders = Occluders::solids;
    const OccluderMap m = build_occluders(w, p, w.placed.bounds);
    EXPECT_GT(std::count_if(m.spans.begin(), m.spans.end(), [](const Spans& s) { return s.lower.high > 0; }), 100);
}

// Against the 3D reference, on the default seed's map and on drawn seeds and
// lights. The ground: solids estimated from the sprites mislight under half
// the ground pixels the paper's footprints do on the default seed, and never
// a point more on the drawn ones; the manifest's shapes through the same
// tracer never more than the footprints (the tracer's own error is small).
// The sprites: not asserted, as solids mislight more of them than
// footprints on some drawn scenes (docs/accuracy.md has the figures).
namespace {

// Lit mismatch against 3D, summed over scenes as pixels (a scene with few
// sprite pixels in its lights' areas counts as little as it weighs).
struct Pooled {
    double floor_wrong = 0, floor_pixels = 0, sprite_wrong = 0, sprite_pixels = 0;
    void add(const SweepPoint& pt) {
        floor_wrong += pt.floor.lit_mismatch * double(pt.floor.pixels);
        floor_pixels += double(pt.floor.pixels);
        sprite_wrong += pt.sprite.lit_mismatch * double(pt.sprite.pixels);
        sprite_pixels += double(pt.sprite.pixels);
    }
    double floor() const { return floor_pixels ? floor_wrong / floor_pixels : 0; }
    double sprites() const { return sprite_pixels ? sprite_wrong / sprite_pixels : 0; }
};

}  // namespace

TEST(Occluders, solidsMislightAtMostHalfWhatFootprintsDoAgainst3d) {
    // The default seed, and seeds and lights drawn here (pooled: two lights
    // on an 8x8 map may meet a handful of sprites), at four light heights:
    // solids mislight at most half the sprite pixels and the ground pixels
    // footprints do at every height.
    // On the default seed the true shapes through the same tracer mislight
    // less ground than the estimate; on the drawn seeds the estimate adds at
    // most a point to the shapes' ground mismatch (its errors may also offset
    // the tracer's: it mislights less there at some heights).
    const std::vector<std::string> heights = {"4", "16", "32", "64"};
    std::vector<Pooled> paper_drawn(heights.size()), solids_drawn(heights.size()), shapes_drawn(heights.size());
    for (std::uint64_t seed = 0; seed < 7; ++seed) {
        Scene s;
        s.width = s.height = 8;
        s.seed = seed == 0 ? "isolux" : "drawn-" + std::to_string(seed);
        s.params.area_a = s.params.area_b = 128;
        s.params.falloff_scale = 8;
        Pcg32 rng(seed + 11);
        const World w = make_world(test::default_tileset(), s);
        const Rect b = w.placed.bounds;
        for (int i = 0; i < 2; ++i)
            s.lights.push_back(Light{double(b.x + 100 + int(rng.below(std::uint32_t(b.w - 200)))) + 0.5,
                                     double(b.y + 80 + int(rng.below(std::uint32_t(b.h - 160)))) + 0.5});
        s.camera = {double(b.x), double(b.y), b.w, b.h};
        SweepOptions o;
        o.frames = 1;
        o.repeats = 1;
        o.carry_light = false;
        o.references = {Reference::three_d};
        const auto points = run_sweep(w, s, {{"occluders", {"footprints", "solids", "shapes"}}, {"light_height", heights}}, o);
        ASSERT_EQ(points.size(), 12u);
        for (std::size_t h = 0; h < heights.size(); ++h) {
            const SweepPoint &paper = points[h], &solids = points[4 + h], &shapes = points[8 + h];
            std::printf("seed %s, light height %s: ground %.1f%% -> %.1f%% (shapes %.1f%%), sprites %.1f%% -> %.1f%% (shapes %.1f%%)\n",
                        s.seed.c_str(), heights[h].c_str(), 100 * paper.floor.lit_mismatch,
                        100 * solids.floor.lit_mismatch, 100 * shapes.floor.lit_mismatch,
                        100 * paper.sprite.lit_mismatch, 100 * solids.sprite.lit_mismatch,
                        100 * shapes.sprite.lit_mismatch);
            if (seed == 0) {
                const std::string where = "the default seed, light height " + heights[h];
                EXPECT_LE(solids.sprite.lit_mismatch, paper.sprite.lit_mismatch / 2) << where;
                EXPECT_LE(solids.floor.lit_mismatch, paper.floor.lit_mismatch / 2) << where;
                EXPECT_LE(shapes.floor.lit_mismatch, solids.floor.lit_mismatch) << where;
                continue;
            }
            paper_drawn[h].add(paper);
            solids_drawn[h].add(solids);
            shapes_drawn[h].add(shapes);
        }
    }
    for (std::size_t h = 0; h < heights.size(); ++h) {
        const std::string where = "drawn seeds, light height " + heights[h];
        std::printf("%s: ground %.1f%% -> %.1f%% (shapes %.1f%%), sprites %.1f%% -> %.1f%% (shapes %.1f%%)\n", where.c_str(),
                    100 * paper_drawn[h].floor(), 100 * solids_drawn[h].floor(), 100 * shapes_drawn[h].floor(),
                    100 * paper_drawn[h].sprites(), 100 * solids_drawn[h].sprites(), 100 * shapes_drawn[h].sprites());
        EXPECT_LE(solids_drawn[h].sprites(), paper_drawn[h].sprites() / 2) << where;
        EXPECT_LE(solids_drawn[h].floor(), paper_drawn[h].floor() / 2) << where;
        EXPECT_LE(solids_drawn[h].floor(), shapes_drawn[h].floor() + 0.01) << where;
    }
}

// The scenes docs/accuracy.md measures (assets/scenes/default.json and
// forest.json, their own settings, 8 frames with the camera moving and a
// light carried, as `isolux-cli sweep` runs them): solids mislight at most
// half the sprite pixels and half the ground pixels footprints do at 4, 16,
// 32 and 64 px.
TEST(Occluders, solidsHalveThePapersErrorOnTheAccuracyScenes) {
    for (const char* name : {"default", "forest"}) {
        const Scene s = load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/" + name + ".json");
        const World w = make_world(test::default_tileset(), s);
        SweepOptions o;
        o.repeats = 1;
        o.references = {Reference::three_d};
        const std::vector<std::string> heights = {"4", "16", "32", "64"};
        const auto points = run_sweep(w, s, {{"occluders", {"footprints", "solids"}}, {"light_height", heights}}, o);
        ASSERT_EQ(points.size(), 8u);
        for (std::size_t h = 0; h < heights.size(); ++h) {
            const SweepPoint &paper = points[h], &solids = points[4 + h];
            const std::string where = std::string(name) + ", light height " + heights[h];
            std::printf("%s: ground %.1f%% -> %.1f%%, sprites %.1f%% -> %.1f%%\n", where.c_str(),
                        100 * paper.floor.lit_mismatch, 100 * solids.floor.lit_mismatch, 100 * paper.sprite.lit_mismatch,
                        100 * solids.sprite.lit_mismatch);
            EXPECT_LE(solids.sprite.lit_mismatch, paper.sprite.lit_mismatch / 2) << where;
            EXPECT_LE(solids.floor.lit_mismatch, paper.floor.lit_mismatch / 2) << where;
        }
    }
}

// The game preset takes what measures closest to 3D on the default map's
// ground and sprites (above, and docs/accuracy.md): solids.
TEST(Occluders, theGamePresetTracesAgainstSolids) {
    EXPECT_EQ(builtin_preset("game").occluders, Occluders::solids);
    EXPECT_EQ(builtin_preset("paper").occluders, Occluders::footprints);
}

// Every mode, ray skip and l frames run with solids: flat mode is the same
// frame as with footprints (no interaction), light and shadow modes light
// something and differ from footprints' frame.
TEST(Occluders, everyModeRaySkipAndLFramesRunWithSolids) {
    Scene s;
    s.width = s.height = 6;
    s.params.falloff_scale = 8;
    const World w = make_world(test::default_tileset(), s);
    const Rect b = w.placed.bounds;
    s.lights = {Light{b.x + b.w / 2.0 + 0.5, b.y + b.h / 2.0 + 0.5}};
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
        for (int skip : {1, 4})
            for (int every : {1, 3}) {
                Scene fp = s, so = s;
                for (Scene* sc : {&fp, &so}) {
                    sc->params.mode = mode;
                    sc->params.ray_skip = skip;
                    sc->params.trace_every = every;
                }
                so.params.occluders = Occluders::solids;
                FrameState a, c;
                for (long f = 0; f < 4; ++f) {
                    const Camera cam{b.x + 8.0 * f, double(b.y), b.w - 40, b.h};
                    render_frame(a, w, fp, cam, f);
                    render_frame(c, w, so, cam, f);
                }
                const auto lit = std::count_if(c.light.texels.begin(), c.light.texels.end(), [](std::uint8_t v) { return v > 0; });
                EXPECT_GT(lit, 1000) << int(mode) << " skip " << skip << " l " << every;
                if (mode == Mode::flat)
                    EXPECT_EQ(a.light.texels, c.light.texels) << "skip " << skip << " l " << every;
                else
                    EXPECT_NE(a.light.texels, c.light.texels) << int(mode) << " skip " << skip << " l " << every;
            }
}

// Each sprite's solids are estimated once and kept: a map built with a warm
// cache (over another region first) holds the same spans, surface and sprite
// index as one built from nothing, and a state that traced a walking light
// for several frames draws what a fresh state draws at the last one.
TEST(Occluders, keptSolidsBuildTheSameMapAndFrameAsFreshOnes) {
    Scene s;
    s.width = s.height = 8;
    s.params.falloff_scale = 8;
    s.params.occluders = Occluders::solids;
    const World w = make_world(test::default_tileset(), s);
    const Rect b = w.placed.bounds;
    SolidsCache cache;
    build_occluders(w, s.params, Rect{b.x, b.y, b.w / 2, b.h / 2}, &cache);
    EXPECT_GT(std::count(cache.made.begin(), cache.made.end(), 1), 0);
    const OccluderMap warm = build_occluders(w, s.params, b, &cache), fresh = build_occluders(w, s.params, b);
    EXPECT_EQ(warm.spans, fresh.spans);
    EXPECT_EQ(warm.surface.instance, fresh.surface.instance);
    EXPECT_EQ(warm.surface.height, fresh.surface.height);
    EXPECT_EQ(warm.shown_start, fresh.shown_start);
    EXPECT_EQ(warm.shown, fresh.shown);
    EXPECT_EQ(warm.flags, fresh.flags);

    FrameState walked;
    const Camera cam{double(b.x), double(b.y), b.w, b.h};
    Scene at = s;
    for (long f = 0; f < 5; ++f) {
        at.lights = {Light{b.x + b.w / 3.0 + 17.0 * f + 0.5, b.y + b.h / 2.0 + 0.5}};
        render_frame(walked, w, at, cam, f);
    }
    FrameState fresh_state;
    render_frame(fresh_state, w, at, cam, 0);
    EXPECT_EQ(walked.light.texels, fresh_state.light.texels);
}

// The passes walk the border rays' prefix tree when the light's area lies in
// the map and its clip holds a good part of it (occluders_tree.cpp; a clip
// past the area takes the whole area's and leaves the rest unlit), ray by
// ray otherwise: the same bytes. A clip of under a quarter of the area takes
// the rays, one a pixel wider than the area the tree; each is compared with
// the area's own, on drawn seeds, light positions and heights, every ray
// skip and area shape, light and shadow modes, solids and shapes; and so is
// each walked on 2 to 4 threads.
TEST(Occluders, theTreePassesGiveTheRaysBytesOnAnyNumberOfThreads) {
    int compared = 0, lit_sprites = 0, shaded_ground = 0, large = 0;
    for (const char* seed : {"isolux", "tree-walk", "forest-7"}) {
        Scene s;
        s.seed = seed;
        s.width = s.height = 14;
        const World w = make_world(test::default_tileset(), s);
        const Rect b = w.placed.bounds;
        for (Occluders o : {Occluders::solids, Occluders::shapes}) {
            Params p;
            p.occluders = o;
            p.falloff_scale = 16;
            const OccluderMap occ = build_occluders(w, p, b);
            for (int draw = 0; draw < 8; ++draw) {
                const std::uint64_t h = hash_point(hash_seed(seed), draw, int(o));
                const int a = 20 + int(h % 130), bb = 20 + int((h >> 8) % 100);
                large += (2 * a + 1) * (2 * bb + 1) >= 32768;  // trees walked on several threads
                const std::int64_t cx = b.x + a + std::int64_t((h >> 16) % std::uint64_t(b.w - 2 * a));
                const std::int64_t cy = b.y + bb + std::int64_t((h >> 32) % std::uint64_t(b.h - 2 * bb));
                const double height = std::array{0.0, 4.0, 16.0, 32.0, 64.0, 200.0}[(h >> 40) % 6];
                p.ray_skip = std::array{1, 2, 5}[(h >> 48) % 3];
                p.mode = (h >> 56) % 2 ? Mode::shadow : Mode::light;
                const Rect area{int(cx) - a, int(cy) - bb, 2 * a + 1, 2 * bb + 1};
                const Rect wider{area.x - 1, area.y - 1, area.w + 2, area.h + 2};
                const Rect part{area.x + 1, area.y, area.w / 2 - 1, area.h / 2 - 1};
                const Rect lower_right{area.x + area.w / 2 + 2, area.y + area.h / 2 + 2, area.w / 2 - 2, area.h / 2 + 3};
                LightMask tree = trace_light_solids(occ, cx, cy, a, bb, height, p, area);
                // The clipped and the threaded walks (the tree's subtrees
                // on 2, 3 and 4 threads) against the area's on one.
                LightMask tree_part = trace_light_solids(occ, cx, cy, a, bb, height, p, part, 2);
                LightMask tree_corner = trace_light_solids(occ, cx, cy, a, bb, height, p, lower_right, 3);
                LightMask threaded = trace_light_solids(occ, cx, cy, a, bb, height, p, area, 2);
                LightMask rays = trace_light_solids_by_rays(occ, cx, cy, a, bb, height, p, area);
                LightMask rays_part = trace_light_solids_by_rays(occ, cx, cy, a, bb, height, p, part);
                LightMask wide = trace_light_solids(occ, cx, cy, a, bb, height, p, wider, 4);
                // Each clipped mask against the area's: the same inside it, unlit past it.
                auto same_as_tree = [&](const LightMask& m, const char* pass) {
                    for (int y = m.clip.y; y < m.clip.y + m.clip.h; ++y)
                        for (int x = m.clip.x; x < m.clip.x + m.clip.w; ++x) {
                            const std::uint8_t t = area.contains(x, y) ? tree.value[std::size_t(y - area.y) * area.w + std::size_t(x - area.x)] : 0;
                            const std::uint8_t r = m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(x - m.clip.x)];
                            if (t != r) {
                                ADD_FAILURE() << pass << ": seed " << seed << " draw " << draw << " pixel " << x << "," << y
                                              << ": area's " << int(t) << ", clipped " << int(r);
                                return;
                            }
                        }
                    ++compared;
                };
                same_as_tree(rays, "ground, rays");
                same_as_tree(rays_part, "ground, rays clipped");
                same_as_tree(tree_part, "ground, tree clipped");
                same_as_tree(tree_corner, "ground, tree clipped to a corner past the area");
                same_as_tree(wide, "ground, wider clip");
                same_as_tree(threaded, "ground, tree on two threads");
                for (std::size_t i = 0; i < tree.value.size(); ++i) shaded_ground += tree.value[i] == 0;
                light_sprite_points(tree, occ, height, p);
                light_sprite_points(tree_part, occ, height, p, 2);
                light_sprite_points(tree_corner, occ, height, p, 3);
                light_sprite_points(threaded, occ, height, p, 2);
                light_sprite_points_by_rays(rays, occ, height, p);
                light_sprite_points_by_rays(rays_part, occ, height, p);
                light_sprite_points(wide, occ, height, p, 4);
                same_as_tree(rays, "sprites, rays");
                same_as_tree(rays_part, "sprites, rays clipped");
                same_as_tree(tree_part, "sprites, tree clipped");
                same_as_tree(tree_corner, "sprites, tree clipped to a corner past the area");
                same_as_tree(wide, "sprites, wider clip");
                same_as_tree(threaded, "sprites, tree on two threads");
                for (std::size_t i = 0; i < tree.value.size(); ++i) {
                    const int px = area.x + int(i % std::size_t(area.w)), py = area.y + int(i / std::size_t(area.w));
                    lit_sprites += tree.value[i] && occ.surface.instance[std::size_t(py - occ.rect.y) * occ.rect.w +
                                                                         std::size_t(px - occ.rect.x)] >= 0;
                }
            }
        }
    }
    EXPECT_EQ(compared, 576);
    // The scenes hold both shaded ground and lit sprites, so the comparison can fail.
    EXPECT_GT(shaded_ground, 10000);
    EXPECT_GT(lit_sprites, 10000);
    EXPECT_GE(large, 4);  // ground trees large enough to be split (min_split_nodes)
}

namespace {

// Every field of two occluder maps, equal.
void expect_same_map(const OccluderMap& a, const OccluderMap& b, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_EQ(a.rect, b.rect);
    EXPECT_TRUE(a.spans == b.spans);
    EXPECT_EQ(a.surface.instance, b.surface.instance);
    EXPECT_EQ(a.surface.height, b.surface.height);
    EXPECT_EQ(a.shown_start, b.shown_start);
    EXPECT_TRUE(a.shown == b.shown);
    EXPECT_EQ(a.flags, b.flags);
    EXPECT_EQ(a.tallest, b.tallest);
}

}  // namespace

// Each pixel of the occluder map depends only on the sprites near it, so a
// region's map is the whole map's there, and update_occluders (what a pan
// and an edit do) gives what building the region whole gives: on drawn
// regions of the default map, pans every way, and drawn edits.
TEST(Occluders, anUpdatedMapIsTheMapBuiltWhole) {
    Scene s;
    s.width = s.height = 10;
    s.params.occluders = Occluders::solids;
    World w = make_world(test::default_tileset(), s);
    const Rect b = w.placed.bounds;
    const OccluderMap whole = build_occluders(w, s.params, b);
    Pcg32 rng(33);
    const auto drawn_region = [&] {
        const int rw = 64 + int(rng.below(std::uint32_t(b.w / 2))), rh = 64 + int(rng.below(std::uint32_t(b.h / 2)));
        return Rect{b.x + int(rng.below(std::uint32_t(b.w - rw))), b.y + int(rng.below(std::uint32_t(b.h - rh))), rw, rh};
    };
    for (int k = 0; k < 6; ++k) {
        const Rect r = drawn_region();
        const OccluderMap part = build_occluders(w, s.params, r);
        bool same = true;
        for (int y = r.y; y < r.y + r.h && same; ++y)
            for (int x = r.x; x < r.x + r.w && same; ++x) {
                const std::size_t i = std::size_t(y - r.y) * r.w + std::size_t(x - r.x);
                const std::size_t j = std::size_t(y - b.y) * b.w + std::size_t(x - b.x);
                same = part.spans[i] == whole.spans[j] && part.surface.instance[i] == whole.surface.instance[j] &&
                       part.surface.height[i] == whole.surface.height[j];
            }
        EXPECT_TRUE(same) << "region " << r.x << "," << r.y << " " << r.w << "x" << r.h;
    }
    // Pans: right, left and down, up, into a larger and a smaller region.
    for (int k = 0; k < 6; ++k) {
        const Rect from = drawn_region(), to = drawn_region();
        if (intersect(from, to).empty()) continue;
        OccluderMap m = build_occluders(w, s.params, from);
        update_occluders(m, w, s.params, to, Rect{});
        expect_same_map(m, build_occluders(w, s.params, to), "pan " + std::to_string(k));
        // The same size moved every way: in place.
        for (const auto& [dx, dy] : {std::pair{37, 0}, {-37, 0}, {0, 21}, {0, -21}, {29, -13}, {-29, 13}}) {
            const Rect moved{from.x + dx, from.y + dy, from.w, from.h};
            if (!b.contains(moved.x, moved.y) || !b.contains(moved.x + moved.w - 1, moved.y + moved.h - 1)) continue;
            OccluderMap panned = build_occluders(w, s.params, from);
            update_occluders(panned, w, s.params, moved, Rect{});
            expect_same_map(panned, build_occluders(w, s.params, moved), "pan by " + std::to_string(dx) + "," + std::to_string(dy));
        }
    }
    OccluderMap grown = build_occluders(w, s.params, Rect{b.x + 40, b.y + 30, 200, 150});
    update_occluders(grown, w, s.params, b, Rect{});
    expect_same_map(grown, whole, "a region grown to the map");
    // Edits: the edited sprites' rectangles, grown by occluder_reach.
    const char* overlays[] = {"oak", "pine", "bush", "rock", "wall"};
    for (int k = 0; k < 4; ++k) {
        OccluderMap m = build_occluders(w, s.params, b);
        TileEdit e;
        e.col = rng.below(10);
        e.row = rng.below(10);
        e.overlays = std::vector<std::string>{overlays[rng.below(5)]};
        if (k == 3) e.overlays = std::vector<std::string>{};
        const Rect changed = set_edits(w, {e});
        if (w.placed.bounds != b) continue;  // an edit that grows the map moves every pixel
        const int reach = occluder_reach(w.tileset);
        const Rect around{changed.x - reach, changed.y - reach, changed.w + 2 * reach, changed.h + 2 * reach};
        update_occluders(m, w, s.params, b, around);
        expect_same_map(m, build_occluders(w, s.params, b), "edit " + std::to_string(k));
    }
}

// A map rebuilt in the storage of another (what the frame does when a
// parameter changes) is the map built fresh: from a map of other parameters
// (another Δy, shapes) over the same region, a larger one and a smaller one,
// and from the footprints' map, which holds no spans.
TEST(Occluders, aRebuiltMapIsTheMapBuiltFresh) {
    Scene s;
    s.width = s.height = 10;
    s.params.occluders = Occluders::solids;
    const World w = make_world(test::default_tileset(), s);
    const Rect b = w.placed.bounds;
    const Rect inner{b.x + 60, b.y + 40, b.w / 2, b.h / 2};
    Params other = s.params;
    other.delta_y = 9;
    Params shapes = s.params;
    shapes.occluders = Occluders::shapes;
    Params footprints = s.params;
    footprints.occluders = Occluders::footprints;
    for (const auto& [from_params, from_region, to_region, what] :
         {std::tuple{other, b, b, "another delta_y, the same region"}, {shapes, b, b, "from shapes"},
          {other, b, inner, "a smaller region"}, {other, inner, b, "a larger region"},
          {footprints, b, b, "from footprints"}}) {
        OccluderMap m = build_occluders(w, from_params, from_region);
        if (from_params.occluders != Occluders::footprints) {
            ASSERT_FALSE(m.shown.empty()) << what;
        }
        rebuild_occluders(m, w, s.params, to_region);
        expect_same_map(m, build_occluders(w, s.params, to_region), what);
    }
}

// The app's frame, panning across a map wider than its obstacle region's
// margin: the obstacle map, the ground lines and (with solids) the occluder
// map it keeps are the ones built whole for its region, and its light the
// light of a frame that starts there.
TEST(Occluders, aPanningFrameKeepsTheMapsBuiltWhole) {
    for (const Occluders o : {Occluders::footprints, Occluders::solids}) {
        SCOPED_TRACE(o == Occluders::solids ? "solids" : "footprints");
        Scene s;
        s.width = s.height = 24;
        s.params.falloff_scale = 8;
        s.params.occluders = o;
        const World w = make_world(test::default_tileset(), s);
        const Rect b = w.placed.bounds;
        FrameState st;
        std::vector<Rect> regions;
        Scene at = s;
        Camera cam;
        // From the map's top left corner to its right edge, which cut the region.
        for (long f = 0; f < 20; ++f) {
            cam = Camera{double(b.x + 100 + 150 * f), double(b.y + 100 + 30 * f), 400, 300};
            at.lights = {Light{cam.x + 200.5, cam.y + 150.5}};
            render_frame(st, w, at, cam, f);
            if (regions.empty() || regions.back() != st.cache.obstacle_region) regions.push_back(st.cache.obstacle_region);
        }
        // The region moved at least twice keeping its size (pans, in place),
        // and changed its size at least twice (grown at the start, cut by
        // the map's edge at the end).
        int pans = 0, resized = 0;
        for (std::size_t k = 1; k < regions.size(); ++k) {
            const bool same_size = regions[k].w == regions[k - 1].w && regions[k].h == regions[k - 1].h;
            pans += same_size;
            resized += !same_size;
        }
        ASSERT_GE(pans, 2);
        ASSERT_GE(resized, 2);
        const Rect region = st.cache.obstacle_region;
        const Mask obstacles = build_obstacle_map(w.tileset, w.placed, s.params, region, &st.cache.footprints);
        EXPECT_EQ(st.obstacles.rect(), region);
        EXPECT_EQ(st.obstacles.bits, obstacles.bits);
        const GroundLines lines = ground_lines(w.placed, st.opacity, region);
        EXPECT_EQ(st.cache.ground.rect, lines.rect);
        EXPECT_EQ(st.cache.ground.below, lines.below);
        EXPECT_EQ(st.cache.ground.below8, lines.below8);
        EXPECT_EQ(st.cache.ground.wide, lines.wide);
        if (o == Occluders::solids) expect_same_map(st.occluders, build_occluders(w, s.params, region), "after the pan");
        FrameState fresh;
        render_frame(fresh, w, at, cam, 0);
        EXPECT_EQ(st.light.texels, fresh.light.texels);
    }
}

// A sprite cut off just below its foot: its solids' ground reaches past its
// rectangle (a canopy's disc stands over ground up to its radius / sqrt(2)
// below the foot), so a region's map must take in the sprites up to
// occluder_reach above it to be the whole map's there.
TEST(Occluders, aRegionTakesInSolidsStandingOverItFromSpritesAbove) {
    Tileset ts = test::default_tileset();
    for (Sprite& sp : ts.sprites) {
        if (sp.kind != SpriteKind::overlay) continue;
        const int h = std::min(sp.image.height, sp.anchor_y + 2);
        sp.image.rgba.resize(std::size_t(sp.image.width) * h * 4);
        if (!sp.image.alpha16.empty()) sp.image.alpha16.resize(std::size_t(sp.image.width) * h);
        if (!sp.height.empty()) sp.height.resize(std::size_t(sp.image.width) * h);
        sp.image.height = h;
    }
    Scene s;
    s.width = s.height = 8;
    s.params.occluders = Occluders::solids;
    const World w = make_world(ts, s);
    const Rect b = w.placed.bounds;
    SolidsCache cache;
    const OccluderMap whole = build_occluders(w, s.params, b, &cache);
    long reaching = 0, differ = 0;  // ground pixels below every sprite that holds them
    for (int y0 = b.y; y0 < b.y + b.h; y0 += 16) {
        const Rect r{b.x, y0, b.w, std::min(16, b.y + b.h - y0)};
        const OccluderMap band = build_occluders(w, s.params, r, &cache);
        for (std::size_t i = 0; i < band.spans.size(); ++i) {
            const std::size_t j = std::size_t(r.y - b.y) * b.w + i;
            differ += !(band.spans[i] == whole.spans[j]);
        }
    }
    // Some ground does lie below every sprite over it: the case is real.
    for (int y = b.y; y < b.y + b.h; ++y)
        for (int x = b.x; x < b.x + b.w; ++x) {
            const std::size_t j = std::size_t(y - b.y) * b.w + std::size_t(x - b.x);
            if (!whole.spans[j].any()) continue;
            std::vector<std::uint32_t> over;
            instances_in(w.placed, Rect{x, y, 1, 1}, true, over);
            reaching += over.empty();
        }
    EXPECT_GT(reaching, 0);
    EXPECT_EQ(differ, 0);
}

// The height each shown sprite pixel takes (sprite_solids tests only the
// heights near its view line's crossing of the deepest cross-section): the topmost
// half-pixel height on its view line inside a solid, front object first,
// found here by trying every height, on every overlay of the default tileset.
TEST(Occluders, aSpritePixelShowsTheTopmostSolidPointOnItsViewLine) {
    const Tileset ts = test::default_tileset();
    Params p;
    p.occluders = Occluders::solids;
    long tested = 0, from_solids = 0;
    for (const Sprite& sp : ts.sprites) {
        if (sp.kind != SpriteKind::overlay) continue;
        const SpriteSolids ss = sprite_solids(ts, sp, p);
        const Mask shown = opacity_map(sp.image, sprite_threshold(sp, p.opacity_threshold));
        ASSERT_EQ(ss.objects.size(), 1u) << sp.name;
        const EstimatedObject& o = ss.objects[0];
        for (int y = 0; y < sp.image.height; ++y)
            for (int x = 0; x < sp.image.width; ++x) {
                if (!shown.get(x, y)) continue;
                const double sx = x + 0.5 - o.center_x, sy = y + 0.5 - o.center_y;
                double expected = -1;
                for (double z = o.height() - 0.5; z >= 0 && expected < 0; z -= 0.5)
                    if (o.contains(ground_frame(sx, sy, z))) expected = z;
                from_solids += expected >= 0;
                if (expected < 0) expected = std::max(0.0, o.center_y - (y + 0.5));
                ++tested;
                ASSERT_EQ(ss.heights[std::size_t(y) * sp.image.width + x], float(expected)) << sp.name << " at " << x << "," << y;
            }
    }
    EXPECT_GT(from_solids, tested / 2);  // most shown pixels show a solid's point
}

// A solid's stamp (its spans over the ground under it) and its silhouette
// are made row by row; here every pixel asks the estimate itself
// (EstimatedObject::span_at, and each cross-section's ellipse drawn pixel by
// pixel), on the default tileset's overlays and on a tree four times their
// size, drawn from its true shapes.
TEST(Occluders, eachStampPixelHoldsItsObjectsSpanAndTheSilhouetteEachCrossSection) {
    Tileset ts = test::default_tileset();
    {
        const std::vector<Solid> tree = {Solid{SolidKind::cylinder, {0, 0, 0}, {16, 16, 120}},
                                         Solid{SolidKind::ellipsoid, {0, 0, 180}, {112, 112, 96}}};
        Sprite big;
        big.name = "big_tree";
        big.image = Image(330, 450);
        big.anchor_x = 165, big.anchor_y = 420;
        for (int y = 0; y < big.image.height; ++y)
            for (int x = 0; x < big.image.width; ++x)
                if (std::isfinite(surface_height(tree, x + 0.5 - big.anchor_x, y + 0.5 - big.anchor_y))) {
                    std::uint8_t* px = big.image.at(x, y);
                    px[0] = px[1] = px[2] = 90, px[3] = 255;
                }
        ts.sprites.push_back(big);
    }
    Params p;
    p.occluders = Occluders::solids;
    long spans = 0, drawn = 0;
    bool big_seen = false;
    for (const Sprite& sp : ts.sprites) {
        if (sp.kind != SpriteKind::overlay) continue;
        const SpriteSolids ss = sprite_solids(ts, sp, p);
        ASSERT_EQ(ss.stamps.size(), ss.objects.size()) << sp.name;
        big_seen = big_seen || (sp.name == "big_tree" && !ss.objects.empty() && ss.objects[0].height() > 200);
        Mask want(Rect{0, 0, sp.image.width, sp.image.height});
        for (std::size_t k = 0; k < ss.objects.size(); ++k) {
            const EstimatedObject& o = ss.objects[k];
            const SpanStamp& st = ss.stamps[k];
            for (int j = 0; j < st.rect.h; ++j)
                for (int i = 0; i < st.rect.w; ++i) {
                    const Vec3 q = ground_frame(st.rect.x + i + 0.5 - o.center_x, st.rect.y + j + 0.5 - o.center_y, 0);
                    double lo = 0, hi = 0;
                    std::pair<float, float> expected{0.f, 0.f};
                    if (o.span_at(q.x, q.y, lo, hi)) expected = {float(lo), float(hi)}, ++spans;
                    ASSERT_EQ(st.spans[std::size_t(j) * st.rect.w + std::size_t(i)], expected)
                        << sp.name << " at " << st.rect.x + i << "," << st.rect.y + j;
                }
            for (std::size_t z = 0; z < o.radius.size(); ++z) {
                const double r = o.radius[z], a = o.across_at(z) * std::sqrt(2.0), b = r / std::sqrt(2.0),
                             yc = o.center_y - (double(z) + 0.5);
                if (r <= 0) continue;
                for (int y = int(std::floor(yc - b)); y <= int(std::ceil(yc + b)); ++y) {
                    const double v = (y + 0.5 - yc) / b;
                    if (v * v > 1) continue;
                    const double hw = a * std::sqrt(1 - v * v);
                    for (int x = int(std::ceil(o.center_x - hw - 0.5)); x <= int(std::floor(o.center_x + hw - 0.5)); ++x)
                        want.set(x, y);
                }
            }
        }
        const Mask got = solid_silhouette(ss.objects, sp.image.width, sp.image.height);
        EXPECT_TRUE(got.bits == want.bits) << sp.name;
        drawn += want.count();
    }
    EXPECT_TRUE(big_seen) << "the large tree gets a solid over 200 px high";
    EXPECT_GT(spans, 10000);
    EXPECT_GT(drawn, 10000);
}

// An occluder map takes about 35 bytes a pixel: a region beyond
// max_occluder_pixels is refused by Error with its size before any of it is
// made, whatever asks (a new map, one made again, a pan).
TEST(Occluders, aRegionBeyondTheLimitIsRefusedWithItsSize) {
    const World w = make_world(test::default_tileset(), Scene{});
    Params p;
    p.occluders = Occluders::solids;
    const Rect huge{0, 0, 8193, 8193};  // 2^26 + 16385 pixels
    ASSERT_GT((long long)huge.w * huge.h, max_occluder_pixels);
    const std::string m = error_of([&] { build_occluders(w, p, huge); });
    EXPECT_NE(m.find("8193x8193"), std::string::npos) << m;
    EXPECT_NE(m.find("megapixel limit"), std::string::npos) << m;
    OccluderMap kept = build_occluders(w, p, Rect{0, 0, 512, 512});
    EXPECT_NE(error_of([&] { update_occluders(kept, w, p, huge, Rect{}); }).find("8193x8193"), std::string::npos);
    EXPECT_NE(error_of([&] { rebuild_occluders(kept, w, p, huge); }).find("8193x8193"), std::string::npos);
    EXPECT_EQ(error_of([&] { rebuild_occluders(kept, w, p, Rect{0, 0, 1024, 512}); }), "");
}
