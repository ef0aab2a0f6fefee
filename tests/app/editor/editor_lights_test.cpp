// The editor's lights (editor_lights.cpp): selection and its operations,
// names, hidden and locked lights.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <unistd.h>

#include "editor/editor.hpp"
#include "editor_util.hpp"
#include "isolux/isolux.hpp"
#include "test_util.hpp"

using namespace isolux;
using namespace isolux::app;
using isolux::test::TempDir;
namespace fs = std::filesystem;
using isolux::test::three_light_editor;

TEST(EditorLights, shiftClickAndBoxSelectMoveDuplicateCopyPasteAndDelete) {
    TempDir d;
    Editor e = three_light_editor(d.path);
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

TEST(EditorLights, namedHiddenAndLockedLightsSurviveTheFileAndHiddenOnesLightNothing) {
    TempDir d;
    Editor e = three_light_editor(d.path);
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
