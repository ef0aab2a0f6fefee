// The level as the seed's map plus hand edits (edits.hpp, world.hpp): the
// scene format, the rules of the entries, and edits costing what they touch
// while giving exactly the pixels a full rebuild gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_texture.hpp"
#include "test_util.hpp"

using namespace isolux;
using isolux::test::error_of;
namespace fs = std::filesystem;

namespace {

const Tileset& tiles() {
    static Tileset t = test::default_tileset();
    return t;
}

int sprite(const char* name) { return test::sprite_index(tiles(), name); }

Scene small_scene() {
    Scene s;
    s.width = 12;
    s.height = 10;
    s.lights = {Light{400.5, 300.5}, Light{900.5, 500.5}, Light{200.5, 700.5}};
    s.params.area_a = s.params.area_b = 96;
    return s;
}

TileEdit edit(int col, int row, std::optional<std::string> floor, std::optional<std::vector<std::string>> overlays) {
    TileEdit e;
    e.col = col;
    e.row = row;
    e.floor = std::move(floor);
    e.overlays = std::move(overlays);
    return e;
}

}  // namespace

TEST(Edits, sceneFilesCarryEditsAndOlderScenesStillLoad) {
    Scene s = small_scene();
    s.edits = {edit(1, 2, "water", std::nullopt), edit(3, 4, std::nullopt, std::vector<std::string>{"oak", "bush"}),
               edit(5, 5, "sand", std::vector<std::string>{})};
    const std::string text = scene_to_json(s);
    EXPECT_NE(text.find("\"schema_version\": 2"), std::string::npos);
    EXPECT_NE(text.find("\"tile\""), std::string::npos);
    const Scene back = scene_from_json(text, "s.json");
    EXPECT_EQ(back.edits, s.edits);
    // "overlays": [] survives as "clear", not as "unchanged".
    ASSERT_TRUE(back.edits[2].overlays.has_value());
    EXPECT_TRUE(back.edits[2].overlays->empty());

    // Version 1 (and no version at all) still loads, with no edits.
    const Scene v1 = scene_from_json(R"({"schema_version": 1, "seed": "old", "width": 4, "height": 4})", "v1.json");
    EXPECT_EQ(v1.seed, "old");
    EXPECT_TRUE(v1.edits.empty());
    EXPECT_NO_THROW(scene_from_json(R"({"seed": "older"})", "v0.json"));
    // A newer one is refused by name.
    EXPECT_NE(error_of([] { scene_from_json(R"({"schema_version": 3})", "new.json"); }).find("newer"), std::string::npos);
}

TEST(Edits, malformedEntriesAreErrorsNamingTheFileAndTheEntry) {
    const char* bad[] = {
        R"({"edits": {"tile": [1, 2]}})",                                      // not an array
        R"({"edits": [{"floor": "water"}]})",                                  // no tile
        R"({"edits": [{"tile": [1], "floor": "water"}]})",                     // one coordinate
        R"({"edits": [{"tile": [1, "2"], "floor": "water"}]})",                // a string coordinate
        R"({"edits": [{"tile": [1, 2.5], "floor": "water"}]})",                // a fraction
        R"({"edits": [{"tile": [1, 2]}]})",                                    // nothing to set
        R"({"edits": [{"tile": [1, 2], "floor": 3}]})",                        // floor not a name
        R"({"edits": [{"tile": [1, 2], "overlays": "oak"}]})",                 // overlays not a list
        R"({"edits": [{"tile": [1, 2], "overlays": ["a", "b", "c", "d"]}]})",  // four overlays
        R"({"edits": [{"tile": [1, 2], "overlays": [7]}]})",                   // a number for a name
        R"({"edits": [{"tile": [1, 2], "floor": "water", "flor": "x"}]})",     // a misspelt field
        R"({"edits": [{"tile": [9999999999999, 2], "floor": "water"}]})",        // beyond any map
        R"({"edits": [5]})",                                                   // not an object
    };
    for (const char* text : bad) {
        const std::string e = error_of([&] { scene_from_json(text, "level.json"); });
        EXPECT_NE(e.find("level.json"), std::string::npos) << text << " -> " << e;
        EXPECT_NE(e.find("edits"), std::string::npos) << text << " -> " << e;
    }
}

TEST(Edits, anUnknownSpriteNameIsAnErrorNamingTheSceneAndTheEntry) {
    Scene s = small_scene();
    s.edits = {edit(1, 1, "water", std::nullopt), edit(2, 2, "lava", std::nullopt)};
    std::string e = error_of([&] { make_world(tiles(), s, "level.json"); });
    EXPECT_NE(e.find("level.json: edits[1]"), std::string::npos) << e;
    EXPECT_NE(e.find("lava"), std::string::npos) << e;
    // A sprite of the wrong kind is named as such.
    s.edits = {edit(1, 1, "oak", std::nullopt)};
    e = error_of([&] { make_world(tiles(), s, "level.json"); });
    EXPECT_NE(e.find("not a floor"), std::string::npos) << e;
    s.edits = {edit(1, 1, std::nullopt, std::vector<std::string>{"grass"})};
    e = error_of([&] { make_world(tiles(), s, "level.json"); });
    EXPECT_NE(e.find("not an overlay"), std::string::npos) << e;
}

TEST(Edits, editsApplyInOrderFieldByFieldAndAnEmptyListClearsOverlays) {
    Scene s = small_scene();
    s.seed = "forest";
    const World seeded = make_world(tiles(), s);
    // A tile with overlays in the seed's map.
    int col = -1, row = -1;
    for (int r = 0; r < s.height && col < 0; ++r)
        for (int c = 0; c < s.width && col < 0; ++c)
            if (seeded.map.at(c, r).overlay_count > 0) col = c, row = r;
    ASSERT_GE(col, 0);
    s.edits = {edit(col, row, "water", std::vector<std::string>{"oak"}), edit(col, row, "sand", std::nullopt),
               edit(col + 1 == s.width ? 0 : col + 1, row, std::nullopt, std::vector<std::string>{})};
    const World w = make_world(tiles(), s);
    const Tile& t = w.map.at(col, row);
    EXPECT_EQ(t.floor, sprite("sand"));  // the later floor wins
    ASSERT_EQ(t.overlay_count, 1);       // the earlier overlays stay: the later entry has none
    EXPECT_EQ(t.overlays[0].sprite, sprite("oak"));
    EXPECT_EQ(w.map.at(col + 1 == s.width ? 0 : col + 1, row).overlay_count, 0);
    // Every other tile is the seed's.
    int differing = 0;
    for (std::size_t i = 0; i < w.map.tiles.size(); ++i)
        differing += w.map.tiles[i].floor != seeded.map.tiles[i].floor ||
                     w.map.tiles[i].overlay_count != seeded.map.tiles[i].overlay_count;
    EXPECT_LE(differing, 2);
    // The world's pixels are the seeded map's: lights do not move.
    EXPECT_EQ(w.placed.shift_x, seeded.placed.shift_x);
    EXPECT_EQ(w.placed.shift_y, seeded.placed.shift_y);
}

// The whole map's picture keeps its frame whatever the edits: a scene whose
// edits clear every overlay (the tall trees on the top edge included) and a
// scene whose edits plant trees everywhere put a world light at the same
// image pixel as the seed's map does, in the frame and in the rendered bytes.
TEST(Edits, editsNeverMoveWhereAWorldPixelLandsInTheWholeMapsPicture) {
    Scene s = small_scene();
    s.seed = "forest";
    const World seeded = make_world(tiles(), s);
    Scene cleared = s, planted = s;
    for (int r = 0; r < s.height; ++r)
        for (int c = 0; c < s.width; ++c) {
            cleared.edits.push_back(edit(c, r, std::nullopt, std::vector<std::string>{}));
            planted.edits.push_back(edit(c, r, std::nullopt, std::vector<std::string>{"pine"}));
        }
    const World bare = make_world(tiles(), cleared), wooded = make_world(tiles(), planted);
    const Rect frame = camera_view(Camera{}, seeded);
    // The edits did change what the sprites cover, and the frame did not follow.
    EXPECT_NE(wooded.placed.bounds, seeded.placed.bounds);
    EXPECT_EQ(camera_view(Camera{}, bare), frame);
    EXPECT_EQ(camera_view(Camera{}, wooded), frame);
    // A light's pixel in the rendered light texture: the brightest one.
    auto brightest = [&](const World& w) {
        Scene one = s;
        one.lights = {Light{frame.x + 300.0, frame.y + 200.0}};
        FrameState st;
        render_frame(st, w, one, Camera{}, 0);
        const Image img = light_texture_image(st.light);
        std::size_t best = 0;
        for (std::size_t i = 0; i < img.rgba.size(); i += 4)
            if (img.rgba[i] > img.rgba[best]) best = i;
        return std::pair{int(best / 4) % img.width, int(best / 4) / img.width};
    };
    EXPECT_EQ(brightest(bare), brightest(seeded));
    EXPECT_EQ(brightest(wooded), brightest(seeded));
}

TEST(Edits, editsOutsideTheMapAreKeptAndReported) {
    Scene s = small_scene();
    s.edits = {edit(3, 3, "water", std::nullopt), edit(40, 2, "water", std::nullopt), edit(-1, 0, "sand", std::nullopt)};
    std::vector<std::string> warnings;
    const World w = make_world(tiles(), s, "level.json", &warnings);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_NE(warnings[0].find("level.json: edits[1]"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("outside"), std::string::npos) << warnings[0];
    EXPECT_EQ(w.edits.size(), 3u);  // kept
    EXPECT_EQ(w.map.at(3, 3).floor, sprite("water"));
    // Growing the map back applies it.
    s.width = 41;
    const World wide = make_world(tiles(), s);
    EXPECT_EQ(wide.map.at(40, 2).floor, sprite("water"));
}

TEST(Edits, theBrushWritesOnlyWhatDiffersFromTheSeed) {
    Scene s = small_scene();
    const World w = make_world(tiles(), s);
    std::vector<TileEdit> edits;
    const Tile& seed = w.seeded.at(4, 4);
    set_tile_edit(edits, w.seeded, tiles(), 4, 4, sprite("water"), overlay_sprites(seed));
    ASSERT_EQ(edits.size(), 1u);
    EXPECT_EQ(edits[0].floor, std::optional<std::string>("water"));
    EXPECT_FALSE(edits[0].overlays.has_value());
    set_tile_edit(edits, w.seeded, tiles(), 4, 4, sprite("water"), {sprite("pine")});
    ASSERT_EQ(edits.size(), 1u);  // one entry per tile
    EXPECT_EQ(edits[0].overlays, std::optional<std::vector<std::string>>(std::vector<std::string>{"pine"}));
    set_tile_edit(edits, w.seeded, tiles(), 4, 4, seed.floor, overlay_sprites(seed));
    EXPECT_TRUE(edits.empty());  // back to the seed: nothing to store
}

// A tree planted on the top row reaches above the origin: the sprites'
// bounds grow, the whole map's frame stays the seed's (a camera or --view
// shows beyond it).
TEST(Edits, aTreeOnTheTopRowReachesAboveTheOriginAndTheWholeMapsFrameStays) {
    Scene s = small_scene();
    s.seed = "lake";
    World w = make_world(tiles(), s);
    const Rect before = w.placed.bounds;
    EXPECT_EQ(before.x, 0);
    EXPECT_EQ(before.y, 0);
    // Diamond layout: tile (0, 0) is the topmost.
    set_edits(w, {edit(0, 0, std::nullopt, std::vector<std::string>{"pine", "pine", "pine"})});
    EXPECT_LT(w.placed.bounds.y, 0);
    EXPECT_EQ(camera_view(Camera{}, w), before);
    // Removing it shrinks the map back exactly.
    set_edits(w, {});
    EXPECT_EQ(w.placed.bounds, before);
}

// Each step: a random edit through set_edits (incremental), against the same
// scene built from scratch: the same sprites, obstacle map and lit frame, byte
// for byte, while the frame rebuilds only around the edit.
TEST(Edits, incrementalEditsGiveTheBytesOfAFullRebuildAndCostWhatTheyTouch) {
    Scene s = small_scene();
    s.seed = "edits";
    const Rect cam{0, 0, 1400, 900};
    const Camera camera{double(cam.x), double(cam.y), cam.w, cam.h};
    World w = make_world(tiles(), s);
    FrameState st;
    render_frame(st, w, s, camera, 0);
    const std::vector<std::string> floors = {"grass", "water", "sand", "stone", "dirt"};
    const std::vector<std::string> overlays = {"oak", "pine", "bush", "rock", "wall", "boulder"};
    Pcg32 rng(42);
    int partial_rebuilds = 0, lights_kept = 0;
    for (int step = 0; step < 24; ++step) {
        TileEdit e;
        e.col = int(rng.below(std::uint32_t(s.width)));
        e.row = int(rng.below(std::uint32_t(s.height)));
        if (rng.below(2)) e.floor = floors[rng.below(std::uint32_t(floors.size()))];
        if (!e.floor || rng.below(2)) {
            e.overlays.emplace();
            for (std::uint32_t k = rng.below(4); k > 0; --k) e.overlays->push_back(overlays[rng.below(std::uint32_t(overlays.size()))]);
        }
        s.edits.push_back(e);
        if (step % 7 == 6) s.edits.erase(s.edits.begin());  // an undo-like removal too
        const Rect changed = set_edits(w, s.edits);
        const FrameReport rep = render_frame(st, w, s, camera, step + 1);

        const World full = make_world(tiles(), s);
        FrameState fresh;
        render_frame(fresh, full, s, camera, 0);
        ASSERT_EQ(st.sprites.rgba, fresh.sprites.rgba) << "step " << step;
        ASSERT_EQ(st.obstacles.rect(), fresh.obstacles.rect()) << "step " << step;
        ASSERT_EQ(st.obstacles.bits, fresh.obstacles.bits) << "step " << step;
        ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "step " << step;
        if (!changed.empty() && rep.rebuilt.w * std::int64_t(rep.rebuilt.h) <
                                    st.obstacles.width * std::int64_t(st.obstacles.height) / 4)
            ++partial_rebuilds;
        lights_kept += rep.lights_reused;
    }
    EXPECT_GE(partial_rebuilds, 12);  // most edits rebuilt a small part
    EXPECT_GT(lights_kept, 0);        // and some lights were not retraced
}

TEST(Edits, anEditRetracesOnlyTheLightsItsRegionMeets) {
    Scene s = small_scene();
    s.lights = {Light{300.5, 300.5}, Light{1200.5, 600.5}};
    s.params.area_a = s.params.area_b = 64;
    World w = make_world(tiles(), s);
    FrameState st;
    const Camera camera{0, 0, 1500, 900};
    render_frame(st, w, s, camera, 0);
    // The tile under the first light.
    int col = 0, row = 0;
    ASSERT_TRUE(tile_at(w.map, w.placed, 300, 300, col, row));
    const std::string other = w.map.at(col, row).floor == sprite("water") ? "grass" : "water";
    set_edits(w, {edit(col, row, other, std::vector<std::string>{"oak"})});
    const FrameReport rep = render_frame(st, w, s, camera, 1);
    EXPECT_EQ(rep.lights_traced, 1);
    EXPECT_EQ(rep.lights_reused, 1);
    EXPECT_FALSE(rep.rebuilt.empty());
    EXPECT_FALSE(intersect(rep.rebuilt, Rect{300 - 64, 300 - 64, 129, 129}).empty());
    EXPECT_TRUE(intersect(rep.rebuilt, Rect{1200 - 64, 600 - 64, 129, 129}).empty());
}

TEST(Edits, setTileGivesTheBytesOfTheBrushsEditsAppliedWholeAndTouchesOnlyItsTile) {
    Scene s = small_scene();
    s.seed = "one tile";
    const Camera camera{0, 0, 1400, 900};
    World w = make_world(tiles(), s);
    FrameState st;
    render_frame(st, w, s, camera, 0);
    const std::vector<int> floors = {sprite("grass"), sprite("water"), sprite("sand"), sprite("stone")};
    const std::vector<int> overlays = {sprite("oak"), sprite("pine"), sprite("bush"), sprite("rock"), sprite("wall")};
    Pcg32 rng(7);
    for (int step = 0; step < 24; ++step) {
        const int col = int(rng.below(std::uint32_t(s.width))), row = int(rng.below(std::uint32_t(s.height)));
        const int floor = floors[rng.below(std::uint32_t(floors.size()))];
        std::vector<int> on;
        for (std::uint32_t k = rng.below(4); k > 0; --k) on.push_back(overlays[rng.below(std::uint32_t(overlays.size()))]);
        const std::vector<Tile> before = w.map.tiles;
        set_tile(w, col, row, floor, on);
        for (std::size_t i = 0; i < before.size(); ++i) {
            if (int(i) == row * s.width + col) continue;
            ASSERT_EQ(w.map.tiles[i], before[i]) << "step " << step << ": tile " << i;
        }
        // The edits it wrote, applied whole from the scene, draw the same frame.
        s.edits = w.edits;
        render_frame(st, w, s, camera, step + 1);
        const World full = make_world(tiles(), s);
        FrameState fresh;
        render_frame(fresh, full, s, camera, 0);
        ASSERT_EQ(w.map.tiles, full.map.tiles) << "step " << step;
        ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "step " << step;
    }
    EXPECT_FALSE(error_of([&] { set_tile(w, s.width, 0, floors[0], {}); }).empty());  // outside the map
}
