// Tileset manifests (tileset_file.cpp) and the default tileset: bad entries
// named, odd PNGs loaded, shapes, height maps and footprints read and saved.
#include <gtest/gtest.h>

#include <algorithm>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <sys/stat.h>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/world.hpp"
#include "test_util.hpp"

using namespace isolux;
using isolux::test::error_of;
using isolux::test::TempDir;
namespace fs = std::filesystem;

namespace {
std::string manifest_with(const std::string& sprite) {
    return R"({"schema_version": 1, "tile": {"width": 64, "height": 32}, "sprites": [
        {"name": "ground", "image": "floor.png", "kind": "floor", "tags": ["grass"]},)" +
           sprite + "]}";
}
void write_png(const fs::path& p, int w, int h) {
    Image im(w, h);
    for (auto& v : im.rgba) v = 200;
    save_image(p, im);
}
}  // namespace

TEST(Tileset, badEntriesNameTheFileAndTheEntry) {
    TempDir d;
    write_png(d.path / "floor.png", 64, 48);
    d.write("notes.png", "this is not an image");
    struct Case {
        std::string sprite, expect;
    } cases[] = {
        {R"({"name": "ghost", "image": "nowhere.png", "kind": "overlay"})", "nowhere.png"},
        {R"({"name": "text", "image": "notes.png", "kind": "overlay"})", "not a readable image"},
        {R"({"name": "cut", "image": "floor.png", "rect": [32, 0, 64, 10], "kind": "overlay"})", "lies outside"},
        {R"({"name": "odd", "image": "floor.png", "kind": "ceiling"})", "ceiling"},
        {R"({"name": "flat", "image": "floor.png", "rect": [0, 0, 0, 5], "kind": "overlay"})", "zero-size"},
        {R"({"name": "noimg", "kind": "overlay"})", "image"},
    };
    for (const Case& c : cases) {
        fs::path m = d.write("tileset.json", manifest_with(c.sprite));
        std::string msg = error_of([&] { load_tileset(m); });
        EXPECT_MENTIONS(msg, "tileset.json");
        EXPECT_MENTIONS(msg, "sprites[1]");
        EXPECT_MENTIONS(msg, c.expect);
    }
}

TEST(Tileset, aTilesetWithoutFloorsIsRefused) {
    TempDir d;
    write_png(d.path / "tree.png", 16, 16);
    fs::path m = d.write("t.json", R"({"sprites": [{"name": "tree", "image": "tree.png", "kind": "overlay"}]})");
    std::string msg = error_of([&] { load_tileset(m); });
    EXPECT_MENTIONS(msg, "t.json");
    EXPECT_MENTIONS(msg, "floor");
}

TEST(Tileset, loadsPaletteSixteenBitAndGreyPngs) {
    Tileset t = test::foreign_tileset();
    ASSERT_EQ(t.sprites.size(), 5u);
    // Palette with tRNS: index 0 transparent, index 1 = (90, 170, 60).
    const Sprite& meadow = t.sprites[0];
    EXPECT_EQ(meadow.image.width, 64);
    EXPECT_EQ(meadow.image.at(0, 0)[3], 0);
    const std::uint8_t* p = meadow.image.at(32, 16);
    EXPECT_EQ(p[3], 255);
    EXPECT_TRUE((p[0] == 90 && p[1] == 170 && p[2] == 60) || (p[0] == 60 && p[1] == 120 && p[2] == 40));
    // The sheet's second rect: the water floor.
    const std::uint8_t* w = t.sprites[1].image.at(32, 16);
    EXPECT_TRUE((w[0] == 40 && w[1] == 90 && w[2] == 200) || (w[0] == 200 && w[1] == 190 && w[2] == 120));
    // 16-bit RGBA: full alpha 65535 -> 255, trunk colour 0.45 -> 115.
    const Sprite& tree = t.sprites[2];
    EXPECT_EQ(tree.image.height, 128);
    EXPECT_EQ(tree.image.at(32, 100)[3], 255);
    EXPECT_NEAR(tree.image.at(32, 100)[0], 115, 1);
    EXPECT_EQ(tree.image.at(0, 127)[3], 0);
    // Grey + alpha: grey copied to r, g, b.
    const Sprite& rock = t.sprites[3];
    const std::uint8_t* r = rock.image.at(20, 14);
    EXPECT_EQ(r[0], r[1]);
    EXPECT_EQ(r[1], r[2]);
    EXPECT_EQ(r[0], 150 - 14 * 2);
    EXPECT_EQ(rock.opacity_threshold.value_or(-1), 0.25);
    // 16-bit grey without alpha: opaque.
    const Sprite& post = t.sprites[4];
    EXPECT_EQ(post.image.at(5, 10)[3], 255);
    EXPECT_NEAR(post.image.at(5, 10)[0], (20000 + 5000) * 255.0 / 65535, 1);
}

TEST(Tileset, defaultTilesetHasEveryFloorAndOverlayKind) {
    Tileset t = test::default_tileset();
    EXPECT_EQ(t.tile_width, 128);
    EXPECT_EQ(t.tile_height, 64);
    for (const char* tag : {"grass", "dirt", "sand", "stone", "water"}) {
        auto found = t.find(SpriteKind::floor, tag);
        ASSERT_FALSE(found.empty()) << tag;
        EXPECT_TRUE(t.sprites[found[0]].has_tag(tag));
    }
    for (const char* tag : {"tree", "bush", "rock", "wall"}) {
        auto found = t.find(SpriteKind::overlay, tag);
        ASSERT_FALSE(found.empty()) << tag;
        EXPECT_TRUE(t.sprites[found[0]].has_tag(tag));
    }
    EXPECT_GE(t.find(SpriteKind::overlay, "tree").size(), 3u);
    for (const Sprite& s : t.sprites) {
        EXPECT_EQ(s.image.width, 128) << s.name;
        EXPECT_EQ(s.image.height, 128) << s.name;
    }
}

namespace {

// Every committed sprite is the generator's, pixel for pixel (`remake`: the command that remakes them).
void expect_generators_output(const GeneratedTileset& g, const Tileset& committed, const char* remake) {
    ASSERT_EQ(g.tileset.sprites.size(), committed.sprites.size());
    for (std::size_t i = 0; i < committed.sprites.size(); ++i) {
        const Sprite &a = g.tileset.sprites[i], &b = committed.sprites[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.anchor_x, b.anchor_x);
        EXPECT_EQ(a.anchor_y, b.anchor_y);
        EXPECT_EQ(a.shape.size(), b.shape.size()) << a.name;
        EXPECT_EQ(a.image.rgba, b.image.rgba) << a.name << ": run " << remake;
    }
}

}  // namespace

TEST(Tileset, committedAssetsAreTheGeneratorsOutput) {
    expect_generators_output(generate_default_tileset(), test::default_tileset(), "isolux-cli tileset --out assets/default");
}

TEST(Tileset, committedTownAssetsAreTheGeneratorsOutput) {
    const Tileset committed = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    expect_generators_output(generate_town_tileset(), committed, "isolux-cli tileset --name town --out assets/town");
    // A mountain wider than a tile, and every object kind the town holds.
    for (const char* name : {"long_wall", "house", "town", "low_rocks", "boulder_pile", "grove", "mountain", "tower",
                             "fence", "tall_tree"})
        EXPECT_TRUE(std::any_of(committed.sprites.begin(), committed.sprites.end(),
                                [&](const Sprite& s) { return s.name == name; })) << name;
    for (const Sprite& s : committed.sprites)
        if (s.name == "mountain") {
            EXPECT_GT(s.image.width, committed.tile_width) << "wider than a tile";
        }
}

TEST(Tileset, generatorWritesHeightMapsThatMatchTheShapes) {
    TempDir d;
    GeneratedTileset g = generate_default_tileset(0.5);
    save_generated_tileset(d.path, g);
    Tileset back = load_tileset(d.path / "tileset.json");
    EXPECT_EQ(back.tile_width, 64);
    auto max_height = [&](const std::string& name) {
        for (std::size_t i = 0; i < g.tileset.sprites.size(); ++i)
            if (g.tileset.sprites[i].name == name)
                return *std::max_element(g.heights[i].begin(), g.heights[i].end());
        return std::uint16_t(0);
    };
    EXPECT_GT(max_height("pine"), max_height("bush"));
    EXPECT_GT(max_height("bush"), 0);
    EXPECT_EQ(max_height("grass"), 0);  // the floor's top is the ground plane
    Image h = load_image(d.path / "pine.height.png");
    EXPECT_EQ(h.width, 64);
}

TEST(Tileset, badShapesNameTheManifestTheEntryAndTheSolid) {
    TempDir d;
    write_png(d.path / "floor.png", 64, 48);
    struct Case {
        std::string shape, expect;
    } cases[] = {
        {R"([{"kind": "pyramid", "base": [0, 0, 0]}])", "pyramid"},
        {R"([{"kind": "box", "min": [0, 0, 0], "max": [-1, 4, 4]}])", "negative size"},
        {R"([{"kind": "cylinder", "base": [0, 0, 0], "radius": -2, "height": 5}])", "radius"},
        {R"([{"kind": "cone", "base": [0, 0, 0], "radius": 2, "height": 1e999}])", "malformed JSON"},
        {R"([{"kind": "ellipsoid", "center": [0, 0, 0], "radii": [1, -1, 1]}])", "radii"},
        {R"([{"kind": "ellipsoid", "center": [0, "x", 0], "radii": [1, 1, 1]}])", "center"},
        {R"({"kind": "box"})", "array"},
        // Beyond where its sprite is drawn: a 64x48 sprite's shape may cover
        // 65,536 ground pixels (its ground box: 363x183 here).
        {R"([{"kind": "box", "min": [0, 0, 0], "max": [180, 180, 1]}])", "covers"},
    };
    for (const Case& c : cases) {
        const std::string sprite =
            R"({"name": "odd", "image": "floor.png", "kind": "overlay", "shape": )" + c.shape + "}";
        fs::path m = d.write("tileset.json", manifest_with(sprite));
        std::string msg = error_of([&] { load_tileset(m); });
        EXPECT_MENTIONS(msg, "tileset.json");
        if (c.expect != "malformed JSON") {
            EXPECT_MENTIONS(msg, "sprites[1]");
            EXPECT_MENTIONS(msg, "shape");
        }
        EXPECT_MENTIONS(msg, c.expect);
    }
    // NaN cannot be written in JSON; a shape is read back exactly as written.
    fs::path m = d.write("tileset.json", manifest_with(
        R"({"name": "post", "image": "floor.png", "kind": "overlay", "shape": [{"kind": "cylinder", "base": [1, 2, 0], "radius": 3, "height": 40}]})"));
    const Tileset t = load_tileset(m);
    ASSERT_EQ(t.sprites[1].shape.size(), 1u);
    EXPECT_EQ(t.sprites[1].shape[0], (Solid{SolidKind::cylinder, {1, 2, 0}, {3, 3, 40}}));
    // Just within the ground a shape may cover (355x179 of 65,536): loaded.
    m = d.write("tileset.json", manifest_with(
        R"({"name": "wide", "image": "floor.png", "kind": "overlay", "shape": [{"kind": "box", "min": [0, 0, 0], "max": [176, 176, 1]}]})"));
    EXPECT_EQ(load_tileset(m).sprites[1].shape.size(), 1u);
}

TEST(Tileset, theDefaultTilesetCarriesItsShapesAndHeightMaps) {
    const Tileset t = test::default_tileset();
    const GeneratedTileset g = generate_default_tileset();
    for (std::size_t i = 0; i < t.sprites.size(); ++i) {
        EXPECT_EQ(t.sprites[i].shape, g.tileset.sprites[i].shape) << t.sprites[i].name;
        EXPECT_EQ(t.sprites[i].height, g.heights[i]) << t.sprites[i].name;
    }
}

TEST(Tileset, footprintsAreReadAndBadOnesNameTheEntry) {
    TempDir d;
    write_png(d.path / "floor.png", 64, 48);
    fs::path m = d.write("tileset.json", manifest_with(
        R"({"name": "post", "image": "floor.png", "kind": "overlay", "footprint": {"run": [3, 40, 10], "shadow_alpha": 0.8}})"));
    const Tileset t = load_tileset(m);
    EXPECT_EQ(t.sprites[1].footprint.mode, FootprintMode::run);
    EXPECT_EQ(t.sprites[1].footprint.run_length, 10);
    EXPECT_EQ(t.sprites[1].footprint.shadow_alpha, 0.8);
    for (const auto& [fp, expect] : std::vector<std::pair<std::string, std::string>>{
             {R"("sideways")", "sideways"}, {R"("run")", "run"}, {R"({"run": [1, 2]})", "run"},
             {R"({"polygon": [[0, 0], [1, 1]]})", "polygon"}, {R"({"shadow_alpha": 2})", "shadow_alpha"},
             {R"({"object": {"foot": [1]}})", "foot"}, {R"({"object": {"height": 0}})", "height"},
             {R"({"object": {"foot": [70000, 1]}})", "object"}, {R"({"object": 3})", "object"}}) {
        m = d.write("tileset.json", manifest_with(R"({"name": "odd", "image": "floor.png", "kind": "overlay", "footprint": )" + fp + "}"));
        std::string msg = error_of([&] { load_tileset(m); });
        EXPECT_MENTIONS(msg, "sprites[1]");
        EXPECT_MENTIONS(msg, "footprint");
        EXPECT_MENTIONS(msg, expect);
    }
}

// A user's correction of the estimated solid (the tileset inspector's) is
// read from the footprint, and saved into the manifest as it was read.
TEST(Tileset, anObjectCorrectionIsReadAndSavedBack) {
    TempDir d;
    write_png(d.path / "floor.png", 64, 48);
    const fs::path m = d.write("tileset.json", manifest_with(
        R"({"name": "post", "image": "floor.png", "kind": "overlay", "footprint": {"object": {"foot": [30, 40], "height": 25}}})"));
    Tileset t = load_tileset(m);
    ASSERT_TRUE(t.sprites[1].footprint.object_foot.has_value());
    EXPECT_EQ(*t.sprites[1].footprint.object_foot, (std::pair{30, 40}));
    EXPECT_EQ(t.sprites[1].footprint.object_height, 25);
    EXPECT_EQ(footprint_to_json(t.sprites[1].footprint), R"({"object":{"foot":[30,40],"height":25}})");
    t.sprites[1].footprint.object_height = 31;
    save_manifest_footprints(m, t);
    EXPECT_EQ(load_tileset(m).sprites[1].footprint, t.sprites[1].footprint);
    t.sprites[1].footprint.object_foot.reset();
    t.sprites[1].footprint.object_height = 0;
    save_manifest_footprints(m, t);
    EXPECT_EQ(load_tileset(m).sprites[1].footprint, FootprintSpec{});
    // The solid's model: read, written back, and a name that is none refused naming the field.
    t.sprites[1].footprint.object_model = ObjectModel::prism;
    EXPECT_EQ(footprint_to_json(t.sprites[1].footprint), R"({"object":{"model":"prism"}})");
    save_manifest_footprints(m, t);
    EXPECT_EQ(load_tileset(m).sprites[1].footprint.object_model, ObjectModel::prism);
    const fs::path bad = d.write("bad.json", manifest_with(
        R"({"name": "post", "image": "floor.png", "kind": "overlay", "footprint": {"object": {"model": "cube"}}})"));
    const std::string said = error_of([&] { load_tileset(bad); });
    for (const char* word : {"bad.json", "object", "model", "\"cube\"", "revolution, prism, mound"}) EXPECT_MENTIONS(said, word);
}
