// Algorithm 1 and the box noise filter (paper 3.1), checked pixel by pixel
// against values worked out by hand in the comments.
#include <gtest/gtest.h>

#include "isolux/hash.hpp"
#include "isolux/footprint.hpp"
#include "isolux/image_file.hpp"

#include <cmath>
#include <cstdint>
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"
#include "test_util.hpp"

using namespace isolux;
using test::mask_from;
using test::set_pixels;
using test::sprite_from;
using V = std::vector<std::string>;

namespace {
int widest_run(const Mask& op) {
    int best = 0;
    for (int y = 0; y < op.height; ++y)
        for (int x = 0, len = 0; x < op.width; ++x) {
            len = op.bits[std::size_t(y) * op.width + x] ? len + 1 : 0;
            best = std::max(best, len);
        }
    return best;
}

void expect_obstacles_at_the_base(const Tileset& ts) {
    Params p;
    for (const Sprite& s : ts.sprites) {
        if (s.kind != SpriteKind::overlay) continue;
        SpriteObstacleTrace t;
        Mask op = opacity_map(s.image, sprite_threshold(s, p.opacity_threshold));
        Mask m = sprite_obstacle(op, p.delta_y, &t);
        ASSERT_GT(m.count(), 0) << s.name;
        // The obstacle stands where the sprite meets the ground: within Δy of
        // its lowest opaque row, no further below the anchor than the
        // footprint reaches (half a floor diamond).
        EXPECT_GE(t.chosen_line, t.last_line - p.delta_y + 1) << s.name;
        EXPECT_GE(t.last_line, s.anchor_y - 2) << s.name;
        EXPECT_LE(t.last_line, s.anchor_y + ts.tile_height / 2) << s.name;
        if (s.has_tag("tree")) {
            // For a tree that is the trunk or the lowest branches, never the
            // canopy's full width, and it is centred on the trunk.
            EXPECT_LT(t.run_length, widest_run(op) * 9 / 10) << s.name;
            EXPECT_NEAR(t.run_start + t.run_length / 2, s.anchor_x, 4) << s.name;
        }
    }
}
}  // namespace

TEST(ObstacleMap, readsDeltaYLinesEndingAtTheLowestOpaqueRow) {
    // Lowest opaque row 5; Δy = 3 reads rows 3..5, all runs of 2 at x = 4:
    // the mean is 2, all tie, the lowest row wins. length/4 = 0: no arms.
    Mask op = opacity_map(sprite_from({".########.", ".########.", ".########.", "....##....", "....##....",
                                       "....##....", ".........."}),
                          0.5);
    SpriteObstacleTrace t;
    Mask m = sprite_obstacle(op, 3, &t);
    EXPECT_EQ(t.first_line, 3);
    EXPECT_EQ(t.last_line, 5);
    EXPECT_EQ(t.chosen_line, 5);
    EXPECT_EQ(set_pixels(m), V({"4,5", "5,5"}));
}

TEST(ObstacleMap, takesTheRunWithLeastDeviationFromTheMean) {
    const V rows = {"##........", "..######..", ".####.....", "...##.###."};
    Mask op = opacity_map(sprite_from(rows), 0.5);
    // Δy = 3: rows 1..3, longest runs 6, 4, 3 (row 3 keeps its 3, not its 2):
    // mean 4.33, deviations 1.67, 0.33, 1.33 -> row 2, start 1, length 4.
    // Centre x = 1 + (4-1)/2 = 2; arms of 4/4 = 1 pixel above and below.
    SpriteObstacleTrace t;
    Mask m = sprite_obstacle(op, 3, &t);
    EXPECT_EQ(t.chosen_line, 2);
    EXPECT_EQ(t.run_start, 1);
    EXPECT_EQ(t.run_length, 4);
    EXPECT_EQ(set_pixels(m), V({"2,1", "1,2", "2,2", "3,2", "4,2", "2,3"}));
    // Δy = 2: rows 2..3, runs 4 and 3, mean 3.5: a tie, the lower row wins:
    // start 6, length 3, centre 7, no arms.
    EXPECT_EQ(set_pixels(sprite_obstacle(op, 2)), V({"6,3", "7,3", "8,3"}));
    // Δy larger than the sprite reads every row: runs 2, 6, 4, 3, mean 3.75,
    // deviations 1.75, 2.25, 0.25, 0.75 -> row 2 again.
    EXPECT_EQ(set_pixels(sprite_obstacle(op, 100)), V({"2,1", "1,2", "2,2", "3,2", "4,2", "2,3"}));
}

TEST(ObstacleMap, fullyTransparentSpriteHasNoObstacle) {
    Mask op = opacity_map(sprite_from({"....", "....", "++++"}), 0.6);
    EXPECT_EQ(sprite_obstacle(op, 25).count(), 0);
}

TEST(ObstacleMap, fullyOpaqueSpriteArmsReachOutsideTheSprite) {
    // 4x4 opaque, Δy = 2: rows 2..3 tie at 4 -> row 3, start 0, centre 1,
    // arms of 1: (1,2) above and (1,4) below the sprite.
    Mask op = opacity_map(sprite_from({"####", "####", "####", "####"}), 0.5);
    EXPECT_EQ(set_pixels(sprite_obstacle(op, 2)), V({"1,2", "0,3", "1,3", "2,3", "3,3", "1,4"}));
}

TEST(ObstacleMap, onePixelSprite) {
    EXPECT_EQ(set_pixels(sprite_obstacle(opacity_map(sprite_from({"#"}), 0.5), 25)), V({"0,0"}));
}

TEST(ObstacleMap, equalRunsOnALineKeepTheLeftmost) {
    EXPECT_EQ(set_pixels(sprite_obstacle(opacity_map(sprite_from({".##.##"}), 0.5), 1)), V({"1,0", "2,0"}));
}

TEST(NoiseFilter, clearsTopLeftPixelsOfSparseWindows) {
    // n = 3. (0,0): its window holds (0,0) and (2,2): 2 < 3, cleared.
    // (2,2): (2,2) (3,2) (4,2) (4,4) = 4, kept. (3,2): 3, kept.
    // (4,2): clipped window holds (4,2) (4,4) = 2, cleared. (4,4): 1, cleared.
    Mask m = mask_from({"#....", ".....", "..###", ".....", "....#"});
    EXPECT_EQ(set_pixels(noise_filter(m, 3)), V({"2,2", "3,2"}));
}

TEST(NoiseFilter, windowOfOneKeepsEverything) {
    Mask m = mask_from({"#.#", ".#.", "#.."});
    EXPECT_EQ(noise_filter(m, 1).bits, m.bits);
}

TEST(NoiseFilter, windowLargerThanTheMapClearsSparseMaps) {
    Mask m = mask_from({"##", "#."});
    EXPECT_EQ(noise_filter(m, 5).count(), 0);  // 3 set pixels < 5 in every window
    EXPECT_EQ(noise_filter(m, 3).count(), 1);  // only (0,0)'s window holds 3
}

TEST(NoiseFilter, equalsThePapersInPlaceSlidingWindow) {
    // The paper's pass, transcribed: slide the window in raster order over the
    // mask being filtered, clearing as it goes.
    auto naive = [](Mask m, int n) {
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x) {
                int count = 0;
                for (int v = y; v < std::min(m.height, y + n); ++v)
                    for (int u = x; u < std::min(m.width, x + n); ++u) count += m.bits[v * m.width + u];
                if (count < n) m.bits[y * m.width + x] = 0;
            }
        return m;
    };
    Pcg32 rng(5);
    for (int trial = 0; trial < 40; ++trial) {
        Mask m(Rect{0, 0, 5 + int(rng.below(30)), 5 + int(rng.below(30))});
        int density = 10 + int(rng.below(60));
        for (auto& b : m.bits) b = int(rng.below(100)) < density;
        int n = 1 + int(rng.below(6));  // odd and even windows
        EXPECT_EQ(noise_filter(m, n).bits, naive(m, n).bits) << "trial " << trial << " n " << n;
    }
}

TEST(ObstacleMap, aRegionEqualsTheSameCropOfTheWholeMap) {
    Tileset ts = test::default_tileset();
    PlacedMap p = place_sprites(generate_map("crop", 8, 8, Layout::diamond, ts), ts);
    Params params;
    params.noise_window = 4;
    Mask whole = build_obstacle_map(ts, p, params, p.bounds);
    ASSERT_GT(whole.count(), 0);
    Rect r{301, 157, 230, 190};
    Mask part = build_obstacle_map(ts, p, params, r);
    for (int y = r.y; y < r.y + r.h; ++y)
        for (int x = r.x; x < r.x + r.w; ++x) ASSERT_EQ(part.get(x, y), whole.get(x, y)) << x << "," << y;
}

TEST(ObstacleMap, sitsAtTheBaseOfTreesAndBushesInTheDefaultTileset) {
    expect_obstacles_at_the_base(test::default_tileset());
}

TEST(ObstacleMap, sitsAtTheBaseOfTreesInATilesetOfOtherArtAndSizes) {
    expect_obstacles_at_the_base(test::foreign_tileset());
}

TEST(ObstacleMap, floorsNeverObstruct) {
    Tileset ts = test::default_tileset();
    Map m = generate_map("floors", 6, 6, Layout::diamond, ts);
    for (Tile& t : m.tiles) t.overlay_count = 0;
    PlacedMap p = place_sprites(m, ts);
    EXPECT_EQ(build_obstacle_map(ts, p, Params{}, p.bounds).count(), 0);
}

// ---------------------------------------------------------------- footprints (not in the paper)
