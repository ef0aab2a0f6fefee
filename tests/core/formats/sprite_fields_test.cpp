// A sprite's fields (sprite_fields.cpp): one parser and one limit, from a
// manifest and from a Tiled map alike.
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
