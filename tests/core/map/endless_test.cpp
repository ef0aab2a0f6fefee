// Endless worlds (endless.hpp): windows of chunks around a view show what a
// finite map shows there, far from the origin as near it, whichever window
// holds a place.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "isolux/endless.hpp"
#include "isolux/error.hpp"
#include "isolux/frame.hpp"
#include "isolux/scene_file.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {

// The final frame of `view` (endless pixels) lit by the scene's lights, from
// the window of chunks endless_chunks gives for it.
Image endless_frame(const Scene& s, WorldRect view, EndlessWindow* out_window = nullptr) {
    const Tileset ts = test::default_tileset();
    const ChunkRange c = endless_chunks(ts, s.layout, view, endless_reach(s, ts), "test");
    EndlessWindow win = make_endless_window(ts, s, c);
    const Scene local = scene_in_window(s, win, view);
    const Rect v = rect_in_window(win, view);
    FrameState st;
    render_frame(st, win.world, local, Camera{double(v.x), double(v.y), v.w, v.h}, 0);
    if (out_window) *out_window = std::move(win);
    return st.final;
}

Scene lit(std::int64_t x, std::int64_t y, const Params& p) {
    Scene s;
    s.endless = true;
    s.params = p;
    s.params.falloff_scale = 8;
    s.lights = {Light{double(x) + 200.5, double(y) + 150.5}, Light{double(x) + 430.5, double(y) + 260.5}};
    s.lights[1].r = 255, s.lights[1].g = 180, s.lights[1].b = 90;
    return s;
}

int differing(const Image& a, int ax, int ay, const Image& b, int bx, int by, int w, int h) {
    int n = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 4; ++k) n += a.at(ax + x, ay + y)[k] != b.at(bx + x, by + y)[k];
    return n;
}

}  // namespace

TEST(Endless, aWindowShowsWhatAFiniteMapShowsThere) {
    // A 40x40 map is the endless world's tiles (0..39, 0..39): a view in its
    // middle, lit by the same lights, has the same pixels from both, with the
    // paper's tracer and with solids.
    for (const char* preset : {"paper", "game"}) {
        Scene finite;
        finite.width = finite.height = 40;
        const World w = make_world(test::default_tileset(), finite);
        // World pixel p of the finite map is endless pixel p - shift.
        const Rect fv{w.placed.bounds.x + w.placed.bounds.w / 2 - 300, w.placed.bounds.y + w.placed.bounds.h / 2 - 200, 600, 400};
        const WorldRect ev{fv.x - w.placed.shift_x, fv.y - w.placed.shift_y, fv.w, fv.h};
        Scene e = lit(ev.x, ev.y, builtin_preset(preset));
        finite.params = e.params;
        for (const Light& l : e.lights) {
            Light f = l;
            f.x += w.placed.shift_x;
            f.y += w.placed.shift_y;
            finite.lights.push_back(f);
        }
        FrameState st;
        render_frame(st, w, finite, Camera{double(fv.x), double(fv.y), fv.w, fv.h}, 0);
        const Image got = endless_frame(e, ev);
        ASSERT_EQ(got.width, 600);
        EXPECT_EQ(differing(got, 0, 0, st.final, 0, 0, 600, 400), 0) << preset;
    }
}

TEST(Endless, onePlaceFarAwayHasTheSamePixelsFromEveryWindowThatHoldsIt) {
    // Near tile (1e9, 1e9): two views that overlap, each lit from its own
    // window of chunks (a different one), agree where they overlap; so do
    // two views reached from either side, with solids.
    const Tileset ts = test::default_tileset();
    std::int64_t x = 0, y = 0;
    endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, 1'000'000'000, 1'000'000'000, x, y);
    for (const char* preset : {"paper", "game"}) {
        const Scene s = lit(x, y, builtin_preset(preset));
        EndlessWindow wa, wb;
        const WorldRect a{x, y, 640, 400}, b{x + 300 - 1024 * 2, y + 170, 640 + 2048, 400};
        const Image ia = endless_frame(s, a, &wa), ib = endless_frame(s, b, &wb);
        EXPECT_FALSE(wa.chunks == wb.chunks);  // two windows
        EXPECT_EQ(differing(ia, 300, 170, ib, 2048, 0, 340, 230), 0) << preset;
        int lit_pixels = 0;
        for (std::size_t i = 0; i < ia.rgba.size(); i += 4) lit_pixels += ia.rgba[i] > 60;
        EXPECT_GT(lit_pixels, 1000) << preset;  // the lights are there
    }
}

TEST(Endless, chunksAreWholeAndTheWorldEndsAtItsBound) {
    const Tileset ts = test::default_tileset();
    Scene s;
    s.endless = true;
    const ChunkRange c = endless_chunks(ts, Layout::diamond, WorldRect{-1234567, 7654321, 900, 500}, endless_reach(s, ts), "t");
    EXPECT_EQ(((c.col0 % chunk_tiles) + chunk_tiles) % chunk_tiles, 0);
    EXPECT_EQ(((c.row0 % chunk_tiles) + chunk_tiles) % chunk_tiles, 0);
    EXPECT_EQ(c.cols % chunk_tiles, 0);
    EXPECT_LE(c.cols, 4 * chunk_tiles);  // a view's worth, not a world's
    std::int64_t x = 0, y = 0;
    endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, max_endless_tile + 10, 0, x, y);
    try {
        endless_chunks(ts, Layout::diamond, WorldRect{x, y, 100, 100}, 0, "far.json");
        FAIL() << "a view past the bound was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("far.json"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("1000000000000"), std::string::npos) << e.what();
    }
    // A finite map's builder refuses an endless scene by name.
    EXPECT_THROW(make_world(ts, s, "level.json"), Error);
    // A view has a bounded map's megapixel cap, checked before any chunk is made.
    try {
        endless_chunks(ts, Layout::diamond, WorldRect{0, 0, 20000, 13500}, 0, "wide.json");
        FAIL() << "a 270-megapixel view was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("wide.json"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("megapixel"), std::string::npos) << e.what();
    }
    EXPECT_NO_THROW(endless_chunks(ts, Layout::diamond, WorldRect{0, 0, 16384, 16384}, 0, "t"));
}

TEST(Endless, editsApplyWhereverTheyAreAndScenesSayEndless) {
    // An edit far out clears its tile in the window that holds it.
    const Tileset ts = test::default_tileset();
    Scene s;
    s.endless = true;
    s.edits.push_back(TileEdit{1'000'000'005, -1'000'000'003, std::string("water"), std::vector<std::string>{}});
    std::int64_t x = 0, y = 0;
    endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, 1'000'000'005, -1'000'000'003, x, y);
    const ChunkRange c = endless_chunks(ts, Layout::diamond, WorldRect{x - 100, y - 100, 200, 200}, 0, "t");
    const EndlessWindow win = make_endless_window(ts, s, c);
    const Tile& t = win.world.map.at(int(1'000'000'005 - c.col0), int(-1'000'000'003 - c.row0));
    EXPECT_EQ(ts.sprites[std::size_t(t.floor)].name, "water");
    EXPECT_EQ(t.overlay_count, 0);
    // The scene file says "endless" for both sides, and refuses one alone.
    const Scene back = scene_from_json(scene_to_json(s), "round trip");
    EXPECT_TRUE(back.endless);
    EXPECT_THROW(scene_from_json(R"({"width": "endless", "height": 12})", "half.json"), Error);
    // A Tiled map has its own edge: a scene naming one cannot also be endless.
    try {
        scene_from_json(R"({"width": "endless", "height": "endless", "map": "level.tmx"})", "both.json");
        FAIL() << "a scene with a map and an endless size was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("both.json: map"), std::string::npos) << e.what();
    }
}

TEST(Endless, aWalkKeepsItsWindowAChunkAtATimeAndEveryFrameIsTheSame) {
    // A camera walking 120 px a frame for 60 frames far out: each frame has
    // the pixels of a fresh window around its view; the window is remade
    // once a chunk or so, not once a frame.
    const Tileset ts = test::default_tileset();
    std::int64_t x = 0, y = 0;
    endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, 3'000'000, -7'000'000, x, y);
    Scene s = lit(x, y, builtin_preset("game"));
    EndlessState st;
    int checked = 0;
    for (int f = 0; f < 60; ++f) {
        const WorldRect view{x + 120 * f, y + 60 * f, 480, 320};
        for (Light& l : s.lights) l.x += 120, l.y += 60;  // carried with the camera
        render_endless_frame(st, ts, s, view, f);
        if (f % 15 == 14) {
            EXPECT_EQ(differing(st.frame.final, 0, 0, endless_frame(s, view), 0, 0, 480, 320), 0) << "frame " << f;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 4);
    EXPECT_GE(st.windows_built, 2u);   // it walked out of the first window
    EXPECT_LE(st.windows_built, 8u);  // 7200 px: a few chunks' worth (a chunk spans 2048 px)
}

TEST(Endless, aWalkMakesEachChunkAndObstacleBlockOnceAndTheyAreTheFreshOnes) {
    // The paper's preset (the obstacle map stops its rays) walking far out:
    // each frame's obstacle map equals a fresh window's over the part both
    // cover, its pixels equal a fresh window's, and later windows copy the
    // chunks and obstacle blocks earlier ones made instead of making them
    // again.
    const Tileset ts = test::default_tileset();
    std::int64_t x = 0, y = 0;
    endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, -5'000'000, 9'000'000, x, y);
    Scene s = lit(x, y, builtin_preset("paper"));
    EndlessState st;
    int checked = 0;
    for (int f = 0; f < 96; ++f) {
        const WorldRect view{x + 150 * f, y + 40 * f, 480, 320};
        for (Light& l : s.lights) l.x += 150, l.y += 40;
        render_endless_frame(st, ts, s, view, f);
        if (f % 24 != 23) continue;
        ++checked;
        EndlessWindow fresh;
        const Image image = endless_frame(s, view, &fresh);
        EXPECT_EQ(differing(st.frame.final, 0, 0, image, 0, 0, 480, 320), 0) << "frame " << f;
        FrameState alone;
        const Rect v = rect_in_window(fresh, view);
        render_frame(alone, fresh.world, scene_in_window(s, fresh, view), Camera{double(v.x), double(v.y), v.w, v.h}, 0);
        // The two obstacle maps over the world pixels both cover.
        const Mask& a = st.frame.obstacles;
        const Mask& b = alone.obstacles;
        const std::int64_t ax = st.window.origin_x, ay = st.window.origin_y, bx = fresh.origin_x, by = fresh.origin_y;
        const std::int64_t x0 = std::max(a.x0 + ax, b.x0 + bx), x1 = std::min(a.x0 + a.width + ax, b.x0 + b.width + bx);
        const std::int64_t y0 = std::max(a.y0 + ay, b.y0 + by), y1 = std::min(a.y0 + a.height + ay, b.y0 + b.height + by);
        ASSERT_GT(x1 - x0, 480);
        ASSERT_GT(y1 - y0, 320);
        long differ = 0, set = 0;
        for (std::int64_t wy = y0; wy < y1; ++wy)
            for (std::int64_t wx = x0; wx < x1; ++wx) {
                const bool pa = a.get(int(wx - ax), int(wy - ay)), pb = b.get(int(wx - bx), int(wy - by));
                differ += pa != pb;
                set += pa;
            }
        EXPECT_EQ(differ, 0) << "frame " << f;
        EXPECT_GT(set, 100) << "frame " << f;  // there are obstacles to compare
    }
    EXPECT_EQ(checked, 4);
    EXPECT_GE(st.windows_built, 3u);
    const EndlessCache& c = st.cache;
    EXPECT_EQ(c.chunks_made, c.chunks.size());  // none made twice (none dropped yet)
    EXPECT_GT(c.chunks_reused, 0u);             // a new window reuses the chunks it shares
    EXPECT_GT(c.blocks_copied, c.blocks_built);  // a rebuilt region copies the blocks it had
    std::printf("# chunks made %llu, reused %llu; blocks built %llu, copied %llu\n", (unsigned long long)c.chunks_made,
                (unsigned long long)c.chunks_reused, (unsigned long long)c.blocks_built, (unsigned long long)c.blocks_copied);
    EXPECT_GT(c.blocks_copied, 0u);
    EXPECT_LE(c.chunks.size(), max_kept_chunks);
    EXPECT_LE(c.blocks.size(), max_obstacle_blocks);
    // A changed edit makes a new window (the old one shows the old tiles).
    const std::uint64_t windows = st.windows_built;
    s.edits.push_back(TileEdit{0, 0, "water", std::nullopt});
    render_endless_frame(st, ts, s, WorldRect{x + 150 * 95, y + 40 * 95, 480, 320}, 96);
    EXPECT_EQ(st.windows_built, windows + 1);
}
