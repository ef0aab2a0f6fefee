// The editor on an endless world (editor.hpp, EndlessPlace): walking makes
// new windows, and the document (lights, edits, undo) keeps its place in the
// world; saving and reopening keep seed, edits and lights; the pixels are
// the CLI's for the same view.
#include <gtest/gtest.h>

#include <cmath>

#include "editor/editor.hpp"
#include "isolux/error.hpp"
#include "isolux/scene_file.hpp"
#include "test_util.hpp"

using namespace isolux;
using namespace isolux::app;
using isolux::test::TempDir;

namespace {

Scene endless_scene(double x, double y) {
    Scene s;
    s.endless = true;
    s.seed = "walker";
    s.camera = Camera{x, y, 800, 450};
    return s;
}

Rect view_rect(const Editor& e) {
    return Rect{int(std::floor(e.view.x)), int(std::floor(e.view.y)), 800, 450};
}

// The final frame of `view` (world pixels) as isolux-cli renders it: a
// window of its own around the view.
Image cli_frame(const Scene& world_scene, WorldRect view) {
    const Tileset ts = test::default_tileset();
    const ChunkRange c = endless_chunks(ts, world_scene.layout, view, endless_reach(world_scene, ts), "test");
    const EndlessWindow win = make_endless_window(ts, world_scene, c);
    const Rect v = rect_in_window(win, view);
    FrameState st;
    render_frame(st, win.world, scene_in_window(world_scene, win, view), Camera{double(v.x), double(v.y), v.w, v.h}, 0);
    return st.final;
}

// The editor's own frame of its view, on the CPU.
Image editor_frame(Editor& e) {
    e.frame.options.cpu_sprites = true;
    e.frame.options.cpu_blur_and_composite = true;
    const Rect v = view_rect(e);
    render_frame(e.frame, e.world, render_scene(e), Camera{double(v.x), double(v.y), v.w, v.h}, e.frame_number++);
    return e.frame.final;
}

// A floor sprite other than the one tile (col, row) has.
int other_floor(const Editor& e, int col, int row) {
    for (int i = 0; i < int(e.world.tileset.sprites.size()); ++i)
        if (e.world.tileset.sprites[std::size_t(i)].kind == SpriteKind::floor && i != e.world.map.at(col, row).floor)
            return i;
    return -1;
}

// A floor stroke on the tile under window pixel (x, y): another floor than
// its own, one undo step. Its tile (window tiles); false when none is there.
bool paint_floor(Editor& e, double x, double y, double now, int& col, int& row) {
    if (!tile_at(e.world.map, e.world.placed, x, y, col, row)) return false;
    e.brush.tool = Tool::floor;
    e.brush.floor = other_floor(e, col, row);
    begin_stroke(e, col, row);
    end_stroke(e, now);
    return true;
}

}  // namespace

TEST(EditorEndless, walkingFarKeepsLightsEditsAndUndoWhereTheyAreInTheWorld) {
    TempDir d{false};
    Editor e = make_editor(endless_scene(1000, 500), d.path);
    ASSERT_TRUE(e.endless.on);
    ASSERT_EQ(e.endless.windows_built, 1u);
    ASSERT_EQ(follow_view(e, view_rect(e)), Follow::kept);
    // A light and a floor edit near the view's centre.
    place_light(e, e.view.x + 400.3, e.view.y + 225.8, 1);
    int col = -1, row = -1;
    ASSERT_TRUE(paint_floor(e, e.view.x + 300, e.view.y + 200, 2, col, row));
    const Scene placed = endless_world_scene(e, e.scene);
    // The panels show the world's tiles, not the window's.
    EXPECT_NE(brush_preview(e, col, row).find("tile " + std::to_string(col + e.endless.chunks.col0) + ", " +
                                              std::to_string(row + e.endless.chunks.row0) + ":"),
              std::string::npos)
        << brush_preview(e, col, row);
    ASSERT_EQ(placed.lights.size(), 1u);
    ASSERT_EQ(placed.edits.size(), 1u);
    EXPECT_EQ(placed.lights[0].x, 1400.5);  // the pixel's centre, in world pixels
    EXPECT_EQ(placed.lights[0].y, 725.5);
    const WorldRect start = e.endless.last_view;

    // Walk 300 steps down and right (about 19,000 pixels): new windows.
    for (int k = 0; k < 300; ++k) {
        e.view.x += 64, e.view.y += 32;
        ASSERT_NE(follow_view(e, view_rect(e)), Follow::refused) << e.status;
    }
    EXPECT_GE(e.endless.windows_built, 4u);
    EXPECT_EQ(e.endless.last_view.x, start.x + 300 * 64);
    EXPECT_EQ(e.endless.last_view.y, start.y + 300 * 32);
    const Scene far = endless_world_scene(e, e.scene);
    EXPECT_EQ(far.lights, placed.lights);
    EXPECT_EQ(far.edits, placed.edits);
    // Undo and redo, windows later, act on the same world places.
    ASSERT_TRUE(undo(e, 3));
    EXPECT_TRUE(endless_world_scene(e, e.scene).edits.empty());
    ASSERT_TRUE(redo(e, 4));
    EXPECT_EQ(endless_world_scene(e, e.scene).edits, placed.edits);

    // Back where it started, the edited tile has its floor, and the frame
    // has the bytes isolux-cli renders there.
    for (int k = 0; k < 300; ++k) {
        e.view.x -= 64, e.view.y -= 32;
        ASSERT_NE(follow_view(e, view_rect(e)), Follow::refused) << e.status;
    }
    const TileEdit& t = placed.edits[0];
    EXPECT_EQ(e.world.map.at(int(t.col - e.endless.chunks.col0), int(t.row - e.endless.chunks.row0)).floor, e.brush.floor);
    const Image mine = editor_frame(e);
    const Image cli = cli_frame(endless_world_scene(e, e.scene), e.endless.last_view);
    ASSERT_EQ(mine.width, cli.width);
    ASSERT_EQ(mine.height, cli.height);
    EXPECT_TRUE(mine.rgba == cli.rgba);
    int lit = 0;
    for (std::size_t i = 0; i < mine.rgba.size(); i += 4) lit += mine.rgba[i] > 60;
    EXPECT_GT(lit, 1000);  // the light is there
}

TEST(EditorEndless, savingKeepsSeedEditsAndLightsAndReopensWhereItWas) {
    TempDir d;
    Editor e = make_editor(endless_scene(-5000, 3000), d.path);
    place_light(e, e.view.x + 100, e.view.y + 80, 1);
    int col = -1, row = -1;
    ASSERT_TRUE(paint_floor(e, e.view.x + 200, e.view.y + 150, 2, col, row));
    for (int k = 0; k < 60; ++k) {
        e.view.x -= 80;
        ASSERT_NE(follow_view(e, view_rect(e)), Follow::refused);
    }
    const Scene world = endless_world_scene(e, e.scene);
    const auto path = d.path / "walk.json";
    ASSERT_TRUE(save_scene_to(e, path)) << e.status;
    const Scene file = load_scene(path);
    EXPECT_TRUE(file.endless);
    EXPECT_EQ(file.seed, "walker");
    EXPECT_EQ(file.lights, world.lights);
    EXPECT_EQ(file.edits, world.edits);
    EXPECT_EQ(file.camera.x, double(e.endless.last_view.x));  // the view, in world pixels, with its size
    EXPECT_EQ(file.camera.width, 800);

    Editor f = make_editor(Scene{}, d.path);
    ASSERT_TRUE(load_scene_from(f, path, 5)) << f.status;
    EXPECT_TRUE(f.scene.endless);
    EXPECT_EQ(endless_world_scene(f, f.scene).lights, world.lights);
    EXPECT_EQ(endless_world_scene(f, f.scene).edits, world.edits);
    EXPECT_EQ(f.endless.last_view.x, e.endless.last_view.x);
    // The reopened view has the pixels of the view it was saved at.
    EXPECT_TRUE(editor_frame(f).rgba == editor_frame(e).rgba);
    // A finite map opened after it is finite again.
    ASSERT_TRUE(undo(f, 6));
    EXPECT_FALSE(f.scene.endless);
    EXPECT_FALSE(f.endless.on);
}

TEST(EditorEndless, theMapTurnsEndlessAndBackKeepingWhereLightsStand) {
    TempDir d{false};
    Scene s;
    s.width = s.height = 40;
    Editor e = make_editor(s, d.path);
    const Rect b = e.world.placed.bounds;
    place_light(e, b.x + b.w / 2 + 0.5, b.y + b.h / 2 + 0.5, 1);
    const std::vector<Light> finite = e.scene.lights;
    MapFields m = map_fields(e);
    m.endless = true;
    regenerate(e, m, 2);
    ASSERT_TRUE(e.scene.endless) << e.status;
    // On the map's tiles the endless world is the map: the light's tile is
    // the same tile.
    const Light& l = e.scene.lights[0];
    int ce = -1, re = -1, cf = -1, rf = -1;
    ASSERT_TRUE(tile_at(e.world.map, e.world.placed, l.x, l.y, ce, re));
    {
        Editor g = make_editor(s, d.path);
        ASSERT_TRUE(tile_at(g.world.map, g.world.placed, finite[0].x, finite[0].y, cf, rf));
    }
    EXPECT_EQ(ce + e.endless.chunks.col0, cf);
    EXPECT_EQ(re + e.endless.chunks.row0, rf);
    m = map_fields(e);
    m.endless = false;
    m.width = m.height = 40;
    regenerate(e, m, 3);
    ASSERT_FALSE(e.scene.endless) << e.status;
    EXPECT_EQ(e.scene.lights, finite);
    // Undo walks back through both.
    ASSERT_TRUE(undo(e, 4));
    EXPECT_TRUE(e.scene.endless);
    ASSERT_TRUE(undo(e, 5));
    EXPECT_FALSE(e.scene.endless);
    EXPECT_EQ(e.scene.lights, finite);
}

TEST(EditorEndless, theOverviewShowsTheWindowsChunksEditsAndLights) {
    TempDir d{false};
    Editor e = make_editor(endless_scene(0, 0), d.path);
    place_light(e, e.view.x + 400, e.view.y + 225, 1);
    const Overview o = endless_overview(e, 4);
    ASSERT_EQ(o.chunks.size(), 81u);
    int in_window = 0, lights = 0;
    for (const OverviewChunk& c : o.chunks) in_window += c.in_window, lights += c.lights;
    EXPECT_EQ(in_window, (e.endless.chunks.cols / chunk_tiles) * (e.endless.chunks.rows / chunk_tiles));
    EXPECT_EQ(lights, 1);
    EXPECT_EQ(o.chunks[40].lights, 1);  // the light is at the view's centre: the middle chunk
    EXPECT_TRUE(o.chunks[40].in_window);
}

TEST(EditorEndless, aViewTooWideOrTooFarIsRefusedAndTheWindowStays) {
    TempDir d{false};
    Editor e = make_editor(endless_scene(0, 0), d.path);
    const ChunkRange before = e.endless.chunks;
    EXPECT_EQ(follow_view(e, Rect{0, 0, 20000, 12000}), Follow::refused);
    EXPECT_NE(e.status.find("zoom in"), std::string::npos) << e.status;
    EXPECT_TRUE(e.endless.chunks == before);
    std::int64_t x = 0, y = 0;
    const Tileset ts = test::default_tileset();
    endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, max_endless_tile + 100, 0, x, y);
    try {
        open_endless(e, endless_scene(double(x), double(y)), WorldRect{x, y, 800, 450}, "far.json");
        FAIL() << "a view beyond the world's tiles was opened";
    } catch (const Error& err) {
        EXPECT_NE(std::string(err.what()).find("far.json"), std::string::npos) << err.what();
        EXPECT_NE(std::string(err.what()).find("1000000000000"), std::string::npos) << err.what();
    }
    EXPECT_TRUE(e.endless.chunks == before);
}

TEST(EditorEndless, editsAHundredBillionTilesOutAreSavedAndReopened) {
    // Edits are 64-bit: painted at tile (1e11, -1e11) they are saved in the
    // world's tiles and reopen onto the same tiles.
    TempDir d;
    std::int64_t x = 0, y = 0;
    const Tileset ts = test::default_tileset();
    endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, 100'000'000'000, -100'000'000'000, x, y);
    Editor e = make_editor(endless_scene(double(x) - 400, double(y) - 225), d.path);
    int col = -1, row = -1;
    ASSERT_TRUE(paint_floor(e, e.view.x + 400, e.view.y + 225, 1, col, row));
    EXPECT_EQ(col + e.endless.chunks.col0, 100'000'000'000);
    EXPECT_EQ(row + e.endless.chunks.row0, -100'000'000'000);
    const auto path = d.path / "far.json";
    ASSERT_TRUE(save_scene_to(e, path)) << e.status;
    const Scene file = load_scene(path);
    ASSERT_EQ(file.edits.size(), 1u);
    EXPECT_EQ(file.edits[0].col, 100'000'000'000);
    EXPECT_EQ(file.edits[0].row, -100'000'000'000);
    Editor f = make_editor(file, d.path);
    EXPECT_EQ(f.world.map.at(int(file.edits[0].col - f.endless.chunks.col0), int(file.edits[0].row - f.endless.chunks.row0)).floor,
              e.brush.floor);
}
