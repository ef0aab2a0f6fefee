// Presets, scenes, tilesets and images: round trips, and bad input that gives a
// clear error naming the file and the entry.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <sys/stat.h>

#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/tiled.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/world.hpp"
#include "test_util.hpp"

using namespace isolux;
using isolux::test::error_of;
using isolux::test::TempDir;
namespace fs = std::filesystem;

TEST(Preset, roundTripsEveryParameter) {
    TempDir d;
    Params p;
    p.delta_y = 30;
    p.noise_window = 4;
    p.ray_skip = 3;
    p.trace_every = 2;
    p.area_a = 64;
    p.area_b = 40;
    p.ambient_clarity = 0.25;
    p.opacity_threshold = 0.3;
    p.blur_radius = 0;
    p.falloff_scale = 6.5;
    p.mode = Mode::shadow;
    p.dark_unlit = true;
    p.rays = Rays::every_pixel;
    save_preset(d.path / "p.json", p);
    EXPECT_EQ(load_preset(d.path / "p.json"), p);
}

TEST(Preset, unknownFieldsWarnAndTheRestLoads) {
    TempDir d;
    std::vector<std::string> warnings;
    Params p = load_preset(d.write("p.json", R"({"schema_version": 1, "delta_y": 12, "sparkle": true})"), &warnings);
    EXPECT_EQ(p.delta_y, 12);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_MENTIONS(warnings[0], "sparkle");
    EXPECT_MENTIONS(warnings[0], "p.json");
}

TEST(Preset, wrongTypesAndOutOfRangeValuesNameTheFileAndField) {
    TempDir d;
    std::string m = error_of([&] { load_preset(d.write("a.json", R"({"noise_window": "big"})")); });
    EXPECT_MENTIONS(m, "a.json");
    EXPECT_MENTIONS(m, "noise_window");
    m = error_of([&] { load_preset(d.write("b.json", R"({"ambient_clarity": 1.5})")); });
    EXPECT_MENTIONS(m, "b.json");
    EXPECT_MENTIONS(m, "ambient_clarity");
    m = error_of([&] { load_preset(d.write("c.json", R"({"area_a": -1})")); });
    EXPECT_MENTIONS(m, "area_a");
    m = error_of([&] { load_preset(d.write("d.json", R"({"mode": "laser"})")); });
    EXPECT_MENTIONS(m, "mode");
    EXPECT_MENTIONS(m, "laser");
    m = error_of([&] { load_preset(d.write("e.json", R"({"ray_skip": 0})")); });
    EXPECT_MENTIONS(m, "ray_skip");
    m = error_of([&] { load_preset(d.write("f.json", R"({"trace_every": 2.5})")); });
    EXPECT_MENTIONS(m, "trace_every");
    m = error_of([&] { load_preset(d.write("g.json", R"({"delta_y": 99999999999999999999})")); });
    EXPECT_MENTIONS(m, "delta_y");
}

TEST(Preset, malformedJsonAndNewerSchemasAreErrors) {
    TempDir d;
    std::string m = error_of([&] { load_preset(d.write("bad.json", R"({"delta_y": )")); });
    EXPECT_MENTIONS(m, "bad.json");
    EXPECT_MENTIONS(m, "malformed JSON");
    m = error_of([&] { load_preset(d.write("new.json", R"({"schema_version": 7})")); });
    EXPECT_MENTIONS(m, "schema_version");
    m = error_of([&] { load_preset(d.write("arr.json", "[1, 2]")); });
    EXPECT_MENTIONS(m, "object");
    m = error_of([&] { load_preset(d.path / "missing.json"); });
    EXPECT_MENTIONS(m, "missing.json");
}

TEST(Files, savingIsAtomicAndLeavesNoTemporaryFiles) {
    TempDir d;
    fs::path p = d.path / "p.json";
    save_preset(p, Params{});
    Params q;
    q.delta_y = 40;
    save_preset(p, q);
    EXPECT_EQ(load_preset(p).delta_y, 40);
    int files = 0;
    for ([[maybe_unused]] auto& e : fs::directory_iterator(d.path)) ++files;
    EXPECT_EQ(files, 1);
    // An invalid preset is refused before anything is written: the old file stays.
    q.noise_window = 0;
    EXPECT_THROW(save_preset(p, q), Error);
    EXPECT_EQ(load_preset(p).delta_y, 40);
}

TEST(Scene, roundTripsSeedMapLightsAndCamera) {
    TempDir d;
    Scene s;
    s.seed = "forest of ünïcode";
    s.width = 20;
    s.height = 12;
    s.layout = Layout::staggered;
    s.tileset = (d.path / "tiles" / "tileset.json").string();
    s.params.ambient_clarity = 0.7;
    Light a;
    a.x = 100.5;
    a.y = 200;
    Light b;
    b.x = -40;
    b.y = 3;
    b.area_a = 30;
    b.area_b = 20;
    b.r = 255, b.g = 128, b.b = 0;
    b.intensity = 2;
    s.lights = {a, b};
    s.camera = {10, 20, 640, 480};
    save_scene(d.path / "s.json", s);
    Scene t = load_scene(d.path / "s.json");
    EXPECT_EQ(t, s);
    // The tileset is stored relative to the scene, so a moved folder still loads.
    std::ifstream f(d.path / "s.json");
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_MENTIONS(text, "\"tiles/tileset.json\"");
}

TEST(Scene, badLightsNameTheLight) {
    TempDir d;
    std::string m = error_of([&] { load_scene(d.write("s.json", R"({"lights": [{"x": 1, "y": 2}, {"x": 1}]})")); });
    EXPECT_MENTIONS(m, "lights[1]");
    m = error_of([&] { load_scene(d.write("t.json", R"({"lights": [{"x": 1, "y": 2, "color": "zz0000"}]})")); });
    EXPECT_MENTIONS(m, "color");
    m = error_of([&] { load_scene(d.write("u.json", R"({"width": 0})")); });
    EXPECT_MENTIONS(m, "width");
    m = error_of([&] { load_scene(d.write("v.json", R"({"layout": "hex"})")); });
    EXPECT_MENTIONS(m, "layout");
}

// ---------------------------------------------------------------- tilesets

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

TEST(Tileset, committedAssetsAreTheGeneratorsOutput) {
    GeneratedTileset g = generate_default_tileset();
    Tileset committed = test::default_tileset();
    ASSERT_EQ(g.tileset.sprites.size(), committed.sprites.size());
    for (std::size_t i = 0; i < committed.sprites.size(); ++i) {
        const Sprite &a = g.tileset.sprites[i], &b = committed.sprites[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.anchor_x, b.anchor_x);
        EXPECT_EQ(a.anchor_y, b.anchor_y);
        EXPECT_EQ(a.image.rgba, b.image.rgba) << a.name << ": run isolux-cli tileset --out assets/default";
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

TEST(Image, sixteenBitAlphaIsComparedAtItsOwnPrecision) {
    // Alpha 32750 / 65535 = 0.49973: above a threshold of 0.4995, though its
    // 8-bit rounding (127 / 255 = 0.49804) is below it.
    TempDir d;
    auto out = OIIO::ImageOutput::create("png");
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(2, 1, 4, OIIO::TypeDesc::UINT16);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    const std::uint16_t px[8] = {60000, 60000, 60000, 32750, 60000, 60000, 60000, 32700};
    ASSERT_TRUE(out->open((d.path / "a16.png").string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, px));
    ASSERT_TRUE(out->close());
    const Image im = load_image(d.path / "a16.png");
    ASSERT_EQ(im.alpha16.size(), 2u);
    EXPECT_EQ(im.alpha16[0], 32750);
    EXPECT_EQ(im.at(0, 0)[3], 127);
    const Mask m = opacity_map(im, 0.4995);
    EXPECT_TRUE(m.get(0, 0));   // 0.49973 > 0.4995
    EXPECT_FALSE(m.get(1, 0));  // 32700 / 65535 = 0.49897 < 0.4995
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
}

TEST(Files, savingThroughASymlinkKeepsTheLinkAndTheModeAndALoopIsRefused) {
    TempDir d;
    fs::create_directories(d.path / "real");
    const fs::path target = d.path / "real" / "scene.json", link = d.path / "scene.json";
    write_file_atomic(target, "old");
    fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write);
    fs::create_symlink(fs::path("real") / "scene.json", link);
    write_file_atomic(link, "new");
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
    std::ifstream in(target);
    std::string text;
    in >> text;
    EXPECT_EQ(text, "new");
    EXPECT_EQ(fs::status(target).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
    // A loop of links is refused, not followed forever.
    fs::create_symlink("loop_b.json", d.path / "loop_a.json");
    fs::create_symlink("loop_a.json", d.path / "loop_b.json");
    EXPECT_MENTIONS(error_of([&] { write_file_atomic(d.path / "loop_a.json", "x"); }), "loop_a.json");
}

TEST(Files, savingAFileWithHardLinksKeepsThemAndItsInode) {
    TempDir d;
    const fs::path a = d.path / "scene.json", b = d.path / "also_scene.json";
    write_file_atomic(a, "old contents, longer than the new");
    fs::create_hard_link(a, b);
    struct stat before {};
    ASSERT_EQ(::stat(a.c_str(), &before), 0);
    write_file_atomic(a, "new");
    struct stat after {};
    ASSERT_EQ(::stat(a.c_str(), &after), 0);
    EXPECT_EQ(after.st_ino, before.st_ino);
    EXPECT_EQ(after.st_nlink, 2u);
    for (const fs::path& p : {a, b}) {
        std::ifstream in(p);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        EXPECT_EQ(text, "new") << p;
    }
    // No temporary file is left beside them.
    int files = 0;
    for (const auto& e : fs::directory_iterator(d.path)) files += e.is_regular_file();
    EXPECT_EQ(files, 2);
    // An image too.
    Image im(3, 2);
    for (std::uint8_t& v : im.rgba) v = 200;
    save_image(d.path / "shot.png", im);
    fs::create_hard_link(d.path / "shot.png", d.path / "shot_link.png");
    im.rgba[0] = 7;
    save_image(d.path / "shot.png", im);
    EXPECT_EQ(load_image(d.path / "shot_link.png").rgba, im.rgba);
}

TEST(Files, noSaveReplacesAFifoADeviceOrASocketAndTheMessageSaysWhy) {
    TempDir d;
    const fs::path fifo = d.path / "pipe", link = d.path / "link.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    fs::create_symlink(fifo, link);
    std::string m = error_of([&] { write_file_atomic(fifo, "x"); });
    EXPECT_MENTIONS(m, "is a FIFO");
    m = error_of([&] { save_image(link, Image(2, 2)); });
    EXPECT_MENTIONS(m, "is a FIFO");
    m = error_of([&] { check_output_file(d.path / "no" / "such.csv"); });
    EXPECT_MENTIONS(m, "does not exist");
    EXPECT_TRUE(fs::is_fifo(fifo));
    // The machine's own /dev/null is refused by name (nothing is written: the
    // check comes before any temporary file).
    m = error_of([&] { check_output_file("/dev/null"); });
    EXPECT_MENTIONS(m, "is a device");
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(Files, aReadErrorIsAnErrorNamingTheFileNotAnotherException) {
    // /proc/self/mem is a regular file whose reads fail (EIO at offset 0).
    std::string m;
    try {
        read_text_file("/proc/self/mem");
    } catch (const Error& e) {
        m = e.what();
    }
    EXPECT_MENTIONS(m, "/proc/self/mem: cannot read");
}

TEST(Files, messagesCarryControlCharactersEscaped) {
    const std::string m = Error(std::string("a\x1b[2J\nb\x07" "c\xc2\x9b" "d\xc3\xa9")).what();
    EXPECT_EQ(m, "a\\x1b[2J\\x0ab\\x07c\\x9bd\xc3\xa9");  // C0, C1 (UTF-8) escaped; é kept
}

namespace {

// A manifest of one floor and one overlay (a 4x4 PNG each) whose overlay
// carries `fields` (a JSON object's members, e.g. "anchor": [1, 2]).
fs::path manifest_with(const TempDir& d, const std::string& name, const std::string& fields) {
    save_image(d.path / "px.png", Image(4, 4));
    return d.write(name, R"({"sprites": [{"name": "g", "image": "px.png", "kind": "floor"},
                                         {"name": "o", "image": "px.png", "kind": "overlay", )" + fields + "}]}");
}

// A 1x1 isometric map whose one tile (an embedded tileset's tile 0) carries
// the isolux_* properties `props` (name, value pairs).
fs::path tiled_map_with(const TempDir& d, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& props) {
    save_image(d.path / "px.png", Image(4, 4));
    std::string p;
    for (const auto& [k, v] : props) p += "<property name=\"" + k + "\" value=\"" + v + "\"/>";
    return d.write(name, R"(<?xml version="1.0" encoding="UTF-8"?>
<map version="1.8" orientation="isometric" renderorder="right-down" width="1" height="1" tilewidth="4" tileheight="2" infinite="0">
 <tileset firstgid="1" name="t" tilewidth="4" tileheight="4" tilecount="1" columns="0">
  <tile id="0"><properties>)" + p + R"(</properties><image width="4" height="4" source="px.png"/></tile>
 </tileset>
 <layer id="1" name="floors" width="1" height="1"><data encoding="csv">1</data></layer>
</map>
)");
}

}  // namespace

TEST(SpriteFields, anAnchorWithinTheOneLimitLoadsFromAManifestAndATiledMap) {
    TempDir d;
    const Tileset ts = load_tileset(manifest_with(d, "m.json", R"("anchor": [65536, -65536], "tags": ["tree"])"));
    EXPECT_EQ(ts.sprites[1].anchor_x, max_sprite_offset);
    EXPECT_EQ(ts.sprites[1].anchor_y, -max_sprite_offset);
    EXPECT_EQ(ts.sprites[1].tags, std::vector<std::string>{"tree"});
    const TiledMap m = load_tiled(tiled_map_with(d, "m.tmx", {{"isolux_anchor_x", "65536"}, {"isolux_tags", "grass,wet"},
                                                              {"isolux_opacity_threshold", "0.25"}}));
    ASSERT_EQ(m.world.tileset.sprites.size(), 1u);
    const Sprite& s = m.world.tileset.sprites[0];
    EXPECT_EQ(s.anchor_x, max_sprite_offset);
    EXPECT_EQ(s.tags, (std::vector<std::string>{"grass", "wet"}));
    EXPECT_EQ(s.opacity_threshold, 0.25);
}

TEST(SpriteFields, oneLimitRefusesTheSameOffsetsInManifestsAndTiledMapsByName) {
    TempDir d;
    // The same field, one past the limit, in each format: refused, naming
    // the file, the field and the limit.
    std::string m = error_of([&] { load_tileset(manifest_with(d, "a.json", R"("anchor": [65537, 0])")); });
    EXPECT_MENTIONS(m, "a.json");
    EXPECT_MENTIONS(m, "anchor");
    EXPECT_MENTIONS(m, "65536");
    m = error_of([&] { load_tiled(tiled_map_with(d, "a.tmx", {{"isolux_anchor_y", "-65537"}})); });
    EXPECT_MENTIONS(m, "a.tmx: tile 0 (isolux_* properties)");
    EXPECT_MENTIONS(m, "anchor");
    EXPECT_MENTIONS(m, "65536");
    // A footprint's points share the limit.
    m = error_of([&] { load_tileset(manifest_with(d, "b.json", R"("footprint": {"run": [65537, 0, 3]})")); });
    EXPECT_MENTIONS(m, "footprint");
    EXPECT_MENTIONS(m, "65536");
    m = error_of([&] {
        load_tiled(tiled_map_with(d, "b.tmx", {{"isolux_footprint", R"({&quot;run&quot;: [0, 65537, 3]})"}}));
    });
    EXPECT_MENTIONS(m, "b.tmx: tile 0 (isolux_* properties): footprint");
    EXPECT_MENTIONS(m, "65536");
    // What is not a number says so, as the manifest's parser words it.
    m = error_of([&] { load_tiled(tiled_map_with(d, "c.tmx", {{"isolux_anchor_x", "12px"}})); });
    EXPECT_MENTIONS(m, "anchor");
    EXPECT_MENTIONS(m, "must be [x, y] integers");
    m = error_of([&] { load_tiled(tiled_map_with(d, "d.tmx", {{"isolux_opacity_threshold", "2"}})); });
    EXPECT_MENTIONS(m, "opacity_threshold must be in [0, 1]");
}

// The files isolux names itself inside a folder the user chose never follow
// a symbolic link out of it: an export's TSX or images folder, an image in the
// images folder an interrupted export left, a generated tileset's image. Each is
// refused by name, and what the link points to keeps its bytes.
TEST(Files, filesIsoluxNamesItselfInAChosenFolderNeverFollowALinkOutOfIt) {
    TempDir d;
    const fs::path outside = d.path / "outside";
    fs::create_directories(outside);
    write_file_atomic(outside / "victim.tsx", "keep");
    const Scene scene = [] {
        Scene s;
        s.width = s.height = 4;
        return s;
    }();
    const World w = make_world(test::default_tileset(), scene);
    auto outside_untouched = [&] {
        EXPECT_EQ(read_text_file(outside / "victim.tsx"), "keep");
        std::size_t n = 0;
        for ([[maybe_unused]] const auto& f : fs::directory_iterator(outside)) ++n;
        EXPECT_EQ(n, 1u) << "a file was written outside the chosen folder";
    };
    {  // the export's TSX is a link to a file outside
        fs::create_directories(d.path / "a");
        fs::create_symlink(outside / "victim.tsx", d.path / "a" / "m_floors.tsx");
        EXPECT_MENTIONS(error_of([&] { export_tiled(w, scene, d.path / "a" / "m.tmx"); }), "m_floors.tsx");
        EXPECT_FALSE(fs::exists(d.path / "a" / "m.tmx"));
        outside_untouched();
    }
    {  // the export's images folder is a link to a folder outside
        fs::create_directories(d.path / "b");
        fs::create_symlink(outside, d.path / "b" / "m_images");
        EXPECT_MENTIONS(error_of([&] { export_tiled(w, scene, d.path / "b" / "m.tmx"); }), "m_images");
        outside_untouched();
    }
    {  // the images folder an interrupted re-export left holds a link where an image goes
        fs::create_directories(d.path / "c");
        export_tiled(w, scene, d.path / "c" / "m.tmx");  // an isolux map: the next export writes m_images.1
        std::string image;
        for (const auto& f : fs::directory_iterator(d.path / "c" / "m_images")) image = f.path().filename().string();
        ASSERT_FALSE(image.empty());
        fs::create_directories(d.path / "c" / "m_images.1");
        fs::create_symlink(outside / "victim.tsx", d.path / "c" / "m_images.1" / image);
        export_tiled(w, scene, d.path / "c" / "m.tmx");  // the leftovers are cleared, the link never followed
        EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(d.path / "c" / "m_images.1" / image)));
        outside_untouched();
    }
    {  // a generated tileset's image is a link
        fs::create_directories(d.path / "t");
        const GeneratedTileset g = generate_default_tileset(0.5);
        fs::create_symlink(outside / "victim.tsx", d.path / "t" / g.image_files.back());
        EXPECT_MENTIONS(error_of([&] { save_generated_tileset(d.path / "t", g); }), g.image_files.back());
        EXPECT_FALSE(fs::exists(d.path / "t" / "tileset.json"));
        outside_untouched();
    }
    // A file the user names is still written through its link.
    fs::create_directories(d.path / "e");
    fs::create_symlink(outside / "victim.tsx", d.path / "e" / "named.json");
    write_file_atomic(d.path / "e" / "named.json", "new");
    EXPECT_EQ(read_text_file(outside / "victim.tsx"), "new");
}
