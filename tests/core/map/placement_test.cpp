// Placement and drawing (placement.cpp): back to front, the same bytes for
// the same seed, the tile under a pixel.
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
}  // namespace

TEST(Placement, spritesAreDrawnBackToFront) {
    for (Layout l : {Layout::paper, Layout::diamond, Layout::staggered}) {
        Map m = generate_map("order", 12, 12, l, tiles());
        PlacedMap p = place_sprites(m, tiles());
        ASSERT_EQ(p.first_overlay, std::size_t(12 * 12));
        for (std::size_t i = 1; i < p.instances.size(); ++i) {
            const SpriteInstance &a = p.instances[i - 1], &b = p.instances[i];
            if (i == p.first_overlay) continue;  // overlays start over, above every floor
            EXPECT_LE(a.ground_y, b.ground_y) << "instance " << i;
        }
        for (const SpriteInstance& in : p.instances) {
            EXPECT_GE(in.x, 0);
            EXPECT_GE(in.y, 0);
        }
    }
}

TEST(Placement, renderIsByteIdenticalForTheSameSeed) {
    auto render = [](const char* seed) {
        Map m = generate_map(seed, 6, 6, Layout::diamond, tiles());
        PlacedMap p = place_sprites(m, tiles());
        return render_sprites(tiles(), p, p.bounds).rgba;
    };
    EXPECT_EQ(render("a"), render("a"));
    EXPECT_NE(render("a"), render("b"));
}

TEST(Placement, tileAtFindsTheTileUnderAPixel) {
    for (Layout l : {Layout::paper, Layout::diamond, Layout::staggered}) {
        Map m = generate_map("pick", 7, 5, l, tiles());
        PlacedMap p = place_sprites(m, tiles());
        for (int r = 0; r < 5; ++r)
            for (int c = 0; c < 7; ++c) {
                int cx, cy, col = -1, row = -1;
                tile_center(l, 128, 64, c, r, cx, cy);
                // A point a little off the centre, well inside the diamond.
                ASSERT_TRUE(tile_at(m, p, cx + p.shift_x + 20.5, cy + p.shift_y - 6.5, col, row));
                EXPECT_EQ(col, c);
                EXPECT_EQ(row, r);
            }
        int col, row;
        EXPECT_FALSE(tile_at(m, p, -5000, -5000, col, row));
    }
}
