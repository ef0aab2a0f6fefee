// The editor's actions (what the panels and scripted input call), with no GL.
#include <gtest/gtest.h>

#include <fstream>
#include <sys/wait.h>
#include <unistd.h>
#include <cmath>

#include "editor/editor.hpp"
#include "editor/overlays.hpp"
#include "test_util.hpp"
#include "isolux/isolux.hpp"

using namespace isolux;
using namespace isolux::app;
using isolux::test::TempDir;
namespace fs = std::filesystem;

namespace {
// The process id of a process that has ended: a window that crashed.
long dead_window() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return long(child);
}

Scene small_scene() {
    Scene s;
    s.width = s.height = 6;
    return s;
}
}  // namespace

TEST(Editor, placingALightIsOneUndoStepAndRedoRestoresIt) {
    TempDir c{false};
    Editor e = make_editor(small_scene(), c.path);
    place_light(e, 100.2, 50.7, 0);
    ASSERT_EQ(e.scene.lights.size(), 1u);
    EXPECT_EQ(e.scene.lights[0].x, 100.5);  // the pixel's centre
    EXPECT_TRUE(e.dirty);
    EXPECT_TRUE(undo(e, 1));
    EXPECT_TRUE(e.scene.lights.empty());
    EXPECT_TRUE(redo(e, 2));
    EXPECT_EQ(e.scene.lights.size(), 1u);
    EXPECT_FALSE(redo(e, 3));
}

TEST(Editor, aSliderDragIsOneUndoStep) {
    TempDir c{false};
    Editor e = make_editor(small_scene(), c.path);
    const Scene before = e.scene;
    for (double v : {0.41, 0.5, 0.62, 0.7}) e.scene.params.ambient_clarity = v;  // live while dragging
    commit_edit(e, before, 0);                                                   // released
    EXPECT_EQ(e.undo_stack.size(), 1u);
    undo(e, 1);
    EXPECT_EQ(e.scene.params.ambient_clarity, 0.4);
}

// Each undo step holds a whole document: a large painted level's history is
// bounded by its bytes as well as its steps, the oldest dropped first.
TEST(Editor, theUndoHistoryOfALargeLevelStaysWithinItsBytes) {
    TempDir c{false};
    Editor e = make_editor(small_scene(), c.path);
    Scene big = e.scene;
    for (int i = 0; i < 100000; ++i)
        big.edits.push_back(TileEdit{i, i, std::string("grass"), std::vector<std::string>{"tree", "rock"}});
    ASSERT_GT(scene_bytes(big), max_undo_bytes / 32) << "each step should hold megabytes";
    for (int k = 0; k < 64; ++k) {
        big.lights = {Light{double(k), 0}};  // each step a document of its own
        commit_edit(e, big, k);
        std::size_t held = 0;
        for (const HistoryStep& h : e.undo_stack) held += h.bytes;
        EXPECT_LE(held, max_undo_bytes) << "after step " << k;
    }
    EXPECT_GE(e.undo_stack.size(), 2u);
    EXPECT_LT(e.undo_stack.size(), 64u);
    // The newest steps are the ones kept: an undo gives the last document committed.
    ASSERT_TRUE(undo(e, 100));
    ASSERT_EQ(e.scene.lights.size(), 1u);
    EXPECT_EQ(e.scene.lights[0].x, 63);
    EXPECT_EQ(e.redo_stack.size(), 1u);
    EXPECT_EQ(e.redo_stack[0].bytes, scene_bytes(e.redo_stack[0].scene));
}

TEST(Editor, outOfRangeParametersAreRefusedWithAMessage) {
    TempDir c{false};
    Editor e = make_editor(small_scene(), c.path);
    Params p = e.scene.params;
    p.noise_window = 0;
    set_params(e, p, 0);
    EXPECT_EQ(e.scene.params.noise_window, 3);
    EXPECT_TRUE(e.status_error);
    EXPECT_NE(e.status.find("noise_window"), std::string::npos);
    EXPECT_TRUE(e.undo_stack.empty());
}

TEST(Editor, aCorruptSceneOrTilesetNeverReplacesTheDocument) {
    TempDir c{false};
    fs::create_directories(c.path);
    Editor e = make_editor(small_scene(), c.path);
    place_light(e, 10, 10, 0);
    std::ofstream(c.path / "bad.json") << "{\"lights\": [";
    EXPECT_FALSE(load_scene_from(e, c.path / "bad.json", 1));
    EXPECT_TRUE(e.status_error);
    EXPECT_NE(e.status.find("bad.json"), std::string::npos);
    EXPECT_EQ(e.scene.lights.size(), 1u);
    const auto revision = e.world.revision;
    EXPECT_FALSE(load_tileset_from(e, c.path / "missing.json", 2));
    EXPECT_TRUE(e.scene.tileset.empty());
    EXPECT_EQ(e.world.revision, revision);
    EXPECT_FALSE(import_preset(e, c.path / "bad.json", 3));
    EXPECT_EQ(e.scene.lights.size(), 1u);
}

TEST(Editor, regenerateBuildsTheSeedsMapAndUndoRestoresTheOldOne) {
    TempDir c{false};
    Editor e = make_editor(small_scene(), c.path);
    const auto tiles = e.world.map.tiles.size();
    regenerate(e, "other", 9, 4, Layout::staggered, 0);
    EXPECT_EQ(e.world.map.width, 9);
    EXPECT_EQ(e.world.map.layout, Layout::staggered);
    undo(e, 1);
    EXPECT_EQ(e.world.map.tiles.size(), tiles);
    EXPECT_EQ(e.scene.seed, "isolux");
}

TEST(Editor, unsavedWorkIsAutosavedAndRecovered) {
    TempDir c{false};
    fs::path crashed;
    {
        Editor e = make_editor(small_scene(), c.path);
        e.window = dead_window();  // the window that will crash
        place_light(e, 30, 40, 10.0);
        EXPECT_FALSE(autosave_tick(e, 10.5));  // not yet due
        EXPECT_TRUE(autosave_tick(e, 10.0 + autosave_delay));
        EXPECT_TRUE(fs::exists(autosave_path(e)));
        crashed = autosave_path(e);
        // ... and the app crashes here.
    }
    Editor e = make_editor(small_scene(), c.path);
    ASSERT_TRUE(has_recovery(e));
    EXPECT_EQ(recovery_path(e), crashed);
    EXPECT_TRUE(recover_autosave(e, 0));
    EXPECT_FALSE(fs::exists(crashed));      // the dead window's file goes...
    EXPECT_TRUE(fs::exists(autosave_path(e)));  // ...once this window holds the work
    ASSERT_EQ(e.scene.lights.size(), 1u);
    EXPECT_EQ(e.scene.lights[0].y, 40.5);
    EXPECT_TRUE(e.dirty);  // recovered work is unsaved until saved
    EXPECT_TRUE(save_scene_to(e, c.path / "saved.json"));
    EXPECT_FALSE(e.dirty);
    EXPECT_FALSE(has_recovery(e));  // saving clears the autosave
    EXPECT_EQ(e.settings.recent.size(), 1u);
}

TEST(Editor, eachWindowHasItsOwnAutosaveAndNeverTouchesAnotherLiveOne) {
    TempDir c{false};
    Editor a = make_editor(small_scene(), c.path);  // this process: a window that runs
    Editor b = make_editor(small_scene(), c.path);
    b.window = long(::getppid());                    // another window that runs
    place_light(a, 30, 40, 1.0);
    place_light(b, 50, 60, 1.0);
    ASSERT_TRUE(autosave_tick(a, 1.0 + autosave_delay));
    ASSERT_TRUE(autosave_tick(b, 1.0 + autosave_delay));
    EXPECT_NE(autosave_path(a), autosave_path(b));
    // A live window's autosave is never offered to another, nor removed by its clean exit.
    EXPECT_FALSE(has_recovery(a));
    EXPECT_FALSE(has_recovery(b));
    discard_autosave(b);
    EXPECT_TRUE(fs::exists(autosave_path(a)));
    EXPECT_FALSE(fs::exists(autosave_path(b)));
    // An older version's single autosave.json counts as a dead window's.
    fs::copy_file(autosave_path(a), c.path / "autosave.json");
    EXPECT_EQ(recovery_path(b), c.path / "autosave.json");
    discard_recovery(b);
    EXPECT_FALSE(fs::exists(c.path / "autosave.json"));
    EXPECT_TRUE(fs::exists(autosave_path(a)));
}

TEST(Editor, settingsSurviveACorruptFile) {
    TempDir c{false};
    fs::create_directories(c.path);
    std::ofstream(c.path / "settings.json") << "not json";
    std::string warning;
    Settings s = load_settings(c.path, &warning);
    EXPECT_TRUE(s.recent.empty());
    EXPECT_NE(warning.find("settings.json"), std::string::npos);
    for (int i = 0; i < 12; ++i) add_recent(s, "f" + std::to_string(i));
    add_recent(s, "f5");
    EXPECT_EQ(s.recent.size(), 8u);
    EXPECT_EQ(s.recent.front().path, "f5");
    save_settings(c.path, s);
    EXPECT_EQ(load_settings(c.path).recent, s.recent);
}

TEST(Editor, theCharactersLightIsRenderedButNeverSaved) {
    TempDir c{false};
    Editor e = make_editor(small_scene(), c.path);
    e.character.enabled = true;
    e.character.x = 300;
    e.character.y = 200;
    EXPECT_EQ(render_scene(e).lights.size(), 1u);
    EXPECT_TRUE(e.scene.lights.empty());
}

namespace {
// What the Map panel shows is the document, and the world is built from it.
void expect_map_panel_matches(const Editor& e, const char* when) {
    const MapFields shown = map_fields(e);
    EXPECT_EQ(shown.seed, e.scene.seed) << when;
    EXPECT_EQ(shown.width, e.scene.width) << when;
    EXPECT_EQ(shown.height, e.scene.height) << when;
    EXPECT_EQ(shown.layout, e.scene.layout) << when;
    EXPECT_EQ(shown.width, e.world.map.width) << when;
    EXPECT_EQ(shown.height, e.world.map.height) << when;
    EXPECT_EQ(shown.layout, e.world.map.layout) << when;
    EXPECT_EQ(e.scene.seed, e.world_source.seed) << when;
}
}  // namespace

TEST(Editor, theMapPanelShowsTheDocumentAfterUndoRedoOpenAndRecover) {
    // The bug a new user met: random seed, 32x32, regenerate, Ctrl+Z: the map
    // went back to 12x12 but the panel said 32x32, and Regenerate rebuilt 32x32.
    TempDir c{false};
    fs::create_directories(c.path);
    Scene start = small_scene();
    start.width = start.height = 12;
    Editor e = make_editor(start, c.path);
    regenerate(e, "moss-42", 12, 12, Layout::diamond, 0);
    regenerate(e, "moss-42", 32, 32, Layout::diamond, 1);
    expect_map_panel_matches(e, "after regenerate");
    ASSERT_TRUE(undo(e, 2));
    expect_map_panel_matches(e, "after undo");
    EXPECT_EQ(map_fields(e).width, 12);
    // Regenerate with what the panel shows builds what it shows.
    const MapFields shown = map_fields(e);
    regenerate(e, shown.seed, shown.width, shown.height, shown.layout, 3);
    EXPECT_EQ(e.world.map.width, 12);
    ASSERT_TRUE(redo(e, 5));  // regenerating what is shown changed nothing: redo still goes to 32x32
    expect_map_panel_matches(e, "after redo");
    EXPECT_EQ(map_fields(e).width, 32);

    Scene other = small_scene();
    other.seed = "opened";
    other.width = 7;
    other.height = 5;
    other.layout = Layout::staggered;
    save_scene(c.path / "other.json", other);
    ASSERT_TRUE(load_scene_from(e, c.path / "other.json", 6));
    expect_map_panel_matches(e, "after open scene");
    EXPECT_EQ(map_fields(e).seed, "opened");

    regenerate(e, "unsaved", 9, 9, Layout::paper, 7);
    e.window = dead_window();  // this window crashes after its autosave
    EXPECT_TRUE(autosave_tick(e, 7 + autosave_delay));
    Editor fresh = make_editor(small_scene(), c.path);
    ASSERT_TRUE(recover_autosave(fresh, 0));
    expect_map_panel_matches(fresh, "after recover");
    EXPECT_EQ(map_fields(fresh).seed, "unsaved");
    EXPECT_EQ(map_fields(fresh).width, 9);
}

TEST(Editor, aSceneSavedInAFolderNamedPresetsReopensAsAScene) {
    TempDir c{false};
    fs::create_directories(c.path / "presets");
    Editor e = make_editor(small_scene(), c.path);
    place_light(e, 50, 60, 0);
    Params p = e.scene.params;
    p.blur_radius = 5;
    set_params(e, p, 0);
    ASSERT_TRUE(save_scene_to(e, c.path / "presets" / "level.json"));
    ASSERT_EQ(e.settings.recent.front().kind, FileKind::scene);
    ASSERT_TRUE(export_preset(e, c.path / "tuned.json"));
    ASSERT_EQ(e.settings.recent.front().kind, FileKind::preset);

    // The kinds survive a restart.
    save_settings(c.path, e.settings);
    Editor again = make_editor(small_scene(), c.path);
    ASSERT_EQ(again.settings.recent.size(), 2u);
    const RecentFile scene_entry = again.settings.recent[1];
    EXPECT_EQ(scene_entry.kind, FileKind::scene);
    ASSERT_TRUE(open_recent(again, scene_entry, 1));
    EXPECT_EQ(again.scene.lights.size(), 1u);  // opened as the scene it is, not as a preset
    EXPECT_EQ(again.scene.params.blur_radius, 5);
}

TEST(Editor, theViewIsNotPartOfTheDocumentButIsSavedWithIt) {
    TempDir c{false};
    fs::create_directories(c.path);
    Scene s = small_scene();
    s.camera = {40, 30, 0, 0};
    Editor e = make_editor(s, c.path);
    EXPECT_EQ(e.view.x, 40);
    EXPECT_EQ(e.scene.camera, Camera{});  // one camera: the view
    e.view.x = 100;  // panning is not an edit
    EXPECT_FALSE(e.dirty);
    EXPECT_TRUE(e.undo_stack.empty());
    ASSERT_TRUE(save_scene_to(e, c.path / "v.json"));
    EXPECT_EQ(load_scene(c.path / "v.json").camera.x, 100);
    reset_view(e);
    EXPECT_EQ(e.view.x, 0);
    EXPECT_EQ(e.view.zoom, 1);
}

TEST(Editor, anInspectedFootprintMovesTheObstacleAndIsSavedIntoTheManifest) {
    TempDir c{false};
    fs::create_directories(c.path / "ts");
    for (const auto& f : fs::directory_iterator(fs::path(ISOLUX_ASSETS_DIR) / "default"))
        fs::copy_file(f.path(), c.path / "ts" / f.path().filename());
    Scene s = small_scene();
    s.tileset = (c.path / "ts" / "tileset.json").string();
    Editor e = make_editor(s, c.path);
    int oak = -1;
    for (int i = 0; i < int(e.world.tileset.sprites.size()); ++i)
        if (e.world.tileset.sprites[std::size_t(i)].name == "oak") oak = i;
    ASSERT_GE(oak, 0);
    const auto revision = e.world.revision;
    FootprintSpec none;
    none.mode = FootprintMode::none;
    set_sprite_footprint(e, oak, none);
    EXPECT_NE(e.world.revision, revision);  // caches rebuild
    EXPECT_TRUE(e.footprints_unsaved);
    EXPECT_TRUE(e.undo_stack.empty());      // not a scene edit
    ASSERT_TRUE(save_footprints(e));
    const Tileset back = load_tileset(c.path / "ts" / "tileset.json");
    EXPECT_EQ(back.sprites[std::size_t(oak)].footprint.mode, FootprintMode::none);
    EXPECT_EQ(back.sprites[std::size_t(oak)].shape, e.world.tileset.sprites[std::size_t(oak)].shape);  // the rest kept
}

TEST(View, fitShowsTheWholeMapAndZoomStaysInRange) {
    TempDir d;
    Scene s;
    s.width = s.height = 64;
    Editor e = make_editor(s, d.path);
    const Rect area{350, 30, 900, 800};
    fit_view(e.view, e.world.placed.bounds, area);
    const Rect b = e.world.placed.bounds;
    // The map's corners land inside the area.
    const double x0 = (b.x - e.view.x) * e.view.zoom, y0 = (b.y - e.view.y) * e.view.zoom;
    const double x1 = (b.x + b.w - e.view.x) * e.view.zoom, y1 = (b.y + b.h - e.view.y) * e.view.zoom;
    EXPECT_GE(x0, area.x);
    EXPECT_GE(y0, area.y);
    EXPECT_LE(x1, area.x + area.w);
    EXPECT_LE(y1, area.y + area.h);
    EXPECT_LT(e.view.zoom, 0.25);  // below the old floor of 0.25: a 64x64 map needs it
    EXPECT_GE(e.view.zoom, min_zoom);
    // A 128x128 map (16384 pixels wide) at the floor of 1/16: centred, its
    // middle shown rather than an empty screen.
    s.width = s.height = 128;
    Editor big = make_editor(s, d.path);
    fit_view(big.view, big.world.placed.bounds, area);
    EXPECT_EQ(big.view.zoom, min_zoom);
    const Rect bb = big.world.placed.bounds;
    EXPECT_NEAR((bb.x + bb.w / 2.0 - big.view.x) * big.view.zoom, area.x + area.w / 2.0, 1.0);
    EXPECT_NEAR((bb.y + bb.h / 2.0 - big.view.y) * big.view.zoom, area.y + area.h / 2.0, 1.0);
    fit_view(e.view, Rect{0, 0, 4, 4}, area);
    EXPECT_EQ(e.view.zoom, max_zoom);
}

TEST(Character, walksOnTheMapAroundObstaclesAndNeverIntoTheVoid) {
    TempDir d;
    Scene s;
    s.width = s.height = 12;
    s.seed = "forest walk";
    Editor e = make_editor(s, d.path);
    e.character.enabled = true;
    // A frame builds the obstacle map around the character's light.
    const Rect b = e.world.placed.bounds;
    e.character.x = b.x + b.w / 2.0;
    e.character.y = b.y + b.h / 2.0;
    // Start on free ground.
    FrameState& f = e.frame;
    render_frame(f, e.world, render_scene(e), Camera{double(b.x), double(b.y), b.w, b.h}, 0);
    while (f.obstacles.get(int(e.character.x), int(e.character.y))) e.character.x += 3;
    int steps_on_obstacles = 0, off_map = 0;
    for (int i = 0; i < 4000; ++i) {
        const double dx = (i / 250) % 2 ? 6 : -6, dy = (i / 400) % 2 ? 3 : -3;
        walk_character(e, dx, dy);
        int col = 0, row = 0;
        off_map += !tile_at(e.world.map, e.world.placed, e.character.x, e.character.y, col, row);
        steps_on_obstacles += f.obstacles.get(int(std::floor(e.character.x)), int(std::floor(e.character.y)));
    }
    EXPECT_EQ(off_map, 0);
    EXPECT_EQ(steps_on_obstacles, 0);
}

// The normals overlay draws the shading's normals as a normal map does, on
// sprite pixels only, and nothing while sprite shading is none.
TEST(Editor, theNormalsOverlayDrawsTheShadingsNormalsOnSpritePixels) {
    Scene s = small_scene();
    s.lights = {Light{200.5, 150.5}};
    const World w = make_world(test::default_tileset(), s);
    Overlays o;
    o.light_areas = false;
    o.normals = true;
    FrameState flat;
    render_frame(flat, w, s, Camera{}, 0);
    const Rect region = camera_view(s.camera, w);
    EXPECT_TRUE(build_overlays(w, flat, s, o, region).image.rgba.empty()) << "no shading, no normals";
    s.params.sprite_shading = SpriteShading::solids;
    FrameState shaded;
    render_frame(shaded, w, s, Camera{}, 0);
    const OverlayImage img = build_overlays(w, shaded, s, o, region);
    ASSERT_EQ(img.rect, intersect(region, w.placed.bounds));
    long sprite = 0, ground_drawn = 0, wrong = 0;
    const ShadingMap& m = shaded.shading;
    for (int y = img.rect.y; y < img.rect.y + img.rect.h; ++y)
        for (int x = img.rect.x; x < img.rect.x + img.rect.w; ++x) {
            const std::uint8_t* c = img.image.at(x - img.rect.x, y - img.rect.y);
            if (!m.rect.contains(x, y)) continue;
            const auto& q = m.normal[std::size_t(y - m.rect.y) * m.rect.w + std::size_t(x - m.rect.x)];
            if (q[0] == 0 && q[1] == 0 && q[2] == 0) {
                ground_drawn += c[3] != 0;
                continue;
            }
            ++sprite;
            const Vec3 t = to_screen_tangent(Vec3{double(q[0]), double(q[1]), double(q[2])} / 127.0);
            for (int k = 0; k < 3; ++k) wrong += std::abs(c[k] - (t[k] + 1) / 2 * 255) > 1.5;
        }
    EXPECT_GT(sprite, 1000);
    EXPECT_EQ(ground_drawn, 0);
    EXPECT_EQ(wrong, 0);
}
