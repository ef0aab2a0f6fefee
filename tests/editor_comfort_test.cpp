// The editor's comforts without GL: the panel layout, light selection and its
// operations, the window title, dropped files, fitting, the file browser's
// listing and the walking character.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <unistd.h>

#include "gui/editor.hpp"
#include "gui/file_browser.hpp"
#include "gui/layout.hpp"
#include "test_util.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"

using namespace isolux;
using namespace isolux::app;
using isolux::test::TempDir;
namespace fs = std::filesystem;

namespace {

Editor editor(const fs::path& config) {
    Scene s;
    s.width = s.height = 10;
    s.lights = {Light{100.5, 100.5}, Light{300.5, 120.5}, Light{600.5, 400.5}};
    return make_editor(s, config);
}

bool inside(Rect outer, Rect inner) { return intersect(outer, inner) == inner; }

}  // namespace

TEST(Layout, everyDockedPanelLiesInsideTheWindowWithoutOverlap) {
    for (auto [w, h] : {std::pair{1280, 720}, {1366, 768}, {1600, 900}, {1920, 1080}, {2560, 1440}}) {
        const PanelLayout l = panel_layout(w, h, 21, 26);
        ASSERT_EQ(l.panels.size(), 6u);
        const Rect screen{0, 21, w, h - 21 - 26};
        for (const PanelRect& p : l.panels) EXPECT_TRUE(inside(screen, p.rect)) << p.name << " at " << w << "x" << h;
        for (std::size_t i = 0; i < l.panels.size(); ++i)
            for (std::size_t j = i + 1; j < l.panels.size(); ++j)
                EXPECT_TRUE(intersect(l.panels[i].rect, l.panels[j].rect).empty())
                    << l.panels[i].name << " overlaps " << l.panels[j].name << " at " << w << "x" << h;
        EXPECT_TRUE(inside(screen, l.floating)) << w << "x" << h;
        // The map keeps the middle, at least 40 % of the width.
        EXPECT_GE(l.free.w, w * 2 / 5) << w;
        for (const PanelRect& p : l.panels) EXPECT_TRUE(intersect(p.rect, l.free).empty()) << p.name;
    }
}

TEST(Lights, shiftClickAndBoxSelectMoveDuplicateCopyPasteAndDelete) {
    TempDir d;
    Editor e = editor(d.path);
    select_light(e, 0);
    select_light(e, 2, true);  // shift-click adds
    EXPECT_EQ(e.selection, (std::vector<int>{0, 2}));
    select_light(e, 0, true);  // and toggles
    EXPECT_EQ(e.selection, (std::vector<int>{2}));
    select_lights_in(e, {0, 0, 400, 200}, false);  // the box holds lights 1 and 2
    EXPECT_EQ(e.selection, (std::vector<int>{0, 1}));
    // Moved together; the locked one stays.
    const Scene before = e.scene;
    e.scene.lights[1].locked = true;
    move_selection(e, 10, -4);
    EXPECT_EQ(e.scene.lights[0].x, 110.5);
    EXPECT_EQ(e.scene.lights[0].y, 96.5);
    EXPECT_EQ(e.scene.lights[1].x, 300.5);
    commit_edit(e, before, 1);
    // Duplicate: copies beside them, selected, one undo step.
    duplicate_selection(e, 2);
    ASSERT_EQ(e.scene.lights.size(), 5u);
    EXPECT_EQ(e.selection, (std::vector<int>{3, 4}));
    EXPECT_EQ(e.scene.lights[3].x, e.scene.lights[0].x + 16);
    EXPECT_FALSE(e.scene.lights[4].locked);  // a copy is not locked
    ASSERT_TRUE(undo(e, 3));
    EXPECT_EQ(e.scene.lights.size(), 3u);
    EXPECT_TRUE(e.selection.empty() || e.selection.back() < 3);
    // Copy and paste centred on a point.
    select_lights_in(e, {0, 0, 400, 200}, false);
    copy_selection(e);
    paste_lights(e, 1000, 1000, 4);
    ASSERT_EQ(e.scene.lights.size(), 5u);
    const double cx = (e.scene.lights[3].x + e.scene.lights[4].x) / 2, cy = (e.scene.lights[3].y + e.scene.lights[4].y) / 2;
    EXPECT_NEAR(cx, 1000, 1.0);
    EXPECT_NEAR(cy, 1000, 1.0);
    // Delete keeps locked lights and says so.
    select_lights_in(e, {0, 0, 400, 200}, false);
    delete_selection(e, 5);
    ASSERT_EQ(e.scene.lights.size(), 4u);
    EXPECT_TRUE(e.scene.lights[0].locked);
    EXPECT_NE(e.status.find("locked"), std::string::npos);
    remove_light(e, 0, 6);
    EXPECT_EQ(e.scene.lights.size(), 4u);  // locked: not removed
}

TEST(Lights, namedHiddenAndLockedLightsSurviveTheFileAndHiddenOnesLightNothing) {
    TempDir d;
    Editor e = editor(d.path);
    e.scene.lights[0].name = "campfire";
    e.scene.lights[1].hidden = true;
    e.scene.lights[2].locked = true;
    ASSERT_TRUE(save_scene_to(e, d.path / "s.json"));
    const Scene back = load_scene(d.path / "s.json");
    EXPECT_EQ(back.lights, e.scene.lights);
    EXPECT_EQ(light_label(back, 0), "campfire");
    EXPECT_EQ(light_label(back, 1), "light 2");
    // A hidden light renders as no light at all.
    Scene without = back;
    without.lights.erase(without.lights.begin() + 1);
    FrameState a, b;
    const Camera cam{0, 0, 800, 600};
    render_frame(a, e.world, back, cam, 0);
    render_frame(b, e.world, without, cam, 0);
    EXPECT_EQ(a.final.rgba, b.final.rgba);
    Scene shown = back;
    shown.lights[1].hidden = false;
    FrameState c;
    render_frame(c, e.world, shown, cam, 0);
    EXPECT_NE(c.final.rgba, a.final.rgba);
}

TEST(Window, theTitleNamesTheFileAndMarksUnsavedWork) {
    TempDir d;
    Editor e = editor(d.path);
    EXPECT_EQ(window_title(e), "untitled - isolux");
    place_light(e, 10, 10, 1);
    EXPECT_EQ(window_title(e), "untitled * - isolux");
    ASSERT_TRUE(save_scene_to(e, d.path / "forest.json"));
    EXPECT_EQ(window_title(e), "forest.json - isolux");
}

TEST(Files, droppedFilesOpenAsWhatTheyAre) {
    TempDir d;
    Editor e = editor(d.path);
    Scene s;
    s.seed = "dropped";
    save_scene(d.path / "level.json", s);
    Params p;
    p.delta_y = 17;
    save_preset(d.path / "tuned.json", p);
    EXPECT_EQ(detect_file_kind(d.path / "level.json"), FileKind::scene);
    EXPECT_EQ(detect_file_kind(d.path / "tuned.json"), FileKind::preset);
    EXPECT_EQ(detect_file_kind(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json"), FileKind::tileset);
    // As the app opens a dropped file: as the kind it detects.
    auto drop = [&](const fs::path& path, double now) {
        return open_recent(e, RecentFile{path.string(), detect_file_kind(path)}, now);
    };
    ASSERT_TRUE(drop(d.path / "tuned.json", 1)) << e.status;
    EXPECT_EQ(e.scene.params.delta_y, 17);
    ASSERT_TRUE(drop(d.path / "level.json", 2)) << e.status;
    EXPECT_EQ(e.scene.seed, "dropped");
    // A folder or a missing file is a message naming it, not a crash.
    std::string message;
    try {
        drop(d.path, 3);
    } catch (const Error& err) {
        message = err.what();
    }
    EXPECT_NE(message.find(d.path.string()), std::string::npos) << message;
    EXPECT_EQ(e.scene.seed, "dropped");
}

TEST(Files, theBrowserListsFoldersFirstThenFilesOfTheKind) {
    TempDir d;
    fs::create_directories(d.path / "b_folder");
    fs::create_directories(d.path / "a_folder");
    for (const char* f : {"z.json", "a.JSON", "m.png", ".hidden.json", "notes.txt"}) std::ofstream(d.path / f) << "{}";
    const FileFilter json{"JSON", {".json"}};
    std::vector<std::string> names;
    for (const FolderEntry& en : list_folder(d.path, json)) names.push_back(en.name);
    EXPECT_EQ(names, (std::vector<std::string>{"a_folder", "b_folder", "a.JSON", "z.json"}));
    const FileFilter all{"All", {}};
    EXPECT_EQ(list_folder(d.path, all).size(), 6u);
    EXPECT_THROW(list_folder(d.path / "missing", all), Error);
    EXPECT_EQ(recent_folders({"/a/x.json", "/b/y.json", "/a/z.json"}), (std::vector<std::string>{"/a", "/b"}));
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
