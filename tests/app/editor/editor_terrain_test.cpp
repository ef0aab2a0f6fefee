// The level editor's terrain tools (editor/editor.hpp), with no GL: each tool,
// a stroke as one undo step, the seed plus edits through a file, and edits
// beyond a shrunk map kept.
#include <gtest/gtest.h>

#include <unistd.h>

#include "editor/editor.hpp"
#include "test_util.hpp"
#include "isolux/edits.hpp"
#include "isolux/isolux.hpp"

using namespace isolux;
using namespace isolux::app;
using isolux::test::TempDir;
namespace fs = std::filesystem;

namespace {

Editor editor(const fs::path& config, int side = 10) {
    Scene s;
    s.width = s.height = side;
    s.seed = "terrain";
    return make_editor(s, config);
}

int sprite(const Editor& e, const char* name) {
    for (std::size_t i = 0; i < e.world.tileset.sprites.size(); ++i)
        if (e.world.tileset.sprites[i].name == name) return int(i);
    ADD_FAILURE() << "no sprite " << name;
    return -1;
}

// A floor none of `tiles` holds, so painting it changes each of them.
int other_floor(const Editor& e, std::initializer_list<std::pair<int, int>> tiles) {
    for (const char* name : {"water", "sand", "stone", "dirt", "grass"}) {
        bool used = false;
        for (auto [c, r] : tiles) used = used || e.world.map.at(c, r).floor == sprite(e, name);
        if (!used) return sprite(e, name);
    }
    ADD_FAILURE() << "every floor is used";
    return -1;
}

void stroke(Editor& e, std::initializer_list<std::pair<int, int>> tiles, double now) {
    auto it = tiles.begin();
    begin_stroke(e, it->first, it->second);
    for (++it; it != tiles.end(); ++it) continue_stroke(e, it->first, it->second);
    end_stroke(e, now);
}

// The world the editor shows equals the scene's world built from scratch.
void expect_world_matches_scene(const Editor& e) {
    const World fresh = make_world(e.world.tileset, e.scene);
    ASSERT_EQ(fresh.map.tiles.size(), e.world.map.tiles.size());
    for (std::size_t i = 0; i < fresh.map.tiles.size(); ++i) {
        EXPECT_EQ(fresh.map.tiles[i].floor, e.world.map.tiles[i].floor) << "tile " << i;
        EXPECT_EQ(overlay_sprites(fresh.map.tiles[i]), overlay_sprites(e.world.map.tiles[i])) << "tile " << i;
    }
    EXPECT_EQ(fresh.placed.bounds, e.world.placed.bounds);
}

}  // namespace

TEST(Terrain, theFloorBrushPaintsEveryTileAStrokeCrossesAsOneUndoStep) {
    TempDir d{false};
    Editor e = editor(d.path);
    e.brush.tool = Tool::floor;
    e.brush.floor = other_floor(e, {{1, 1}, {2, 1}, {3, 1}, {3, 2}});
    const Map seeded = e.world.map;
    stroke(e, {{1, 1}, {2, 1}, {3, 1}, {3, 2}}, 1);
    for (auto [c, r] : {std::pair{1, 1}, {2, 1}, {3, 1}, {3, 2}}) EXPECT_EQ(e.world.map.at(c, r).floor, e.brush.floor);
    EXPECT_EQ(e.undo_stack.size(), 1u);
    EXPECT_TRUE(e.dirty);
    expect_world_matches_scene(e);
    ASSERT_TRUE(undo(e, 2));
    for (std::size_t i = 0; i < seeded.tiles.size(); ++i) EXPECT_EQ(e.world.map.tiles[i].floor, seeded.tiles[i].floor);
    EXPECT_TRUE(e.scene.edits.empty());
    ASSERT_TRUE(redo(e, 3));
    EXPECT_EQ(e.world.map.at(3, 2).floor, e.brush.floor);
    expect_world_matches_scene(e);
}

TEST(Terrain, theRectangleFillsItsCornersRectangleAtTheEnd) {
    TempDir d{false};
    Editor e = editor(d.path);
    e.brush.tool = Tool::floor_rect;
    e.brush.floor = sprite(e, "sand");
    begin_stroke(e, 6, 2);
    continue_stroke(e, 4, 3);
    EXPECT_TRUE(e.scene.edits.empty() || e.world.map.at(5, 2).floor != e.brush.floor);  // nothing until the end
    continue_stroke(e, 2, 5);
    end_stroke(e, 1);
    int painted = 0;
    for (int r = 0; r < 10; ++r)
        for (int c = 0; c < 10; ++c) {
            const bool inside = c >= 2 && c <= 6 && r >= 2 && r <= 5;
            if (inside) {
                EXPECT_EQ(e.world.map.at(c, r).floor, e.brush.floor) << c << "," << r;
            }
            painted += e.world.map.at(c, r).floor == e.brush.floor;
        }
    EXPECT_GE(painted, 20);
    EXPECT_EQ(e.undo_stack.size(), 1u);
    expect_world_matches_scene(e);
}

TEST(Terrain, theBucketFillsTheConnectedTilesOfOneFloor) {
    TempDir d{false};
    Editor e = editor(d.path);
    // A known region: a 3x3 block of stone in a field of grass.
    e.brush.tool = Tool::floor_rect;
    e.brush.floor = sprite(e, "grass");
    stroke(e, {{0, 0}, {9, 9}}, 1);
    e.brush.floor = sprite(e, "stone");
    stroke(e, {{2, 2}, {4, 4}}, 2);
    e.brush.tool = Tool::floor_fill;
    e.brush.floor = sprite(e, "water");
    stroke(e, {{3, 3}}, 3);
    for (int r = 0; r < 10; ++r)
        for (int c = 0; c < 10; ++c) {
            const bool block = c >= 2 && c <= 4 && r >= 2 && r <= 4;
            EXPECT_EQ(e.world.map.at(c, r).floor, block ? sprite(e, "water") : sprite(e, "grass")) << c << "," << r;
        }
    EXPECT_EQ(e.undo_stack.size(), 3u);
    expect_world_matches_scene(e);
}

TEST(Terrain, overlaysArePlacedUpToThreeRemovedErasedAndPicked) {
    TempDir d{false};
    Editor e = editor(d.path);
    e.brush.tool = Tool::eraser;
    stroke(e, {{5, 5}}, 1);
    EXPECT_EQ(e.world.map.at(5, 5).overlay_count, 0);
    e.brush.tool = Tool::overlay_add;
    e.brush.overlay = sprite(e, "oak");
    for (int i = 0; i < 4; ++i) stroke(e, {{5, 5}}, 2 + i);  // the fourth does nothing
    ASSERT_EQ(e.world.map.at(5, 5).overlay_count, 3);
    EXPECT_NE(brush_preview(e, 5, 5).find("full"), std::string::npos);
    // "Any sprite with tag tree".
    e.brush.overlay_tag = "tree";
    stroke(e, {{6, 5}}, 10);
    e.brush.tool = Tool::eraser;
    stroke(e, {{7, 5}}, 11);
    e.brush.tool = Tool::overlay_add;
    stroke(e, {{7, 5}}, 12);
    ASSERT_EQ(e.world.map.at(7, 5).overlay_count, 1);
    EXPECT_TRUE(e.world.tileset.sprites[std::size_t(e.world.map.at(7, 5).overlays[0].sprite)].has_tag("tree"));
    e.brush.tool = Tool::overlay_remove;
    stroke(e, {{5, 5}}, 13);
    EXPECT_EQ(e.world.map.at(5, 5).overlay_count, 2);
    e.brush.tool = Tool::eraser;
    stroke(e, {{5, 5}}, 14);
    EXPECT_EQ(e.world.map.at(5, 5).overlay_count, 0);
    // The eyedropper takes a tile's floor and top overlay.
    e.brush = Brush{Tool::eyedropper, -1, -1, ""};
    stroke(e, {{7, 5}}, 15);
    EXPECT_EQ(e.brush.floor, e.world.map.at(7, 5).floor);
    EXPECT_EQ(e.brush.overlay, e.world.map.at(7, 5).overlays[0].sprite);
    expect_world_matches_scene(e);
    // Every stroke that changed the level is one undo step; undoing all gives the seed's map back.
    while (undo(e, 20)) {
    }
    EXPECT_TRUE(e.scene.edits.empty());
    expect_world_matches_scene(e);
}

TEST(Terrain, aLevelSurvivesSaveAndReopenAndRendersTheSame) {
    TempDir d{false};
    Editor e = editor(d.path);
    e.brush.tool = Tool::floor_rect;
    e.brush.floor = sprite(e, "water");
    stroke(e, {{1, 1}, {4, 3}}, 1);  // a lake
    e.brush.tool = Tool::eraser;
    stroke(e, {{6, 6}, {7, 6}, {7, 7}}, 2);  // a clearing
    e.brush.tool = Tool::overlay_add;
    e.brush.overlay = sprite(e, "pine");
    stroke(e, {{0, 8}, {1, 8}, {2, 8}, {3, 8}}, 3);  // a wall of trees
    place_light(e, 500.5, 400.5, 4);
    const fs::path file = d.path / "level.json";
    fs::create_directories(d.path);
    ASSERT_TRUE(save_scene_to(e, file)) << e.status;
    Editor f = editor(d.path / "other");
    ASSERT_TRUE(load_scene_from(f, file, 5)) << f.status;
    EXPECT_EQ(f.scene.edits, e.scene.edits);
    ASSERT_EQ(f.world.map.tiles.size(), e.world.map.tiles.size());
    for (std::size_t i = 0; i < f.world.map.tiles.size(); ++i) {
        EXPECT_EQ(f.world.map.tiles[i].floor, e.world.map.tiles[i].floor);
        EXPECT_EQ(overlay_sprites(f.world.map.tiles[i]), overlay_sprites(e.world.map.tiles[i]));
    }
    // The same pixels from both worlds.
    FrameState a, b;
    const Camera cam{0, 0, 1200, 800};
    render_frame(a, e.world, e.scene, cam, 0);
    render_frame(b, f.world, f.scene, cam, 0);
    EXPECT_EQ(a.final.rgba, b.final.rgba);
}

TEST(Terrain, editsBeyondAShrunkMapAreKeptReportedAndComeBack) {
    TempDir d{false};
    Editor e = editor(d.path);
    e.brush.tool = Tool::floor;
    const int floor = e.brush.floor = other_floor(e, {{8, 8}, {1, 1}});
    stroke(e, {{8, 8}}, 1);
    stroke(e, {{1, 1}}, 2);
    regenerate(e, e.scene.seed, 5, 5, e.scene.layout, 3);
    EXPECT_EQ(e.scene.edits.size(), 2u);
    EXPECT_EQ(edits_outside(e.scene), 1);
    EXPECT_NE(e.status.find("outside the map"), std::string::npos) << e.status;
    EXPECT_EQ(e.world.map.at(1, 1).floor, floor);
    regenerate(e, e.scene.seed, 10, 10, e.scene.layout, 4);
    EXPECT_EQ(e.world.map.at(8, 8).floor, floor);
    // Clearing them is the user's choice.
    regenerate(e, "other", 10, 10, e.scene.layout, 5, false);
    EXPECT_TRUE(e.scene.edits.empty());
    ASSERT_TRUE(undo(e, 6));
    EXPECT_EQ(e.scene.edits.size(), 2u);
}
