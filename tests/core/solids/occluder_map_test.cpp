// The occluder map (occluder_map.cpp): kept, updated, rebuilt and panned
// maps equal the map built whole; regions take in solids from above; limits.
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
#include "isolux/occluder_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/solid.hpp"
#include "isolux/solid_estimate.hpp"
#include "test_util.hpp"
#include "core/solids/same_map.hpp"
#include "solids/oracles.hpp"
#include "frame/frame_cache.hpp"

using namespace isolux;
using isolux::test::error_of;
using isolux::test::expect_same_map;

namespace {


}  // namespace

// Each sprite's solids are estimated once and kept: a map built with a warm
// cache (over another region first) holds the same spans, surface and sprite
// index as one built from nothing, and a state that traced a walking light
// for several frames draws what a fresh state draws at the last one.
TEST(OccluderMap, keptSolidsBuildTheSameMapAndFrameAsFreshOnes) {
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

// Each pixel of the occluder map depends only on the sprites near it, so a
// region's map is the whole map's there, and update_occluders (what a pan
// and an edit do) gives what building the region whole gives: on drawn
// regions of the default map, pans every way, and drawn edits.
TEST(OccluderMap, anUpdatedMapIsTheMapBuiltWhole) {
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

// Edits in place relist only their pixels (update_occluders): one map
// edited again and again, trees planted where there were none and taken
// away (its lists grow into new room and shrink into padding), lists what
// a build lists after every edit, its tallest point included; a light
// traced against it, ground and sprite passes, lights the bytes a fresh
// map's light does (every pass skips the padding); and a pan afterwards
// lists without padding.
TEST(OccluderMap, aMapEditedAgainAndAgainListsWhatABuildLists) {
    Scene s;
    s.width = s.height = 10;
    s.params.occluders = Occluders::solids;
    World w = make_world(test::default_tileset(), s);
    const Rect b = w.placed.bounds;
    OccluderMap m = build_occluders(w, s.params, b);
    const int reach = occluder_reach(w.tileset);
    const char* overlays[] = {"oak", "pine", "bush", "rock", "wall", "birch"};
    Pcg32 rng(91);
    std::size_t most_padding = 0;
    int tallest_changes = 0, in_place = 0, moved_up = 0;
    for (int k = 0; k < 16; ++k) {
        TileEdit e;
        e.col = 1 + int(rng.below(8));
        e.row = 1 + int(rng.below(8));
        e.overlays = k % 3 == 2 ? std::vector<std::string>{} : std::vector<std::string>{overlays[rng.below(6)]};
        const int tallest_before = m.tallest;
        const std::size_t entries_before = m.shown.size();
        const Rect changed = set_edits(w, {e});
        ASSERT_EQ(w.placed.bounds, b);
        update_occluders(m, w, s.params, b, Rect{changed.x - reach, changed.y - reach, changed.w + 2 * reach, changed.h + 2 * reach});
        in_place += m.shown.size() == entries_before;  // the lists fit their room
        moved_up += m.shown.size() > entries_before;   // the entries after them moved up
        const OccluderMap built = build_occluders(w, s.params, b);
        expect_same_map(m, built, "edit " + std::to_string(k));
        most_padding = std::max(most_padding, m.padding);
        tallest_changes += m.tallest != tallest_before;
        // A light at the edit, its two passes against the edited map and the built one.
        const std::int64_t cx = changed.x + changed.w / 2, cy = changed.y + changed.h;
        for (const double height : {16.0, 48.0}) {
            LightMask lit = trace_light_solids(m, cx, cy, 96, 96, height, s.params, Rect{int(cx) - 96, int(cy) - 96, 193, 193});
            light_sprite_points(lit, m, height, s.params);
            LightMask fresh = trace_light_solids(built, cx, cy, 96, 96, height, s.params, Rect{int(cx) - 96, int(cy) - 96, 193, 193});
            light_sprite_points(fresh, built, height, s.params);
            EXPECT_EQ(lit.value, fresh.value) << "edit " << k << " height " << height;
        }
    }
    // The map's overlays cleared, then one pine planted and taken away: its
    // tallest point rises with the pine and falls when it goes.
    std::vector<TileEdit> clear;
    for (int row = 0; row < 10; ++row)
        for (int col = 0; col < 10; ++col) {
            TileEdit e;
            e.col = col, e.row = row, e.overlays = std::vector<std::string>{};
            clear.push_back(e);
        }
    for (const auto& [edits, what] : {std::pair{clear, "cleared"}, {std::vector<TileEdit>{{5, 5, {}, std::vector<std::string>{"pine"}}}, "a pine"},
                                      {std::vector<TileEdit>{{5, 5, {}, std::vector<std::string>{}}}, "the pine gone"}}) {
        const int tallest_before = m.tallest;
        const Rect changed = set_edits(w, edits);
        update_occluders(m, w, s.params, b, Rect{changed.x - reach, changed.y - reach, changed.w + 2 * reach, changed.h + 2 * reach});
        expect_same_map(m, build_occluders(w, s.params, b), what);
        most_padding = std::max(most_padding, m.padding);
        tallest_changes += m.tallest != tallest_before;
    }
    EXPECT_GE(tallest_changes, 2);  // up with the pine, down without it (sought among the lists)
    EXPECT_GT(most_padding, 0u);  // some edit's lists shrank
    EXPECT_GT(in_place, 0);
    EXPECT_GT(moved_up, 0);
    const Rect moved{b.x + 40, b.y + 20, b.w - 80, b.h - 60};
    update_occluders(m, w, s.params, moved, Rect{});
    EXPECT_EQ(m.padding, 0u);
    expect_same_map(m, build_occluders(w, s.params, moved), "a pan after the edits");
    std::printf("16 edits: %d in place, %d moving the entries after them; most padding %zu entries; the tallest point changed %d times\n",
                in_place, moved_up, most_padding, tallest_changes);
}

// A map rebuilt in the storage of another (what the frame does when a
// parameter changes) is the map built fresh: from a map of other parameters
// (another Δy, shapes) over the same region, a larger one and a smaller one,
// and from the footprints' map, which holds no spans.
TEST(OccluderMap, aRebuiltMapIsTheMapBuiltFresh) {
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
TEST(OccluderMap, aPanningFrameKeepsTheMapsBuiltWhole) {
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
            if (regions.empty() || regions.back() != st.cache->obstacle_region) regions.push_back(st.cache->obstacle_region);
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
        const Rect region = st.cache->obstacle_region;
        const Mask obstacles = build_obstacle_map(w.tileset, w.placed, s.params, region, &st.cache->footprints);
        EXPECT_EQ(st.obstacles.rect(), region);
        EXPECT_EQ(st.obstacles.bits, obstacles.bits);
        const GroundLines lines = ground_lines(w.placed, st.opacity, region);
        EXPECT_EQ(st.cache->ground.rect, lines.rect);
        EXPECT_EQ(st.cache->ground.below, lines.below);
        EXPECT_EQ(st.cache->ground.below8, lines.below8);
        EXPECT_EQ(st.cache->ground.wide, lines.wide);
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
TEST(OccluderMap, aRegionTakesInSolidsStandingOverItFromSpritesAbove) {
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

// An occluder map takes about 35 bytes a pixel: a region beyond
// max_occluder_pixels is refused by Error with its size before any of it is
// made, whatever asks (a new map, one made again, a pan).
TEST(OccluderMap, aRegionBeyondTheLimitIsRefusedWithItsSize) {
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
