// Seeded generation (paper sections 2 and 3, map.cpp): the same seed gives the
// same map, a larger map extends a smaller one, terrain not noise, the layouts.
#include <gtest/gtest.h>

#include <map>

#include "isolux/error.hpp"
#include "isolux/map.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {
const Tileset& tiles() {
    static Tileset t = test::default_tileset();
    return t;
}
bool same_tiles(const Map& a, const Map& b) {
    if (a.tiles.size() != b.tiles.size()) return false;
    for (std::size_t i = 0; i < a.tiles.size(); ++i) {
        const Tile &x = a.tiles[i], &y = b.tiles[i];
        if (x.floor != y.floor || x.overlay_count != y.overlay_count) return false;
        for (int k = 0; k < x.overlay_count; ++k)
            if (x.overlays[k].sprite != y.overlays[k].sprite || x.overlays[k].dx != y.overlays[k].dx ||
                x.overlays[k].dy != y.overlays[k].dy)
                return false;
    }
    return true;
}
}  // namespace

TEST(Map, sameSeedGivesTheSameMap) {
    Map a = generate_map("isolux", 32, 32, Layout::diamond, tiles());
    Map b = generate_map("isolux", 32, 32, Layout::diamond, tiles());
    EXPECT_TRUE(same_tiles(a, b));
}

TEST(Map, otherSeedGivesAnotherMap) {
    Map a = generate_map("isolux", 32, 32, Layout::diamond, tiles());
    Map b = generate_map("isolux2", 32, 32, Layout::diamond, tiles());
    EXPECT_FALSE(same_tiles(a, b));
}

TEST(Map, aLargerMapExtendsASmallerOne) {
    Map small = generate_map("s", 8, 8, Layout::diamond, tiles());
    Map big = generate_map("s", 20, 12, Layout::diamond, tiles());
    for (int r = 0; r < 8; ++r)
        for (int c = 0; c < 8; ++c) EXPECT_EQ(small.at(c, r).floor, big.at(c, r).floor);
}

TEST(Map, refusesZeroNegativeAndTooLargeSizes) {
    EXPECT_THROW(generate_map("s", 0, 4, Layout::diamond, tiles()), Error);
    EXPECT_THROW(generate_map("s", 4, -1, Layout::diamond, tiles()), Error);
    EXPECT_THROW(generate_map("s", max_map_side + 1, 4, Layout::diamond, tiles()), Error);
    // A side may reach 4096 tiles, the tiles in all 1024 x 1024's: a long
    // strip is a map, the same area as a square, as many tiles again not.
    const Map strip = generate_map("s", max_map_side, 8, Layout::diamond, tiles());
    EXPECT_EQ(strip.tiles.size(), std::size_t(max_map_side) * 8);
    EXPECT_TRUE(map_size_ok(4096, 256));
    EXPECT_TRUE(map_size_ok(1024, 1024));
    EXPECT_FALSE(map_size_ok(1024, 1025));
    EXPECT_THROW(generate_map("s", 2048, 1024, Layout::diamond, tiles()), Error);
    try {
        generate_map("s", 0, 4, Layout::diamond, tiles());
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("0x4"), std::string::npos) << e.what();
    }
}

TEST(Map, generates256x256Maps) {
    Map m = generate_map("big", 256, 256, Layout::diamond, tiles());
    EXPECT_EQ(m.tiles.size(), 256u * 256u);
    PlacedMap p = place_sprites(m, tiles());
    EXPECT_GE(p.instances.size(), 256u * 256u);
    EXPECT_GE(p.bounds.w, 256 * 128);  // W+H half-tiles wide, plus overlays at the edges
    EXPECT_LT(p.bounds.w, 256 * 128 + 2 * 128);
}

TEST(Map, readsAsTerrainNotNoise) {
    // Biome noise makes regions: neighbouring tiles share their floor far more
    // often than independent choices among 5 floors would (about 1 in 5).
    Map m = generate_map("isolux", 48, 48, Layout::diamond, tiles());
    int same = 0, pairs = 0;
    std::map<std::string, int> floors;
    for (int r = 0; r < 48; ++r)
        for (int c = 0; c < 48; ++c) {
            floors[tiles().sprites[m.at(c, r).floor].tags[0]]++;
            if (c + 1 < 48) {
                ++pairs;
                same += m.at(c, r).floor == m.at(c + 1, r).floor;
            }
        }
    EXPECT_GT(double(same) / pairs, 0.6);
    EXPECT_GE(floors.size(), 4u) << "expected meadows, forests, water and sand";
}

TEST(Map, tilesHoldAFloorAndAtMostThreeOverlaysAndWaterHoldsNone) {
    Map m = generate_map("isolux", 48, 48, Layout::diamond, tiles());
    int with_overlays = 0;
    for (const Tile& t : m.tiles) {
        ASSERT_GE(t.floor, 0);
        EXPECT_EQ(tiles().sprites[t.floor].kind, SpriteKind::floor);
        ASSERT_LE(t.overlay_count, 3);
        for (int k = 0; k < t.overlay_count; ++k)
            EXPECT_EQ(tiles().sprites[t.overlays[k].sprite].kind, SpriteKind::overlay);
        if (tiles().sprites[t.floor].has_tag("water")) {
            EXPECT_EQ(t.overlay_count, 0);
        }
        with_overlays += t.overlay_count > 0;
    }
    EXPECT_GT(with_overlays, 0);
}

TEST(Map, paperLayoutFollowsSection3AssemblyRule) {
    const int tw = 128, th = 64;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) {
            int x, y, rx, ry;
            tile_center(Layout::paper, tw, th, col, row, x, y);
            // The next block of the line sits right of this one.
            tile_center(Layout::paper, tw, th, col + 1, row, rx, ry);
            EXPECT_EQ(rx, x + tw);
            EXPECT_EQ(ry, y);
        }
    // After a line break: below the previous line's first block p, centred
    // between p and p+1.
    for (int row = 1; row < 4; ++row) {
        int px, py, qx, qy, nx, ny;
        tile_center(Layout::paper, tw, th, 0, row - 1, px, py);
        tile_center(Layout::paper, tw, th, 1, row - 1, qx, qy);
        tile_center(Layout::paper, tw, th, 0, row, nx, ny);
        EXPECT_EQ(nx, (px + qx) / 2);
        EXPECT_EQ(ny, py + th / 2);
    }
}

TEST(Map, diamondAndStaggeredMatchTiled) {
    int x, y;
    tile_center(Layout::diamond, 128, 64, 3, 1, x, y);
    EXPECT_EQ(x, (3 - 1) * 64);
    EXPECT_EQ(y, (3 + 1) * 32);
    tile_center(Layout::staggered, 128, 64, 2, 3, x, y);  // odd row: shifted half a tile
    EXPECT_EQ(x, 2 * 128 + 64);
    EXPECT_EQ(y, 3 * 32);
    tile_center(Layout::staggered, 128, 64, 2, 2, x, y);
    EXPECT_EQ(x, 2 * 128);
}

TEST(Map, worksWithOtherArtAndSizes) {
    Tileset f = test::foreign_tileset();
    EXPECT_EQ(f.tile_width, 64);
    Map m = generate_map("foreign", 10, 10, Layout::diamond, f);
    PlacedMap p = place_sprites(m, f);
    Image im = render_sprites(f, p, p.bounds);
    EXPECT_EQ(im.width, p.bounds.w);
    int trees = 0;
    for (const Tile& t : m.tiles)
        for (int k = 0; k < t.overlay_count; ++k) trees += f.sprites[t.overlays[k].sprite].name == "lollipop";
    EXPECT_GT(trees, 0);
}

TEST(Map, aTilesetWhoseFloorsCarryUnknownTagsStillBuildsMaps) {
    // Found by tests/fuzz/fuzz_tileset: no floor tagged grass, water, ... and
    // none untagged used to index an empty list.
    Tileset t;
    for (const char* tag : {"nrass", "lava"}) {
        Sprite s;
        s.name = tag;
        s.kind = SpriteKind::floor;
        s.tags = {tag};
        s.image = Image(8, 8);
        t.sprites.push_back(s);
    }
    Map m = generate_map("any", 6, 6, Layout::diamond, t);
    for (const Tile& tile : m.tiles) {
        ASSERT_GE(tile.floor, 0);
        EXPECT_EQ(t.sprites[tile.floor].kind, SpriteKind::floor);
    }
}
