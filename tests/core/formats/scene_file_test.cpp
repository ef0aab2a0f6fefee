// Presets and scenes (scene_file.cpp): round trips, unknown fields, and bad
// input that gives a clear error naming the file and the field.
#include <gtest/gtest.h>

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

