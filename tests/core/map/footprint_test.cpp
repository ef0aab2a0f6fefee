// Footprints on real art (footprint.cpp): auto on the default tileset is the
// paper's Algorithm 1; baked ground, whole bases, explicit runs and polygons.
#include <gtest/gtest.h>

#include "isolux/hash.hpp"
#include "isolux/footprint.hpp"
#include "isolux/image_file.hpp"

#include <algorithm>
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

// Trees' feet (trunks_on_tile): a foot off the floor diamond is a branch's;
// pieces of one trunk (side by side on the ground, or one above another in
// a column) are one trunk standing on the lowest; a grove's trees stay apart.
TEST(Footprint, trunksAreFeetOnTheTileWithTheirPiecesMerged) {
    // A 128 x 64 tile anchored at (64, 100): its diamond spans rows 68..132.
    const std::vector<TrunkFoot> found = {
        {40, 30},                  // a branch high in a crown
        {30, 104}, {40, 110},      // one trunk in two pieces, 10 + 5 ground px apart
        {90, 96},  {91, 84},       // one trunk crossed by a bough: one column, 12 rows apart
        {64, 120}};                // a third tree
    const std::vector<TrunkFoot> trunks = trunks_on_tile(found, 64, 100, 128, 64);
    ASSERT_EQ(trunks.size(), 3u);
    EXPECT_EQ(trunks[0].x, 40);  // the lowest piece, trunks by column
    EXPECT_EQ(trunks[0].y, 110);
    EXPECT_EQ(trunks[1].x, 64);
    EXPECT_EQ(trunks[2].x, 90);
    EXPECT_EQ(trunks[2].y, 96);
    // Two trees 20 px apart on the ground stay two.
    EXPECT_EQ(trunks_on_tile({{50, 100}, {70, 110}}, 64, 100, 128, 64).size(), 2u);
}

// Bark is brown: a trunk under an orange crown of the same hue is found
// (the crown, as red as bark but saturated, is not bark).
TEST(Footprint, aTrunkUnderAnOrangeCrownIsFound) {
    Image im(64, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            std::uint8_t* p = im.at(x, y);
            if (std::hypot(x + 0.5 - 32, y + 0.5 - 20) <= 14) p[0] = 190, p[1] = 100, p[2] = 30, p[3] = 255;
            if (x >= 30 && x < 34 && y > 30 && y < 56) p[0] = 80, p[1] = 54, p[2] = 42, p[3] = 255;
        }
    const std::vector<TrunkFoot> feet = find_trunks(im);
    ASSERT_EQ(feet.size(), 1u);
    EXPECT_NEAR(feet[0].x, 31.5, 0.01);
    EXPECT_EQ(feet[0].y, 55);
}

// A grove's crowns are told apart by colour: two crowns that overlap,
// each shaded smoothly and outlined in a dark line, are two regions, the
// one behind keeping only what shows; the outline and the trunk belong to
// neither. Foliage textured pixel by pixel (neighbours 40 or more apart)
// holds no region a crown's size.
TEST(Footprint, crownsAreTheRegionsOfOneSmoothlyShadedColour) {
    Image im(64, 64);
    auto crown = [&](double cx, double cy, double r, int red, int green, bool textured) {
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
                if (d > r) continue;
                std::uint8_t* p = im.at(x, y);
                const int shade = int(20 * (x - cx) / r) + (textured && (x + y) % 2 ? 40 : 0);
                p[0] = std::uint8_t(std::clamp(red + shade, 0, 255)), p[1] = std::uint8_t(std::clamp(green + shade, 0, 255));
                p[2] = 30, p[3] = 255;
                if (d > r - 1) p[0] = p[1] = p[2] = 20;  // the outline
            }
    };
    crown(26, 22, 12, 200, 110, false);  // orange, behind
    crown(36, 30, 12, 210, 190, false);  // yellow, in front
    for (int y = 42; y < 60; ++y)
        for (int x = 34; x < 38; ++x) {
            std::uint8_t* p = im.at(x, y);
            p[0] = 80, p[1] = 54, p[2] = 42, p[3] = 255;  // bark
        }
    const Mask object = opacity_map(im, 0.5);
    const std::vector<Mask> crowns = crown_regions(im, object);
    ASSERT_EQ(crowns.size(), 2u);
    // Row-major order: the orange crown's first pixel is higher.
    EXPECT_TRUE(crowns[0].get(20, 16));
    EXPECT_FALSE(crowns[0].get(36, 30));
    EXPECT_TRUE(crowns[1].get(36, 30));
    EXPECT_LT(crowns[0].count(), crowns[1].count());  // the front crown hides part of the one behind
    for (const Mask& c : crowns) {
        EXPECT_FALSE(c.get(36, 50));   // the trunk
        EXPECT_FALSE(c.get(36, 18));   // the front crown's outline, at its top
    }
    Image noisy(64, 64);
    std::swap(im, noisy);
    crown(32, 28, 16, 60, 140, true);
    EXPECT_TRUE(crown_regions(im, opacity_map(im, 0.5)).empty());
}

// A scatter of things on one tile (rocks): each part standing on the floor
// diamond is an object's own, with Algorithm 1's footprint under it; a
// blob floating above the diamond (a crown's leaf) and a speck are not.
TEST(Footprint, partsStandingApartOnTheTileAreTheirOwn) {
    Image im(128, 128);
    auto disc = [&](double cx, double cy, double r) {
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x)
                if (std::hypot(x + 0.5 - cx, (y + 0.5 - cy) * 1.5) <= r) {
                    std::uint8_t* p = im.at(x, y);
                    p[0] = 120, p[1] = 120, p[2] = 130, p[3] = 255;
                }
    };
    disc(40, 100, 12);  // a rock, bottom at row 108
    disc(84, 94, 9);    // another, further back
    disc(64, 20, 10);   // a floating blob: its bottom far above the diamond (rows 68..132)
    disc(100, 110, 1.2);  // a speck
    const Mask op = opacity_map(im, 0.5);
    FootprintReport r;
    sprite_footprint(im, op, 64, 100, 128, 64, 25, FootprintMode::automatic, FootprintSpec{}, &r);
    ASSERT_EQ(r.parts.size(), 2u);
    std::vector<double> centres;
    for (const ObjectPart& part : r.parts) {
        double cx = 0, cy = 0, fx = 0, fy = 0;
        Rect box, fbox;
        ASSERT_TRUE(mask_centre(part.object, cx, cy, box));
        ASSERT_TRUE(mask_centre(part.footprint, fx, fy, fbox));
        EXPECT_NEAR(fx, cx, 1.5);  // the footprint is under its own part
        EXPECT_GT(fy, cy);
        centres.push_back(cx);
    }
    std::sort(centres.begin(), centres.end());
    EXPECT_NEAR(centres[0], 40, 1);
    EXPECT_NEAR(centres[1], 84, 1);
    // One part alone is the whole object: no parts.
    Image one(128, 128);
    for (int y = 80; y < 100; ++y)
        for (int x = 50; x < 70; ++x) one.at(x, y)[3] = 255;
    FootprintReport single;
    sprite_footprint(one, opacity_map(one, 0.5), 64, 100, 128, 64, 25, FootprintMode::automatic, FootprintSpec{}, &single);
    EXPECT_TRUE(single.parts.empty());
}
