// Stamping a sprite's solids (occluder_stamp.cpp): every pixel holds its
// object's span, and a sprite pixel the topmost point on its view line.
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "isolux/accuracy.hpp"
#include "isolux/error.hpp"
#include "isolux/hash.hpp"
#include "isolux/frame.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/solid.hpp"
#include "isolux/solid_estimate.hpp"
#include "test_util.hpp"
#include "solids/oracles.hpp"
#include "frame/frame_cache.hpp"

using namespace isolux;
using isolux::test::error_of;

// The height each shown sprite pixel takes (sprite_solids tests only the
// heights near its view line's crossing of the deepest cross-section): the topmost
// half-pixel height on its view line inside a solid, front object first,
// found here by trying every height, on every overlay of the default tileset;
// on a flat-topped prism's top cross-section, its top face's height.
TEST(OccluderStamp, aSpritePixelShowsTheTopmostSolidPointOnItsViewLine) {
    const Tileset ts = test::default_tileset();
    Params p;
    p.occluders = Occluders::solids;
    long tested = 0, from_solids = 0, on_flat_tops = 0;
    for (const Sprite& sp : ts.sprites) {
        if (sp.kind != SpriteKind::overlay) continue;
        const SpriteSolids ss = sprite_solids(ts, sp, p);
        const Mask shown = opacity_map(sp.image, sprite_threshold(sp, p.opacity_threshold));
        ASSERT_EQ(ss.objects.size(), 1u) << sp.name;
        const EstimatedObject& o = ss.objects[0];
        for (int y = 0; y < sp.image.height; ++y)
            for (int x = 0; x < sp.image.width; ++x) {
                if (!shown.get(x, y)) continue;
                const double sx = x + 0.5 - o.center_x, sy = y + 0.5 - o.center_y;
                double expected = -1;
                for (double z = o.height() - 0.5; z >= 0 && expected < 0; z -= 0.5)
                    if (o.contains(ground_frame(sx, sy, z))) expected = z;
                if (o.flat_top && expected == o.height() - 0.5) {
                    expected = o.height();
                    ++on_flat_tops;
                }
                from_solids += expected >= 0;
                if (expected < 0) expected = std::max(0.0, o.center_y - (y + 0.5));
                ++tested;
                ASSERT_EQ(ss.heights[std::size_t(y) * sp.image.width + x], float(expected)) << sp.name << " at " << x << "," << y;
            }
    }
    EXPECT_GT(from_solids, tested / 2);  // most shown pixels show a solid's point
    EXPECT_GT(on_flat_tops, 100);        // the wall's top
}

// A solid's stamp (its spans over the ground under it) and its silhouette
// are made row by row; here every pixel asks the estimate itself
// (EstimatedObject::span_at, and each cross-section's ellipse drawn pixel by
// pixel, or a prism's view lines sampled), on the default and town
// tilesets' overlays and on a tree four times their size, drawn from its
// true shapes.
TEST(OccluderStamp, eachStampPixelHoldsItsObjectsSpanAndTheSilhouetteEachCrossSection) {
    Tileset ts = test::default_tileset();
    {
        const std::vector<Solid> tree = {Solid{SolidKind::cylinder, {0, 0, 0}, {16, 16, 120}},
                                         Solid{SolidKind::ellipsoid, {0, 0, 180}, {112, 112, 96}}};
        Sprite big;
        big.name = "big_tree";
        big.image = Image(330, 450);
        big.anchor_x = 165, big.anchor_y = 420;
        for (int y = 0; y < big.image.height; ++y)
            for (int x = 0; x < big.image.width; ++x)
                if (std::isfinite(surface_height(tree, x + 0.5 - big.anchor_x, y + 0.5 - big.anchor_y))) {
                    std::uint8_t* px = big.image.at(x, y);
                    px[0] = px[1] = px[2] = 90, px[3] = 255;
                }
        ts.sprites.push_back(big);
    }
    Params p;
    p.occluders = Occluders::solids;
    long spans = 0, drawn = 0;
    int prisms = 0;
    bool big_seen = false;
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    for (const Tileset* set : {static_cast<const Tileset*>(&ts), &town}) {
    for (const Sprite& sp : set->sprites) {
        if (sp.kind != SpriteKind::overlay) continue;
        const SpriteSolids ss = sprite_solids(*set, sp, p);
        Mask sampled(Rect{0, 0, sp.image.width, sp.image.height});
        ASSERT_EQ(ss.stamps.size(), ss.objects.size()) << sp.name;
        big_seen = big_seen || (sp.name == "big_tree" && !ss.objects.empty() && ss.objects[0].height() > 200);
        Mask want(Rect{0, 0, sp.image.width, sp.image.height});
        for (std::size_t k = 0; k < ss.objects.size(); ++k) {
            const EstimatedObject& o = ss.objects[k];
            const SpanStamp& st = ss.stamps[k];
            for (int j = 0; j < st.rect.h; ++j)
                for (int i = 0; i < st.rect.w; ++i) {
                    const Vec3 q = ground_frame(st.rect.x + i + 0.5 - o.center_x, st.rect.y + j + 0.5 - o.center_y, 0);
                    double lo = 0, hi = 0;
                    std::pair<float, float> expected{0.f, 0.f};
                    if (o.span_at(q.x, q.y, lo, hi)) expected = {float(lo), float(hi)}, ++spans;
                    ASSERT_EQ(st.spans[std::size_t(j) * st.rect.w + std::size_t(i)], expected)
                        << sp.name << " at " << st.rect.x + i << "," << st.rect.y + j;
                }
            if (o.model == ObjectModel::prism) {
                // A prism's view lines, sampled every 1/32 px of height: what
                // they meet is drawn (the silhouette may add only the
                // pixels whose line grazes an edge between two samples),
                // on the pixels of its hull (a view line's points all show
                // at its own pixel).
                ++prisms;
                for (int y = 0; y < sp.image.height; ++y)
                    for (int x = 0; x < sp.image.width; ++x)
                        for (double z = 0; z <= o.height() && o.hull_shows(x, y); z += 1.0 / 32) {
                            const Vec3 q = ground_frame(x + 0.5 - o.center_x, y + 0.5 - o.center_y, z);
                            if (std::abs(q.x) <= o.half_x && std::abs(q.y) <= o.half_y && z <= o.top_at(q.x, q.y) &&
                                o.behind_front(q.x, q.y)) {
                                sampled.set(x, y);
                                break;
                            }
                        }
                continue;
            }
            for (std::size_t z = 0; z < o.radius.size(); ++z) {
                const double r = o.radius[z], a = o.across_at(z) * std::sqrt(2.0), b = r / std::sqrt(2.0),
                             yc = o.center_y - (double(z) + 0.5);
                if (r <= 0) continue;
                for (int y = int(std::floor(yc - b)); y <= int(std::ceil(yc + b)); ++y) {
                    const double v = (y + 0.5 - yc) / b;
                    if (v * v > 1) continue;
                    const double hw = a * std::sqrt(1 - v * v);
                    for (int x = int(std::ceil(o.center_x - hw - 0.5)); x <= int(std::floor(o.center_x + hw - 0.5)); ++x)
                        want.set(x, y);
                }
            }
        }
        const Mask got = solid_silhouette(ss.objects, sp.image.width, sp.image.height);
        long extra = 0;
        for (int y = 0; y < sp.image.height; ++y)
            for (int x = 0; x < sp.image.width; ++x) {
                if (sampled.get(x, y)) want.set(x, y);
                extra += got.get(x, y) && !want.get(x, y);
                EXPECT_TRUE(got.get(x, y) || !want.get(x, y)) << sp.name << ": " << x << "," << y << " not drawn";
            }
        EXPECT_LE(double(extra), 0.01 * double(sampled.count())) << sp.name;
        drawn += want.count();
    }
    }
    EXPECT_GE(prisms, 3) << "the town's walls, house and hedge are prisms";
    EXPECT_TRUE(big_seen) << "the large tree gets a solid over 200 px high";
    EXPECT_GT(spans, 10000);
    EXPECT_GT(drawn, 10000);
}
