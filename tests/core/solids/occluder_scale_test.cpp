// The occluders' resolution as a knob (occluder_scale.cpp): the coarse map
// of a map blown up comes back whole, a wall one pixel thin still casts,
// each fine pixel takes its block's answer with its own falloff, and frames
// traced coarse are deterministic and near the full-resolution ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/frame.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/params.hpp"
#include "isolux/scene_file.hpp"
#include "test_util.hpp"
#include "core/solids/same_map.hpp"

using namespace isolux;

namespace {

const World& default_world() {
    static const World w = [] {
        Scene s;
        s.width = s.height = 8;
        return make_world(test::default_tileset(), s);
    }();
    return w;
}

// `m` blown up s times: each pixel an s x s block, its spans' and surface's
// heights times s.
OccluderMap blown_up(const OccluderMap& m, int s) {
    OccluderMap f;
    f.rect = {m.rect.x * s, m.rect.y * s, m.rect.w * s, m.rect.h * s};
    const std::size_t n = std::size_t(f.rect.w) * f.rect.h;
    f.spans.assign(n, Spans{});
    f.surface.rect = f.rect;
    f.surface.instance.assign(n, -1);
    f.surface.height.assign(n, 0.f);
    const float k = float(s);
    for (int y = 0; y < f.rect.h; ++y)
        for (int x = 0; x < f.rect.w; ++x) {
            const std::size_t i = std::size_t(y / s) * m.rect.w + std::size_t(x / s), j = std::size_t(y) * f.rect.w + x;
            const Spans& sp = m.spans[i];
            f.spans[j] = Spans{{sp.lower.low * k, sp.lower.high * k}, {sp.upper.low * k, sp.upper.high * k}};
            f.surface.instance[j] = m.surface.instance[i];
            f.surface.height[j] = m.surface.height[i] * k;
        }
    index_occluders(f);
    return f;
}

}  // namespace

TEST(OccluderScale, theCoarseMapOfAMapBlownUpIsThatMap) {
    Params p;
    p.occluders = Occluders::solids;
    const World& w = default_world();
    const OccluderMap m = build_occluders(w, p, w.placed.bounds);
    ASSERT_GT(std::count_if(m.spans.begin(), m.spans.end(), [](const Spans& s) { return s.any(); }), 1000);
    for (int s : {2, 4}) {
        const OccluderMap c = coarse_occluders(blown_up(m, s), s);
        // The map, with two pixels of bare ground all round.
        ASSERT_EQ(c.rect, (Rect{m.rect.x - 2, m.rect.y - 2, m.rect.w + 4, m.rect.h + 4})) << s;
        int differing = 0, sprite_pixels = 0;
        for (int y = 0; y < c.rect.h; ++y)
            for (int x = 0; x < c.rect.w; ++x) {
                const std::size_t j = std::size_t(y) * c.rect.w + x;
                const bool inside = x >= 2 && y >= 2 && x < m.rect.w + 2 && y < m.rect.h + 2;
                const std::size_t i = inside ? std::size_t(y - 2) * m.rect.w + std::size_t(x - 2) : 0;
                const Spans want = inside ? m.spans[i] : Spans{};
                const std::int32_t instance = inside ? m.surface.instance[i] : -1;
                const float height = inside ? m.surface.height[i] : 0.f;
                differing += !(c.spans[j] == want) || c.surface.instance[j] != instance || c.surface.height[j] != height;
                sprite_pixels += instance >= 0;
            }
        EXPECT_EQ(differing, 0) << "scale " << s;
        EXPECT_GT(sprite_pixels, 1000);
        EXPECT_EQ(c.tallest, m.tallest) << "scale " << s;
    }
}

TEST(OccluderScale, aWallOnePixelThinStillCastsAtHalfResolution) {
    // A wall 1 px thick at an odd column (the right pixel of its block), 40
    // px tall, before a light 30 px high: the ground behind it is shaded to
    // the border, the ground before it lit, at full resolution and at half.
    const Rect r{-100, -20, 201, 41};
    OccluderMap m;
    m.rect = r;
    m.spans.assign(std::size_t(r.w) * r.h, Spans{});
    for (int y = -20; y <= 20; ++y) m.spans[std::size_t(y - r.y) * r.w + std::size_t(31 - r.x)] = Spans{{0, 40}, {}};
    m.surface.rect = r;
    m.surface.instance.assign(m.spans.size(), -1);
    m.surface.height.assign(m.spans.size(), 0.f);
    index_occluders(m);
    const OccluderMap c = coarse_occluders(m, 2);
    EXPECT_TRUE(c.spans_at(15, 0) == (Spans{{0, 20}, {}}));
    EXPECT_TRUE(c.spans_at(16, 0) == Spans{});
    Params p;
    p.falloff_scale = 8;
    for (int s : {1, 2}) {
        LightMask mask;
        start_mask(mask, 0, 0, 90, 10, p, Rect{-90, -10, 181, 21});
        if (s == 1) mask = trace_light_solids(m, 0, 0, 90, 10, 30, p, mask.clip);
        else trace_solids_at_scale(mask, c, 2, 30, p, true);
        auto at = [&](int x, int y) { return mask.value[std::size_t(y + 10) * 181 + std::size_t(x + 90)]; };
        for (int y : {-5, 0, 5}) {
            EXPECT_EQ(at(20, y), falloff(20, 8)) << "scale " << s << ": lit before the wall, with its own falloff";
            EXPECT_EQ(at(-60, y), falloff(60, 8)) << "scale " << s << ": lit on the other side";
            EXPECT_EQ(at(40, y), 0) << "scale " << s << ": shaded behind the wall";
            EXPECT_EQ(at(90, y), 0) << "scale " << s << ": to the border";
        }
    }
}

TEST(OccluderScale, eachPixelTakesItsBlocksAnswerWithItsOwnFalloff) {
    Params p;
    p.falloff_scale = 3;
    p.mode = Mode::shadow;
    for (int s : {2, 3, 4}) {
        LightMask fine;
        // A centre and a clip at negative, odd coordinates: the blocks floor.
        start_mask(fine, -7, -3, 21, 13, p, Rect{-25, -16, 30, 27}, true);
        const Params cp = coarse_params(p);
        LightMask coarse;
        start_coarse_mask(coarse, fine, s, cp);
        EXPECT_EQ(coarse.a, 21 / s + 1);
        EXPECT_EQ(coarse.b, 13 / s + 1);
        auto block = [&](int v) { return int(std::floor(double(v) / s)); };
        EXPECT_EQ(coarse.cx, block(-7));
        EXPECT_EQ(coarse.cy, block(-3));
        for (int y = 0; y < coarse.clip.h; ++y)
            for (int x = 0; x < coarse.clip.w; ++x)
                coarse.value[std::size_t(y) * coarse.clip.w + x] = (x * 7 + y * 3) % 5 < 2 ? 255 : 0;
        upsample_mask(fine, coarse, s, p);
        int lit = 0, dark = 0;
        for (int y = fine.clip.y; y < fine.clip.y + fine.clip.h; ++y)
            for (int x = fine.clip.x; x < fine.clip.x + fine.clip.w; ++x) {
                const std::size_t i = std::size_t(y - fine.clip.y) * fine.clip.w + std::size_t(x - fine.clip.x);
                const int X = block(x), Y = block(y);
                ASSERT_TRUE(coarse.clip.contains(X, Y)) << x << "," << y;
                const bool block_lit =
                    coarse.value[std::size_t(Y - coarse.clip.y) * coarse.clip.w + std::size_t(X - coarse.clip.x)] != 0;
                const bool in_area = std::abs(x + 7) <= 21 && std::abs(y + 3) <= 13;
                const std::uint8_t want = in_area && block_lit ? falloff(std::max(std::abs(x + 7), std::abs(y + 3)), 3) : 0;
                EXPECT_EQ(fine.value[i], want) << "scale " << s << " at " << x << "," << y;
                EXPECT_EQ(fine.reached[i], 1) << "shadow mode: every pixel reached";
                (want ? lit : dark)++;
            }
        EXPECT_GT(lit, 100);
        EXPECT_GT(dark, 100);
    }
}

TEST(OccluderScale, aPannedCoarseMapIsTheCoarseMapOfThePannedMap) {
    // The occluder map of a view's region, panned by odd and even steps,
    // across and out of the old region: the coarse map and picks updated in
    // place are those made whole from the panned map.
    Params p;
    p.occluders = Occluders::solids;
    const World& w = default_world();
    const Rect b = w.placed.bounds;
    const Rect first{b.x + 100, b.y + 60, 500, 320};
    SolidsCache cache;
    const OccluderMap from = build_occluders(w, p, first, &cache);
    int pans = 0;
    for (int s : {2, 3})
        for (const auto& [dx, dy] : std::vector<std::pair<int, int>>{{37, 0}, {-64, 21}, {5, -3}, {260, 170}, {900, 0}}) {
            const Rect to{first.x + dx, first.y + dy, first.w + (dx % 2), first.h};
            const OccluderMap panned = build_occluders(w, p, to, &cache);
            OccluderMap c = coarse_occluders(from, s);
            std::vector<std::uint8_t> picks = coarse_picks(from.surface, c, s);
            pan_coarse_occluders(c, picks, panned, first, s);
            const OccluderMap whole = coarse_occluders(panned, s);
            const std::string what = "scale " + std::to_string(s) + " by " + std::to_string(dx) + "," + std::to_string(dy);
            test::expect_same_map(c, whole, what);
            EXPECT_EQ(c.surface.rect, whole.surface.rect) << what;
            EXPECT_EQ(picks, coarse_picks(panned.surface, whole, s)) << what;
            ++pans;
        }
    EXPECT_EQ(pans, 10);
}

TEST(OccluderScale, anEditedCoarseMapIsTheCoarseMapOfTheEditedMap) {
    // A tree planted, changed and taken away on one tile, again and again,
    // the fine map updated in place: the coarse map and picks updated over
    // the edit's part alone are those made whole from the edited map, and
    // the fine map changed somewhere each time.
    Params p;
    p.occluders = Occluders::solids;
    int edits = 0;
    for (int s : {2, 3}) {
        World w = default_world();
        const Rect b = w.placed.bounds;
        const int reach = occluder_reach(w.tileset);
        OccluderMap fine = build_occluders(w, p, b);
        OccluderMap c = coarse_occluders(fine, s);
        std::vector<std::uint8_t> picks = coarse_picks(fine.surface, c, s);
        for (const char* overlay : {"oak", "pine", "", "oak", ""}) {
            TileEdit e;
            e.col = 7, e.row = 7;
            e.overlays = *overlay ? std::vector<std::string>{overlay} : std::vector<std::string>{};
            const Rect changed = set_edits(w, {e});
            const Rect part{changed.x - reach, changed.y - reach, changed.w + 2 * reach, changed.h + 2 * reach};
            const OccluderMap before = c;
            update_occluders(fine, w, p, b, part);
            edit_coarse_occluders(c, picks, fine, part, s);
            const OccluderMap whole = coarse_occluders(fine, s);
            const std::string what = "scale " + std::to_string(s) + " after " + (*overlay ? overlay : "clearing");
            test::expect_same_map(c, whole, what);
            EXPECT_EQ(picks, coarse_picks(fine.surface, whole, s)) << what;
            EXPECT_FALSE(before.spans == whole.spans) << what << ": the edit changed the coarse map";
            ++edits;
        }
    }
    EXPECT_EQ(edits, 10);
}

TEST(OccluderScale, editedFramesTracedCoarseGiveTheFreshFramesBytes) {
    // The default scene at s = 2 under the game preset, a tree planted and
    // taken away by hand between frames (the coarse map then updated over
    // the edit alone): each frame equals a fresh state's frame.
    Scene scene = load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/default.json");
    World w = make_world(test::default_tileset(), scene);
    scene.params = builtin_preset("game");
    scene.params.occluder_scale = 2;
    // The view centred on the edited tile, so that its lights reach it.
    TileEdit probe;
    probe.col = 8, probe.row = 6;
    probe.overlays = std::vector<std::string>{"oak"};
    World copy = w;
    const Rect tile = set_edits(copy, {probe});
    ASSERT_FALSE(tile.empty());
    const Camera cam{double(tile.x + tile.w / 2 - 320), double(tile.y + tile.h / 2 - 180), 640, 360};
    scene.lights.push_back(Light{double(tile.x + tile.w / 2) + 0.5, double(tile.y + tile.h - 40) + 0.5});  // before the tree
    FrameState editing;
    render_frame(editing, w, scene, cam, 0);
    std::vector<std::uint8_t> last = editing.traced.texels;
    int f = 1;
    for (const char* overlay : {"oak", "", "pine"}) {
        TileEdit e = probe;
        e.overlays = *overlay ? std::vector<std::string>{overlay} : std::vector<std::string>{};
        set_edits(w, {e});
        const FrameReport rep = render_frame(editing, w, scene, cam, f);
        FrameState fresh;
        render_frame(fresh, w, scene, cam, f++);
        EXPECT_FALSE(rep.rebuilt.empty()) << overlay;
        EXPECT_LT(double(rep.rebuilt.w) * rep.rebuilt.h, 0.5 * double(editing.occluders.rect.w) * editing.occluders.rect.h)
            << "an edit, not a rebuild";
        ASSERT_EQ(editing.traced.rect, fresh.traced.rect) << overlay;
        EXPECT_EQ(editing.traced.texels, fresh.traced.texels) << overlay;
        EXPECT_EQ(editing.final.rgba, fresh.final.rgba) << overlay;
        EXPECT_NE(fresh.traced.texels, last) << overlay << ": the edit changes the light";
        last = fresh.traced.texels;
    }
}

TEST(OccluderScale, aPanningCameraTracedCoarseGivesTheFreshFramesBytes) {
    // The default scene under the game preset at s = 2, the camera moving
    // by odd steps (past the region's margin twice in 8 frames, where the
    // coarse map is updated in place): each frame equals a fresh state's
    // frame there.
    Scene scene = load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/default.json");
    const World w = make_world(test::default_tileset(), scene);
    scene.params = builtin_preset("game");
    scene.params.occluder_scale = 2;
    const Rect b = w.placed.bounds;
    FrameState moving;
    for (int f = 0; f < 8; ++f) {
        const Camera cam{double(b.x + 100 + 151 * f), double(b.y + 60 + 67 * f), 640, 360};
        render_frame(moving, w, scene, cam, f);
        FrameState fresh;
        render_frame(fresh, w, scene, cam, f);
        ASSERT_EQ(moving.traced.rect, fresh.traced.rect) << "frame " << f;
        EXPECT_EQ(moving.traced.texels, fresh.traced.texels) << "frame " << f;
        EXPECT_EQ(moving.final.rgba, fresh.final.rgba) << "frame " << f;
        EXPECT_GT(std::count_if(fresh.traced.texels.begin(), fresh.traced.texels.end(), [](std::uint8_t v) { return v != 0; }), 5000);
    }
}

TEST(OccluderScale, aSpritePixelWhoseBlockShowsTheGroundTakesItsSpritesAnswer) {
    // Fine columns 0..7 of one row band: ground at x = 0..2, an overlay
    // (instance 5) at x = 3..7, its height rising 2 a column. At s = 2 the
    // block of x = 2, 3 samples x = 2, the ground: x = 3 shows the overlay,
    // so it takes the next block's (x = 4, height 4 / 2 = 2, nearest its
    // own 3 / 2); x = 2 keeps its block. Every other pixel matches its block.
    Surface fine;
    fine.rect = {0, 0, 8, 4};
    fine.instance.assign(32, -1);
    fine.height.assign(32, 0.f);
    for (int y = 0; y < 4; ++y)
        for (int x = 3; x < 8; ++x) {
            fine.instance[std::size_t(y) * 8 + x] = 5;
            fine.height[std::size_t(y) * 8 + x] = float(2 * (x - 2));
        }
    OccluderMap m;
    m.rect = fine.rect;
    m.spans.assign(32, Spans{});
    m.surface = fine;
    index_occluders(m);
    const OccluderMap c = coarse_occluders(m, 2);
    const std::vector<std::uint8_t> picks = coarse_picks(fine, c, 2);
    ASSERT_EQ(picks.size(), 32u);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            const int want = x == 3 ? 3 : 0;  // 3: the block to the right
            EXPECT_EQ(picks[std::size_t(y) * 8 + x], want) << x << "," << y;
        }
    // A coarse answer with the ground's block lit and the overlay's dark:
    // the overlay's pixel at x = 3 is dark, the ground's at x = 2 lit.
    Params p;
    p.falloff_scale = 1e6;
    LightMask f;
    start_mask(f, 4, 2, 4, 2, p, Rect{0, 0, 9, 5});
    LightMask coarse;
    start_coarse_mask(coarse, f, 2, coarse_params(p));
    for (int y = 0; y < coarse.clip.h; ++y)
        for (int x = 0; x < coarse.clip.w; ++x)
            coarse.value[std::size_t(y) * coarse.clip.w + x] = coarse.clip.x + x <= 1 ? 255 : 0;
    upsample_mask(f, coarse, 2, p, &fine, &picks);
    EXPECT_NE(f.value[1 * 9 + 2], 0) << "the ground's pixel, its block lit";
    EXPECT_EQ(f.value[1 * 9 + 3], 0) << "the overlay's pixel, its sprite's block dark";
    LightMask blocks;
    start_mask(blocks, 4, 2, 4, 2, p, Rect{0, 0, 9, 5});
    upsample_mask(blocks, coarse, 2, p);
    EXPECT_NE(blocks.value[1 * 9 + 3], 0) << "without the picks it takes its block's, the ground's";
}

TEST(OccluderScale, framesTracedCoarseAreTheSameOnAnyThreadsAndNearTheFullOnes) {
    // The default scene's map and lights, under the game preset.
    Scene scene = load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/default.json");
    const World w = make_world(test::default_tileset(), scene);
    scene.params = builtin_preset("game");
    for (Occluders kind : {Occluders::solids, Occluders::shapes}) {
        scene.params.occluders = kind;
        scene.params.occluder_scale = 1;
        FrameState full;
        render_frame(full, w, scene, Camera{}, 0);
        for (int s : {2, 3}) {
            const std::string where = std::string(kind == Occluders::solids ? "solids" : "shapes") + " scale " + std::to_string(s);
            scene.params.occluder_scale = s;
            FrameState one, two;
            one.options.threads = 1;
            two.options.threads = 2;
            render_frame(one, w, scene, Camera{}, 0);
            render_frame(two, w, scene, Camera{}, 0);
            EXPECT_EQ(one.traced.texels, two.traced.texels) << where;
            EXPECT_EQ(one.final.rgba, two.final.rgba) << where;
            // Lit or dark as at full resolution but near shadows' edges: a
            // few percent of the texels the lights reach (2.8 and 4.1 % with
            // solids at 2 and 3 when written), at most 2.5 % a step.
            std::size_t reached = 0, changed = 0;
            ASSERT_EQ(one.traced.texels.size(), full.traced.texels.size());
            for (std::size_t i = 0; i < one.traced.texels.size(); ++i) {
                const bool a = full.traced.texels[i] != 0, b = one.traced.texels[i] != 0;
                reached += a || b;
                changed += a != b;
            }
            EXPECT_GT(reached, 50000u) << where << ": the lights must stand on the map";
            EXPECT_GT(changed, 0u) << where << ": the scale is honoured";
            EXPECT_LT(double(changed), 0.025 * s * double(reached)) << where;
            std::printf("%s: %zu of %zu texels lit or dark otherwise than at full resolution\n", where.c_str(),
                        changed, reached);
        }
    }
}

TEST(OccluderScale, aScaleOutsideOneToFourIsRefusedNamingTheField) {
    Params p;
    for (const char* bad : {"0", "5", "-1", "2.5"}) {
        try {
            set_param(p, "occluder_scale", bad, "preset.json");
            FAIL() << bad << " accepted";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("preset.json"), std::string::npos) << what;
            EXPECT_NE(what.find("occluder_scale"), std::string::npos) << what;
        }
    }
    set_param(p, "occluder_scale", "4", "preset.json");
    EXPECT_EQ(p.occluder_scale, 4);
}
