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

TEST(OpacityMap, alphaExactlyAtTheThresholdIsTransparent) {
    Image im = sprite_from({"#+."});
    Mask m = opacity_map(im, 128 / 255.0);
    EXPECT_EQ(set_pixels(m), V({"0,0"}));
    EXPECT_EQ(set_pixels(opacity_map(im, 0.5)), V({"0,0", "1,0"}));  // 128/255 > 0.5
    EXPECT_EQ(set_pixels(opacity_map(im, 1.0)), V{});
}

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

TEST(Footprint, autoIsThePapersAlgorithmOnTheDefaultTileset) {
    // Its sprites carry neither a baked ground nor a baked shadow: the
    // default footprint changes nothing the paper's estimate gives them.
    const Tileset t = test::default_tileset();
    Params paper, automatic;
    paper.footprint = Footprint::paper;
    for (const Sprite& s : t.sprites) {
        if (s.kind != SpriteKind::overlay) continue;
        FootprintReport r;
        EXPECT_EQ(tileset_footprint(t, s, automatic, &r).bits, tileset_footprint(t, s, paper).bits) << s.name;
        EXPECT_FALSE(r.baked_ground) << s.name;
        EXPECT_FALSE(r.baked_shadow) << s.name;
    }
}

TEST(Footprint, aBakedGroundDiamondIsTakenOutAndTheObjectsFootKept) {
    // A 64x48 sprite: a green diamond (64x32, centre 32,32) and a brown post
    // 4 px wide standing at x = 20..23 from y = 0 down to y = 30, inside it.
    Image im(64, 48);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            std::uint8_t* p = im.at(x, y);
            if (std::abs(x + 0.5 - 32) / 32 + std::abs(y + 0.5 - 32) / 16 <= 1) p[0] = 60, p[1] = 160, p[2] = 50, p[3] = 255;
            if (x >= 20 && x < 24 && y <= 30) p[0] = 110, p[1] = 70, p[2] = 40, p[3] = 255;
        }
    const Mask op = opacity_map(im, 0.5);
    FootprintReport r;
    FootprintSpec spec;
    const Mask fp = sprite_footprint(im, op, 32, 32, 64, 32, 25, FootprintMode::automatic, spec, &r);
    EXPECT_TRUE(r.baked_ground);
    EXPECT_FALSE(r.whole_base);  // the diamond's V, but the post covers little of it
    double cx = 0, cy = 0;
    Rect box;
    ASSERT_TRUE(mask_centre(fp, cx, cy, box));
    EXPECT_NEAR(cx, 22, 1.5);  // the post's foot, not the diamond's middle
    EXPECT_NEAR(cy, 30, 2.5);
    const Mask paper = sprite_footprint(im, op, 32, 32, 64, 32, 25, FootprintMode::paper, spec);
    ASSERT_TRUE(mask_centre(paper, cx, cy, box));
    EXPECT_GT(std::abs(cx - 22), 6);  // the paper's run lies on the diamond
}

TEST(Footprint, aBlockThatFillsItsTileStandsOnItsWholeBase) {
    // A 64x56 sprite: a grey block whose base is the tile's diamond (64x32,
    // centre 32,40), 16 px tall: the diamond and the diamond 16 px higher,
    // joined by its vertical sides; its top, left and right faces shaded
    // apart, as a lit block is. It reads as a baked ground diamond (its
    // lower half is opaque, nothing is outside it), but a third of its base
    // is not the colour of its ring.
    Image im(64, 56);
    auto in_diamond = [](double x, double y, double cy) { return std::abs(x - 32) / 32 + std::abs(y - cy) / 16 <= 1; };
    for (int y = 0; y < 56; ++y)
        for (int x = 0; x < 64; ++x) {
            bool in = false;
            for (int z = 0; z <= 16 && !in; ++z) in = in_diamond(x + 0.5, y + 0.5 + z, 40);
            if (!in) continue;
            const bool top = in_diamond(x + 0.5, y + 0.5 + 16, 40);
            std::uint8_t* p = im.at(x, y);
            p[0] = p[1] = p[2] = top ? 150 : x < 32 ? 70 : 200;
            p[3] = 255;
        }
    const Mask op = opacity_map(im, 0.5);
    FootprintReport r;
    FootprintSpec spec;
    const Mask fp = sprite_footprint(im, op, 32, 40, 64, 32, 25, FootprintMode::automatic, spec, &r);
    EXPECT_TRUE(r.whole_base);
    ASSERT_EQ(r.base.size(), 4u);
    double cx = 0, cy = 0;
    Rect box;
    ASSERT_TRUE(mask_centre(fp, cx, cy, box));
    EXPECT_NEAR(cx, 32, 1.5);  // the base's centre: the tile's
    EXPECT_NEAR(cy, 40, 1.5);
    EXPECT_GE(box.w, 60);
    EXPECT_GE(box.h, 28);
    // Algorithm 1 alone: a run across the block's front.
    const Mask paper = sprite_footprint(im, op, 32, 40, 64, 32, 25, FootprintMode::paper, spec, &r);
    EXPECT_FALSE(r.whole_base);
    EXPECT_LT(paper.count() * 4, fp.count());
}

TEST(Footprint, explicitRunsPolygonsAndNoneAreTaken) {
    Image im(32, 32);
    const Mask op = opacity_map(im, 0.5);
    FootprintSpec spec;
    spec.run_x = 4, spec.run_y = 20, spec.run_length = 8;
    const Mask run = sprite_footprint(im, op, 16, 31, 64, 32, 25, FootprintMode::run, spec);
    EXPECT_TRUE(run.get(4, 20) && run.get(11, 20) && !run.get(12, 20));
    EXPECT_TRUE(run.get(8, 18) && run.get(8, 22) && !run.get(8, 23));  // arms of length / 4 = 2
    spec.polygon = {{2, 2}, {10, 2}, {10, 6}, {2, 6}};
    const Mask poly = sprite_footprint(im, op, 16, 31, 64, 32, 25, FootprintMode::polygon, spec);
    EXPECT_EQ(poly.count(), 8 * 4);
    EXPECT_EQ(sprite_footprint(im, op, 16, 31, 64, 32, 25, FootprintMode::none, spec).count(), 0);
}

// The row-by-row fill against the even-odd rule tested pixel by pixel, on a
// concave polygon with edges that cross pixel centres' rows at odd places.
TEST(Footprint, polygonFillIsTheEvenOddRuleAtEveryPixelCentre) {
    Image im(97, 61);
    const Mask op = opacity_map(im, 0.5);
    FootprintSpec spec;
    Pcg32 rng(7);
    for (int k = 0; k < 40; ++k) {
        const double angle = 6.283185307179586 * k / 40;
        const double r = 10 + double(rng.below(20));
        spec.polygon.push_back({48 + int(std::lround(r * std::cos(angle) * 1.6)), 30 + int(std::lround(r * std::sin(angle)))});
    }
    spec.polygon.push_back({-5, 70});  // a spike out of the sprite
    const Mask poly = sprite_footprint(im, op, 48, 60, 64, 32, 25, FootprintMode::polygon, spec);
    long inside_count = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            bool inside = false;
            const double px = x + 0.5, py = y + 0.5;
            const auto& p = spec.polygon;
            for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
                const double xi = p[i].first, yi = p[i].second, xj = p[j].first, yj = p[j].second;
                if ((yi > py) != (yj > py) && px < (xj - xi) * (py - yi) / (yj - yi) + xi) inside = !inside;
            }
            ASSERT_EQ(poly.get(x, y), inside) << x << "," << y;
            inside_count += inside;
        }
    EXPECT_GT(inside_count, 500);
}

// A sprite's footprint mask is budgeted with its image: Algorithm 1 on a
// sprite W wide may mark W x W/2 pixels, so one 65536 x 1 sprite counts for
// two gigapixels and is refused by the readers (tests/bad/run.py).
TEST(Footprint, theMaskBudgetCoversAlgorithm1AndRuns) {
    FootprintSpec spec;
    EXPECT_EQ(footprint_pixels(128, 128, spec), 128 * 128);
    EXPECT_EQ(footprint_pixels(128, 8, spec), 128 * 65);
    EXPECT_GT(footprint_pixels(65536, 1, spec), max_input_sprite_pixels);
    spec.run_length = 4000;
    EXPECT_EQ(footprint_pixels(16, 16, spec), 16 * (16 + 2000));
    // The largest mask each mode draws stays within the bound.
    Image im(64, 6);
    for (int x = 0; x < 64; ++x) im.at(x, 5)[3] = 255;
    const Mask op = opacity_map(im, 0.5);
    spec.run_x = 0, spec.run_y = 5, spec.run_length = 64;
    for (FootprintMode m : {FootprintMode::paper, FootprintMode::run, FootprintMode::automatic}) {
        const Mask mask = sprite_footprint(im, op, 32, 5, 64, 32, 25, m, spec);
        EXPECT_LE(std::int64_t(mask.width) * mask.height, footprint_pixels(64, 6, spec)) << int(m);
        EXPECT_GT(mask.count(), 0) << int(m);
    }
}
