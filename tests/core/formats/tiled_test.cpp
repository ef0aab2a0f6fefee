// Tiled maps out and in (core/src/formats/tiled/tiled_export.cpp, tiled_import.cpp): what
// an export writes and where, and that a map read back exports again whole.
// (Tiled's own renderer judges the exports in tests/tiled/.)
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/tiled.hpp"
#include "isolux/world.hpp"
#include "isolux/sprite_shading.hpp"
#include "test_util.hpp"

using namespace isolux;
using isolux::test::error_of;
using isolux::test::TempDir;
namespace fs = std::filesystem;

namespace {

Scene small_scene() {
    Scene s;
    s.seed = "tiled";
    s.width = s.height = 6;
    s.lights = {Light{300.5, 200.5}};
    return s;
}

Image final_frame(const World& w, const Scene& s) {
    FrameState st;
    const Rect b = w.placed.bounds;
    render_frame(st, w, s, Camera{double(b.x), double(b.y), b.w, b.h}, 0);
    return st.final;
}

std::size_t floor_count(const World& w) {
    return std::size_t(std::count_if(w.placed.instances.begin(), w.placed.instances.end(), [&](const SpriteInstance& in) {
        return in.sprite >= 0 && w.tileset.sprites[std::size_t(in.sprite)].kind == SpriteKind::floor;
    }));
}

}  // namespace

TEST(TiledExport, aMapReadBackExportsAgainToTheSamePixels) {
    TempDir d;
    const Scene scene = small_scene();
    const World seeded = make_world(test::default_tileset(), scene);
    fs::create_directories(d.path / "a");
    fs::create_directories(d.path / "b");
    export_tiled(seeded, scene, d.path / "a" / "map.tmx");
    const TiledMap once = load_tiled(d.path / "a" / "map.tmx");
    ASSERT_EQ(floor_count(once.world), std::size_t(scene.width * scene.height));
    export_tiled(once.world, once.scene, d.path / "b" / "map.tmx");
    const TiledMap twice = load_tiled(d.path / "b" / "map.tmx");
    // Every floor survives the second export (it was written as gid 0).
    EXPECT_EQ(floor_count(twice.world), floor_count(once.world));
    EXPECT_EQ(twice.world.placed.instances.size(), once.world.placed.instances.size());
    const Image a = final_frame(once.world, once.scene), b = final_frame(twice.world, twice.scene);
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    EXPECT_TRUE(a.rgba == b.rgba);
}

TEST(TiledExport, spriteNamesNeverBecomePathsAndSameNamesGetImagesOfTheirOwn) {
    TempDir d;
    Tileset ts = test::default_tileset();
    // Names a received manifest or TMX may carry: paths out of the folder,
    // an absolute path, and one name for two different sprites.
    std::vector<std::string> hostile = {"../../escape", "/tmp/absolute", "dup", "DUP", "dup"};
    std::size_t k = 0;
    for (Sprite& s : ts.sprites)
        if (k < hostile.size()) s.name = hostile[k++];
    const Scene scene = small_scene();
    const World w = make_world(ts, scene);
    fs::create_directories(d.path / "out" / "deep");
    const fs::path tmx = d.path / "out" / "deep" / "map.tmx";
    export_tiled(w, scene, tmx);
    // Everything written lies inside the export's folder.
    for (const auto& f : fs::recursive_directory_iterator(d.path)) {
        if (!f.is_regular_file()) continue;
        const std::string p = f.path().string();
        EXPECT_EQ(p.rfind((d.path / "out" / "deep").string(), 0), 0u) << p << " was written outside the export's folder";
    }
    EXPECT_FALSE(fs::exists("/tmp/absolute.png"));
    // One image per sprite used, none shared: as many PNGs as sprites used.
    std::set<int> used;
    for (const SpriteInstance& in : w.placed.instances)
        if (in.sprite >= 0) used.insert(in.sprite);
    std::size_t pngs = 0;
    for (const auto& f : fs::directory_iterator(d.path / "out" / "deep" / "map_images")) pngs += f.path().extension() == ".png";
    EXPECT_EQ(pngs, used.size());
    // Read back, each sprite draws its own pixels.
    const TiledMap back = load_tiled(tmx);
    const Image a = final_frame(w, scene), b = final_frame(back.world, back.scene);
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    EXPECT_TRUE(a.rgba == b.rgba);
}

// With normal_maps each sprite's normal map and height map lie beside its
// image, named in its tile's properties, their pixels those of
// sprite_normals; a sprite named after another's normal map ("oak.normal")
// gets files of its own.
TEST(TiledExport, normalMapsLieBesideTheSpritesNamedInTheirTiles) {
    TempDir d;
    Scene scene = small_scene();
    World w = make_world(test::default_tileset(), scene);
    std::set<int> used;
    for (const SpriteInstance& in : w.placed.instances)
        if (in.sprite >= 0) used.insert(in.sprite);
    // Two floors the map shows, the second named after the first's normal map.
    std::vector<int> floors;
    for (int s : used)
        if (w.tileset.sprites[std::size_t(s)].kind == SpriteKind::floor) floors.push_back(s);
    ASSERT_GE(floors.size(), 2u);
    w.tileset.sprites[std::size_t(floors[1])].name = w.tileset.sprites[std::size_t(floors[0])].name + ".normal";
    const Tileset& ts = w.tileset;
    const fs::path tmx = d.path / "map.tmx";
    TiledExport opt;
    opt.normal_maps = true;
    export_tiled(w, scene, tmx, opt);
    std::size_t normals = 0, heights = 0, images = 0;
    for (const auto& f : fs::directory_iterator(d.path / "map_images")) {
        const std::string n = f.path().filename().string();
        const bool normal = n.size() > 11 && n.substr(n.size() - 11) == ".normal.png";
        const bool height = n.size() > 11 && n.substr(n.size() - 11) == ".height.png";
        normals += normal, heights += height, images += !normal && !height;
    }
    EXPECT_EQ(images, used.size());
    EXPECT_EQ(normals, used.size()) << "one normal map a sprite, none written over another's image";
    EXPECT_EQ(heights, used.size());
    // Each tile names its maps; the oak's are sprite_normals' bytes.
    const std::string tsx = read_text_file(d.path / "map_overlays.tsx");
    EXPECT_NE(tsx.find("name=\"normal_map\" type=\"file\" value=\"map_images/oak.normal.png\""), std::string::npos);
    EXPECT_NE(tsx.find("name=\"isolux_height_map\" type=\"file\" value=\"map_images/oak.height.png\""), std::string::npos);
    const Sprite& oak = ts.sprites[std::size_t(ts.find(SpriteKind::overlay, "tree").front())];
    ASSERT_EQ(oak.name, "oak");
    const SpriteNormals n = sprite_normals(ts, oak, scene.params, SpriteShading::solids);
    const Image normal = load_image(d.path / "map_images" / "oak.normal.png");
    const std::vector<std::uint8_t> want = normal_map_rgb(n, NormalConvention::opengl);
    ASSERT_EQ(normal.width, n.width);
    for (std::size_t i = 0; i < want.size() / 3; ++i)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(normal.rgba[i * 4 + std::size_t(c)], want[i * 3 + std::size_t(c)]) << i;
    EXPECT_EQ(load_gray16(d.path / "map_images" / "oak.height.png", n.width, n.height), height_map_values(n));
    // Read back, the level draws as it did: the maps change nothing isolux reads.
    const TiledMap back = load_tiled(tmx);
    EXPECT_TRUE(final_frame(w, scene).rgba == final_frame(back.world, back.scene).rgba);
}

// A first export beside files of the user's that bear the export's names
// (their own level_floors.tsx, a level_images folder) is refused by the
// name, writes nothing, and leaves them as they were.
TEST(TiledExport, aFirstExportNeverReplacesFilesItDidNotWrite) {
    TempDir d;
    const Scene scene = small_scene();
    const World w = make_world(test::default_tileset(), scene);
    const fs::path tmx = d.path / "level.tmx";
    auto listing = [&] {
        std::vector<std::string> names;
        for (const auto& f : fs::recursive_directory_iterator(d.path)) names.push_back(f.path().string());
        std::sort(names.begin(), names.end());
        return names;
    };
    for (const char* own : {"level_floors.tsx", "level_overlays.tsx", "level_light.png", "level_final.png"}) {
        write_file_atomic(d.path / own, "the user's own");
        const auto before = listing();
        const std::string m = error_of([&] { export_tiled(w, scene, tmx); });
        EXPECT_MENTIONS(m, own);
        EXPECT_MENTIONS(m, "already exists");
        EXPECT_EQ(read_text_file(d.path / own), "the user's own");
        EXPECT_EQ(listing(), before) << "the refused export wrote or removed a file";
        fs::remove(d.path / own);
    }
    fs::create_directories(d.path / "level_images");
    write_file_atomic(d.path / "level_images" / "mine.png", "the user's own");
    EXPECT_MENTIONS(error_of([&] { export_tiled(w, scene, tmx); }), "level_images");
    EXPECT_EQ(read_text_file(d.path / "level_images" / "mine.png"), "the user's own");
    EXPECT_FALSE(fs::exists(tmx));
    // Elsewhere, or once the name is free, the export is written whole.
    fs::remove_all(d.path / "level_images");
    export_tiled(w, scene, tmx);
    EXPECT_TRUE(fs::exists(d.path / "level_images"));
    EXPECT_EQ(load_tiled(tmx).world.map.width, w.map.width);
}

TEST(TiledExport, aReExportWritesNewFilesThenTheMapThenRemovesTheOldOnes) {
    TempDir d;
    Scene scene = small_scene();
    const World w = make_world(test::default_tileset(), scene);
    const fs::path tmx = d.path / "level.tmx";
    auto names = [&](const std::string& text) { return read_text_file(tmx).find(text) != std::string::npos; };
    TiledExport with_images;
    with_images.images = true;
    export_tiled(w, scene, tmx, with_images);
    EXPECT_TRUE(names("\"level_overlays.tsx\""));
    EXPECT_TRUE(fs::exists(d.path / "level_images"));
    EXPECT_TRUE(fs::exists(d.path / "level_final.png"));
    // The second export's files stand under the other names before the map
    // names them; the first export's are gone once it does.
    scene.lights.push_back(Light{200.5, 150.5});
    export_tiled(w, scene, tmx, with_images);
    EXPECT_TRUE(names("\"level_overlays.1.tsx\""));
    ASSERT_TRUE(fs::exists(d.path / "level_overlays.1.tsx"));
    EXPECT_NE(read_text_file(d.path / "level_overlays.1.tsx").find("\"level_images.1/"), std::string::npos);
    EXPECT_TRUE(fs::exists(d.path / "level_final.1.png"));
    for (const char* old : {"level_overlays.tsx", "level_floors.tsx", "level_images", "level_final.png", "level_light.png"})
        EXPECT_FALSE(fs::exists(d.path / old)) << old << " outlived the export that replaced it";
    EXPECT_EQ(load_tiled(tmx).scene.lights.size(), 2u);
    // And back: a third export takes the first names again.
    export_tiled(w, scene, tmx);
    EXPECT_TRUE(names("\"level_overlays.tsx\""));
    EXPECT_FALSE(fs::exists(d.path / "level_overlays.1.tsx"));
    EXPECT_FALSE(fs::exists(d.path / "level_images.1"));
    EXPECT_EQ(load_tiled(tmx).scene.lights.size(), 2u);
}

TEST(TiledExport, aMapIntoAFolderThatDoesNotExistIsRefusedBeforeAnythingIsWritten) {
    TempDir d;
    const Scene scene = small_scene();
    const World w = make_world(test::default_tileset(), scene);
    EXPECT_MENTIONS(error_of([&] { export_tiled(w, scene, d.path / "missing" / "level.tmx"); }), "does not exist");
    EXPECT_FALSE(fs::exists(d.path / "missing"));
}
