// Solids estimated from a sprite's alpha alone (core/src/solids/solid_estimate.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "isolux/footprint.hpp"
#include "isolux/solid_estimate.hpp"
#include "isolux/tileset_file.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {

// The sprite of `set` named `name` (nullptr: none).
const Sprite* find_sprite(const Tileset& set, const std::string& name) {
    for (const Sprite& c : set.sprites)
        if (c.name == name) return &c;
    return nullptr;
}

// The opaque pixels of `shape` drawn by the projection with its anchor at
// (ax, ay) of a w x h sprite: where the view line meets a solid.
Mask drawn(const std::vector<Solid>& shape, int w, int h, int ax, int ay) {
    Mask m(Rect{0, 0, w, h});
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (std::isfinite(surface_height(shape, x + 0.5 - ax, y + 0.5 - ay))) m.set(x, y);
    return m;
}

// A footprint of a few pixels around the anchor: where the trunk stands.
Mask foot(int w, int h, int ax, int ay) {
    Mask m(Rect{0, 0, w, h});
    for (int y = ay - 2; y < ay + 2; ++y)
        for (int x = ax - 2; x < ax + 2; ++x) m.set(x, y);
    return m;
}

// The heights the solid fills `d` ground pixels from its axis in depth
// (toward the viewer), where its cross-sections are the discs it fitted.
bool span_in_depth(const EstimatedObject& o, double d, double& lo, double& hi) {
    return o.span_at(d / std::sqrt(2.0), d / std::sqrt(2.0), lo, hi);
}

const Solid trunk{SolidKind::cylinder, {0, 0, 0}, {4, 4, 30}};
const Solid canopy{SolidKind::ellipsoid, {0, 0, 45}, {28, 28, 24}};

}  // namespace

// A tree drawn from its true shapes: the estimate stands a canopy off the
// ground above a thin trunk and shares most of the tree's volume. A dome's
// outline reaches above its top (seen from above at an angle), and the discs
// go up to the outline's top row: the top is estimated a few pixels high.
TEST(SolidEstimate, aTreeGetsATrunkAndACanopyStandingOffTheGround) {
    const int w = 200, h = 170, ax = 100, ay = 150;
    const Mask object = drawn({trunk, canopy}, w, h, ax, ay);
    const auto objects = estimate_objects(object, foot(w, h, ax, ay));
    ASSERT_EQ(objects.size(), 1u);
    const EstimatedObject& o = objects[0];
    EXPECT_NEAR(o.center_x, ax, 0.01);
    EXPECT_NEAR(o.center_y, ay, 0.01);
    EXPECT_NEAR(o.height(), 45 + 24, 10);
    double lo = 0, hi = 0;
    ASSERT_TRUE(o.span_at(0, 0, lo, hi));  // at the axis: from the ground to the top
    EXPECT_EQ(lo, 0);
    EXPECT_EQ(hi, o.height());
    // 20 px from the axis, past the trunk: only the canopy, well off the ground.
    ASSERT_TRUE(span_in_depth(o, 20, lo, hi));
    const double half = 24 * std::sqrt(1 - (20.0 / 28) * (20.0 / 28));
    EXPECT_NEAR(lo, 45 - half, 4);
    EXPECT_GT(lo, 20);
    EXPECT_NEAR(hi, 45 + half, 6);
    EXPECT_FALSE(span_in_depth(o, 35, lo, hi));  // beyond the canopy: nothing
    EXPECT_GT(volume_overlap(objects, ax, ay, {trunk, canopy}), 0.75);
}

// A bush whose footprint Algorithm 1 puts at its widest row (its equator,
// 10 px above where it stands): the foot moves down to where the bush meets
// the ground, so the solid is a dome on the ground, not a pancake at the
// equator. Its discs reach the outline's top row: the ellipsoid's outline
// tops out sqrt(13^2 + 17^2 / 2) = 17.7 px above its centre, 27.7 px up.
// The equator's lines may also have put the footprint a column or two off
// the axis: the axis moves back to it.
TEST(SolidEstimate, aBushsFootMovesDownFromItsEquatorToWhereItStands) {
    const int w = 120, h = 120, ax = 60, ay = 100;
    const std::vector<Solid> bush{{SolidKind::ellipsoid, {0, 0, 10}, {17, 17, 13}}};
    const Mask object = drawn(bush, w, h, ax, ay);
    const auto at_equator = estimate_objects(object, foot(w, h, ax, ay - 10));
    ASSERT_EQ(at_equator.size(), 1u);
    EXPECT_NEAR(at_equator[0].center_y, ay, 3);
    EXPECT_GE(at_equator[0].height(), 10 + 13);  // a dome up to the outline's top
    EXPECT_LE(at_equator[0].height(), 28);
    EXPECT_GT(volume_overlap(at_equator, ax, ay, bush), 0.6);
    for (int off : {-2, 2}) {
        const auto off_axis = estimate_objects(object, foot(w, h, ax + off, ay - 10));
        ASSERT_EQ(off_axis.size(), 1u);
        EXPECT_NEAR(off_axis[0].center_x, ax, 0.5) << "footprint " << off << " px off the axis";
        EXPECT_NEAR(off_axis[0].center_y, ay, 3);
    }
    // A footprint already where it stands stays there.
    const auto at_foot = estimate_objects(object, foot(w, h, ax, ay));
    ASSERT_EQ(at_foot.size(), 1u);
    EXPECT_NEAR(at_foot[0].center_y, ay, 3);
}

// The default tileset's bush: a dome with two smaller clumps at its sides
// (across the view), all sunk a little into the ground. The largest disc
// that fits near the ground stops at the dome's lower front, short of the
// clumps; widened across the view to the silhouette's width at their
// height, the cross-sections near the ground reach them, as a low light's
// shadow needs.
TEST(SolidEstimate, aBushsSideClumpsNearTheGroundAreReachedAcrossTheView) {
    const int w = 160, h = 130, ax = 80, ay = 110;
    const std::vector<Solid> bush{{SolidKind::ellipsoid, {0, 0, 10}, {17, 17, 13}},
                                  {SolidKind::ellipsoid, {9, -6, 8}, {11, 11, 9}},
                                  {SolidKind::ellipsoid, {-7, 8, 9}, {11, 11, 10}}};
    const auto objects = estimate_objects(drawn(bush, w, h, ax, ay), foot(w, h, ax, ay));
    ASSERT_EQ(objects.size(), 1u);
    const EstimatedObject& o = objects[0];
    const Vec3 axis = ground_frame(o.center_x - ax, o.center_y - ay, 0);
    for (const Vec3 clump : {Vec3{9, -6, 0}, Vec3{-7, 8, 0}}) {
        // 7 px beyond the clump's centre, away from the axis, 2 px up: inside the clump.
        const Vec3 out = clump + 7.0 * glm::normalize(clump);
        bool in_shape = false;
        for (const Solid& s : bush) in_shape = in_shape || solid_contains(s, Vec3{out.x, out.y, 2});
        ASSERT_TRUE(in_shape);
        double lo = 0, hi = 0;
        ASSERT_TRUE(o.span_at(out.x - axis.x, out.y - axis.y, lo, hi)) << "clump at " << clump.x << "," << clump.y;
        EXPECT_LT(lo, 4) << "the estimate stands there from near the ground";
        EXPECT_FALSE(span_in_depth(o, glm::length(out - axis), lo, hi) && lo < 4)
            << "in depth, where the silhouette says nothing, the same distance is past the discs near the ground";
    }
}

// A skirted tree: a cone of foliage from 10 px up whose front edge hangs
// lower on screen than its trunk's foot, so the sprite never shows the
// trunk. Every disc below the skirt is hidden behind it: they stand on a
// stem (hidden_stem_ratio of the skirt), not on a cone of foliage reaching
// the ground. A bush resting on the ground shows its lower half below its
// widest disc and keeps its discs as the silhouette allows.
TEST(SolidEstimate, aSkirtThatHidesItsTrunkStandsOnAStem) {
    const int w = 160, h = 150, ax = 80, ay = 120;
    const std::vector<Solid> pine{{SolidKind::cylinder, {0, 0, 0}, {3, 3, 16}}, {SolidKind::cone, {0, 0, 10}, {24, 24, 60}}};
    const Mask object = drawn(pine, w, h, ax, ay);
    const auto objects = estimate_objects(object, foot(w, h, ax, ay));
    ASSERT_EQ(objects.size(), 1u);
    const std::vector<double>& r = objects[0].radius;
    const auto widest = std::size_t(std::max_element(r.begin(), r.end()) - r.begin());
    EXPECT_GE(widest, 6u);
    EXPECT_GT(r[widest], 18);
    for (std::size_t z = 0; z < widest; ++z) EXPECT_LE(r[z], hidden_stem_ratio * r[widest] + 1e-9) << z;
    double lo = 0, hi = 0;
    ASSERT_TRUE(span_in_depth(objects[0], 12, lo, hi));  // under the skirt: the foliage starts off the ground
    EXPECT_GE(lo, double(widest) - 1);
    EXPECT_GT(volume_overlap(objects, ax, ay, pine), 0.6);

    const std::vector<Solid> bush{{SolidKind::ellipsoid, {0, 0, 10}, {17, 17, 13}}};
    const auto resting = estimate_objects(drawn(bush, w, h, ax, ay), foot(w, h, ax, ay));
    ASSERT_EQ(resting.size(), 1u);
    const std::vector<double>& b = resting[0].radius;
    EXPECT_GT(b[0], 0.5 * *std::max_element(b.begin(), b.end()));
}

// On the default tileset the pine alone hides what stands below its widest
// disc (its skirt); its bushes and rocks show their lower halves and its
// trees their trunks.
TEST(SolidEstimate, onTheDefaultTilesetOnlyThePinesSkirtHidesItsStem) {
    const Tileset ts = test::default_tileset();
    const Params p;
    int overlays = 0;
    for (const Sprite& s : ts.sprites) {
        if (s.kind != SpriteKind::overlay) continue;
        ++overlays;
        FootprintReport r;
        tileset_footprint(ts, s, p, &r);
        const auto objects = sprite_objects(ts, s, p);
        ASSERT_EQ(objects.size(), 1u) << s.name;
        EXPECT_EQ(hidden_below_widest(r.estimate, objects[0]), s.name == "pine") << s.name;
    }
    EXPECT_EQ(overlays, 9);
}

// A user's correction (the tileset inspector's): the axis stands on the
// pixel they chose and the solid is as tall as they said, lower or higher
// than the estimate's own; an object with no footprint gets one where they
// put it.
TEST(SolidEstimate, aCorrectionSetsTheFootAndTheHeight) {
    const int w = 200, h = 170, ax = 100, ay = 150;
    const Mask object = drawn({trunk, canopy}, w, h, ax, ay);
    FootprintSpec fix;
    fix.object_foot = std::pair{ax - 3, ay - 2};
    fix.object_height = 40;
    auto objects = estimate_objects(object, foot(w, h, ax, ay), &fix);
    ASSERT_EQ(objects.size(), 1u);
    EXPECT_EQ(objects[0].center_x, ax - 3 + 0.5);
    EXPECT_EQ(objects[0].center_y, ay - 2 + 0.5);
    EXPECT_EQ(objects[0].height(), 40);
    fix.object_height = 90;  // above what the estimate reaches (about 69): its top disc held up
    objects = estimate_objects(object, foot(w, h, ax, ay), &fix);
    ASSERT_EQ(objects.size(), 1u);
    EXPECT_EQ(objects[0].height(), 90);
    EXPECT_GT(objects[0].radius.back(), 0);
    fix.object_height = 0;  // the foot alone: the estimate's height from there
    objects = estimate_objects(object, Mask(Rect{0, 0, w, h}), &fix);
    ASSERT_EQ(objects.size(), 1u);
    EXPECT_NEAR(objects[0].height(), 45 + 24, 12);
    EXPECT_EQ(objects[0].rect, (Rect{ax - 3, ay - 2, 1, 1}));
}

// A cylinder standing on its whole base (a building) is itself: its flat
// top is one disc's ellipse. On a footprint (a trunk, a bush) it is the
// largest solid of revolution its outline allows: the cylinder, and above
// its top the discs that fit inside the top's ellipse, up to the outline's
// top row (20 / sqrt(2) px higher), which the camera cannot tell from a
// dome. And an empty footprint or sprite gives no object.
TEST(SolidEstimate, aCylinderIsItselfAndEmptyInputsGiveNoObject) {
    const int w = 120, h = 120, ax = 60, ay = 100;
    const Solid post{SolidKind::cylinder, {0, 0, 0}, {20, 20, 50}};
    const Mask object = drawn({post}, w, h, ax, ay);
    const auto objects = estimate_objects(object, foot(w, h, ax, ay), nullptr, nullptr, true);
    ASSERT_EQ(objects.size(), 1u);
    EXPECT_NEAR(objects[0].height(), 50, 3);
    double lo = 0, hi = 0;
    ASSERT_TRUE(span_in_depth(objects[0], 15, lo, hi));
    EXPECT_EQ(lo, 0);
    EXPECT_NEAR(hi, 50, 3);
    EXPECT_GT(volume_overlap(objects, ax, ay, {post}), 0.85);
    const auto on_footprint = estimate_objects(object, foot(w, h, ax, ay));
    ASSERT_EQ(on_footprint.size(), 1u);
    EXPECT_NEAR(on_footprint[0].height(), 50 + 20 / std::sqrt(2.0), 3);
    const std::vector<double>& r = on_footprint[0].radius;
    for (std::size_t z = 0; z + 3 < 50; ++z) EXPECT_NEAR(r[z], 20, 1) << "the cylinder's disc at " << z;
    for (std::size_t z = 53; z < r.size(); ++z) EXPECT_LT(r[z], 20 - 1) << "the cap's disc at " << z;
    EXPECT_GT(volume_overlap(on_footprint, ax, ay, {post}), 0.8);
    EXPECT_TRUE(estimate_objects(object, Mask(Rect{0, 0, w, h})).empty());
    EXPECT_TRUE(estimate_objects(Mask(Rect{0, 0, w, h}), foot(w, h, ax, ay)).empty());
}

// The default tileset, whose sprites were drawn from their manifest shapes:
// every overlay gets an object, and the trees' estimates share most of their
// shapes' volume. (Walls and fences are long boxes, not solids of revolution;
// docs/beyond.md has every sprite's figure.)
TEST(SolidEstimate, theDefaultTilesetsTreesShareMostOfTheirShapesVolume) {
    const Tileset ts = test::default_tileset();
    const Params p;
    int trees = 0;
    for (const Sprite& s : ts.sprites) {
        if (s.kind != SpriteKind::overlay) continue;
        const auto objects = sprite_objects(ts, s, p);
        ASSERT_EQ(objects.size(), 1u) << s.name;
        EXPECT_GE(objects[0].height(), 4) << s.name;
        ASSERT_FALSE(s.shape.empty()) << s.name;
        if (std::find(s.tags.begin(), s.tags.end(), "tree") == s.tags.end()) continue;
        ++trees;
        EXPECT_GT(volume_overlap(objects, s.anchor_x, s.anchor_y, s.shape), 0.6) << s.name;
    }
    EXPECT_EQ(trees, 3);
}

// The estimate's silhouette covers most of the sprite's opaque pixels. Each
// disc is the largest that fits, and each cross-section reaches across the
// view no farther than the sprite does on the row where its centre shows:
// there every pixel it draws is opaque. (Below that row a widened
// cross-section may draw past the outline, where the sprite narrows to
// its front.)
TEST(SolidEstimate, theSolidsSilhouetteCoversTheSpriteAndEachCrossSectionFitsItsRow) {
    const int w = 200, h = 170, ax = 100, ay = 150;
    const Mask object = drawn({trunk, canopy}, w, h, ax, ay);
    const auto objects = estimate_objects(object, foot(w, h, ax, ay));
    ASSERT_EQ(objects.size(), 1u);
    const EstimatedObject& o = objects[0];
    const Mask drawn_solid = solid_silhouette(objects, w, h);
    long inside = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) inside += drawn_solid.get(x, y) && object.get(x, y);
    EXPECT_GT(double(inside), 0.85 * double(object.count()));
    int widened = 0;
    for (std::size_t z = 0; z < o.radius.size(); ++z) {
        EXPECT_GE(o.across_at(z), o.radius[z]) << z;
        if (o.radius[z] <= 0) continue;
        widened += o.across_at(z) > o.radius[z] + 1;
        // The centre row: the pixels whose centres the cross-section's ellipse holds there.
        const int y = int(std::floor(o.center_y - (double(z) + 0.5)));
        const double hw = o.across_at(z) * std::sqrt(2.0);
        for (int x = int(std::ceil(o.center_x - hw - 0.5)); x <= int(std::floor(o.center_x + hw - 0.5)); ++x)
            EXPECT_TRUE(object.get(x, y)) << "cross-section " << z << " draws " << x << "," << y << " outside the sprite";
    }
    EXPECT_GT(widened, 0) << "the canopy's underside reaches wider across than its discs";
}

// The models (docs/beyond.md): on the town tileset, drawn from true shapes
// in another look, the walls, the house and the hedge fit prisms, which
// share far more of their true volume than the solids of revolution a user
// could force; the trees and the tower stay solids of revolution.
TEST(SolidModels, wallsAndHousesArePrismsAndShareMoreOfTheirTrueVolume) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    const Tileset def = test::default_tileset();
    const Params p;
    auto sprite = [&](const std::string& name) -> const Sprite& {
        for (const Sprite& s : town.sprites)
            if (s.name == name) return s;
        throw std::runtime_error("no sprite " + name);
    };
    for (const char* name : {"long_wall", "house", "hedge"}) {
        const Sprite& s = sprite(name);
        const auto objects = sprite_objects(town, s, p);
        ASSERT_EQ(objects.size(), 1u) << name;
        EXPECT_EQ(objects[0].model, ObjectModel::prism) << name;
        // The hedge's top is flat; the house's stepped roof and the wall's
        // crenellations are not, but rise by a few pixels a column: no steps.
        EXPECT_EQ(objects[0].flat_top, std::string(name) == "hedge") << name;
        EXPECT_TRUE(objects[0].steps.empty()) << name;
        const double overlap = volume_overlap(objects, s.anchor_x, s.anchor_y, s.shape);
        Sprite forced = s;
        forced.footprint.object_model = ObjectModel::revolution;
        const auto revolution = sprite_objects(town, forced, p);
        ASSERT_EQ(revolution.size(), 1u) << name;
        EXPECT_EQ(revolution[0].model, ObjectModel::revolution) << name;
        const double forced_overlap = volume_overlap(revolution, s.anchor_x, s.anchor_y, s.shape);
        std::printf("%s: a prism shares %.3f of the true volume, a solid of revolution %.3f\n", name, overlap, forced_overlap);
        EXPECT_GT(overlap, 0.8) << name;
        EXPECT_GT(overlap, 1.6 * forced_overlap) << name;
    }
    // The fences' rails hide the ground between their posts, and the town's
    // boxes stand on several V's, so too few of their columns stand on one V;
    // low and fitting far better than the other models, they are prisms by
    // the rule, closer to their true volume than a solid of revolution.
    for (const auto& [set, name] : {std::pair{&town, "fence"}, std::pair{&town, "town"}, std::pair{&def, "fence"}}) {
        const Sprite* s = nullptr;
        for (const Sprite& c : set->sprites)
            if (c.name == name) s = &c;
        ASSERT_NE(s, nullptr) << name;
        const auto kept = sprite_objects(*set, *s, p);
        ASSERT_EQ(kept.size(), 1u) << name;
        EXPECT_EQ(kept[0].model, ObjectModel::prism) << name;
        // The town's houses of several heights step; a fence's posts do not.
        EXPECT_EQ(!kept[0].steps.empty(), std::string(name) == "town") << name;
        Sprite forced = *s;
        forced.footprint.object_model = ObjectModel::revolution;
        const auto revolution = sprite_objects(*set, forced, p);
        const double as_prism = volume_overlap(kept, s->anchor_x, s->anchor_y, s->shape),
                     as_revolution = volume_overlap(revolution, s->anchor_x, s->anchor_y, s->shape);
        std::printf("%s: a prism shares %.3f of the true volume, a solid of revolution %.3f\n", name, as_prism,
                    as_revolution);
        EXPECT_GT(as_prism, 1.5 * as_revolution) << name;
    }
    for (const char* name : {"tall_tree", "tower", "round_hut"})
        for (const EstimatedObject& o : sprite_objects(town, sprite(name), p))
            EXPECT_EQ(o.model, ObjectModel::revolution) << name;
    for (const Sprite& s : def.sprites) {
        if (std::find(s.tags.begin(), s.tags.end(), "tree") == s.tags.end()) continue;
        for (const EstimatedObject& o : sprite_objects(def, s, p)) EXPECT_EQ(o.model, ObjectModel::revolution) << s.name;
    }
}

// A prism is carved by its hull (docs/beyond.md, *Prisms*): nothing stands
// on a view line the sprite leaves empty. The town's fence: its prism holds
// its posts from the ground but leaves the gap under its lower rail (true:
// 5 px) open between them, where the uncarved prism filled it, so a low
// light reaches the ground behind it; and it shares more of the fence's
// true volume than the uncarved prism.
TEST(SolidModels, aFencesPrismLeavesTheGapUnderItsRailsOpen) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    const Sprite* fence = find_sprite(town, "fence");
    ASSERT_NE(fence, nullptr);
    const auto objects = sprite_objects(town, *fence, Params{});
    ASSERT_EQ(objects.size(), 1u);
    const EstimatedObject& o = objects[0];
    ASSERT_EQ(o.model, ObjectModel::prism);
    ASSERT_FALSE(o.hull.bits.empty());
    EstimatedObject uncarved = o;
    uncarved.hull = Mask{};
    // The span over the fence's line at true ground point (X, 0), relative to the anchor.
    auto span = [&](const EstimatedObject& e, double X, double& lo, double& hi) {
        const Vec3 q = ground_frame(fence->anchor_x + X - e.center_x, fence->anchor_y + X / 2 - e.center_y, 0);
        return e.span_at(q.x, q.y, lo, hi);
    };
    double lo = 0, hi = 0;
    for (double X : {-13.0, 13.0}) {  // between the posts (true: at X = -26, 0 and 26)
        ASSERT_TRUE(span(uncarved, X, lo, hi)) << X;
        EXPECT_EQ(lo, 0) << X;
        ASSERT_TRUE(span(o, X, lo, hi)) << X;
        EXPECT_GE(lo, 3) << "the gap under the lower rail at X = " << X;
        EXPECT_LE(lo, 6) << "the lower rail itself at X = " << X;
        EXPECT_GE(hi, 16) << "the upper rail at X = " << X;
    }
    ASSERT_TRUE(span(o, 0, lo, hi));
    EXPECT_EQ(lo, 0) << "the middle post stands on the ground";
    const double carved = volume_overlap({o}, fence->anchor_x, fence->anchor_y, fence->shape),
                 filled = volume_overlap({uncarved}, fence->anchor_x, fence->anchor_y, fence->shape);
    std::printf("fence: carved prism shares %.3f of the true volume, uncarved %.3f\n", carved, filled);
    EXPECT_GT(carved, filled) << "carving takes off more empty space than fence";
}

// A box drawn from its true shape: the prism's rectangle and height are the
// box's within a pixel or two, and its solid holds the box's inside and not
// its outside.
TEST(SolidModels, aBoxFitsThePrismOfItsRectangleAndHeight) {
    const int w = 160, h = 140, ax = 80, ay = 110;
    const Solid box{SolidKind::box, {-30, -12, 0}, {30, 12, 36}};
    const Mask object = drawn({box}, w, h, ax, ay);
    const std::optional<EstimatedObject> o = fit_prism(object);
    ASSERT_TRUE(o.has_value());
    EXPECT_EQ(o->model, ObjectModel::prism);
    EXPECT_NEAR(o->half_x, 30, 1.5);
    EXPECT_NEAR(o->half_y, 12, 1.5);
    EXPECT_NEAR(o->height(), 36, 2);
    // Its foot: the box's centre on the ground, on screen.
    EXPECT_NEAR(o->center_x, ax + 0.0, 1.5);
    EXPECT_NEAR(o->center_y, ay + 0.0, 1.5);
    EXPECT_TRUE(o->contains({0, 0, 20}));
    EXPECT_TRUE(o->contains({27, 10, 33}));
    EXPECT_FALSE(o->contains({0, 16, 10}));
    EXPECT_FALSE(o->contains({0, 0, 40}));
    EXPECT_GT(volume_overlap({*o}, ax, ay, {box}), 0.85);
    EXPECT_GT(silhouette_fit({*o}, object), 0.95);
    // A cylinder's round base is no V: its prism fits worse than its solid of revolution.
    const Mask round = drawn({Solid{SolidKind::cylinder, {0, 0, 0}, {20, 20, 50}}}, w, h, ax, ay);
    const auto estimated = estimate_objects(round, foot(w, h, ax, ay));
    ASSERT_EQ(estimated.size(), 1u);
    EXPECT_EQ(estimated[0].model, ObjectModel::revolution);
}

// A house drawn from its true shapes (walls under a roof stepped up to a
// ridge along one ground axis), in both orientations: the prism takes a
// pitched roof along that axis, its ridge and eaves near the true ones, and
// holds more of the house's volume, and fits its silhouette better, than
// the flat top fit_prism gives it.
TEST(SolidModels, aHousesRoofIsPitchedAlongItsRidge) {
    const int w = 160, h = 150, ax = 80, ay = 115;
    for (int axis = 0; axis < 2; ++axis) {
        // Ground extents (along the ridge, across it) as box corners for this axis.
        auto box = [&](double along, double across, double z0, double z1) {
            return axis == 0 ? Solid{SolidKind::box, {-along, -across, z0}, {along, across, z1}}
                             : Solid{SolidKind::box, {-across, -along, z0}, {across, along, z1}};
        };
        const std::vector<Solid> house = {box(24, 16, 0, 20), box(24, 12, 20, 26), box(24, 7, 26, 32), box(24, 2, 32, 36)};
        const Mask object = drawn(house, w, h, ax, ay);
        const std::optional<EstimatedObject> flat = fit_prism(object);
        ASSERT_TRUE(flat.has_value()) << axis;
        ASSERT_FALSE(flat->flat_top) << axis;
        EstimatedObject o = *flat;
        top_prism(object, o);
        EXPECT_EQ(o.ridge_axis, axis);
        EXPECT_TRUE(o.steps.empty()) << axis;
        EXPECT_NEAR(o.height(), 36, 4) << axis;
        EXPECT_GE(o.eaves, 16) << axis;
        EXPECT_LE(o.eaves, 28) << axis;
        // Under the ridge the roof stands high; at the eaves it does not.
        const Vec3 ridge = axis == 0 ? Vec3{10, 0, 32} : Vec3{0, 10, 32}, eave = axis == 0 ? Vec3{10, 14, 32} : Vec3{14, 10, 32};
        EXPECT_TRUE(o.contains(ridge)) << axis;
        EXPECT_FALSE(o.contains(eave)) << axis;
        const double pitched = volume_overlap({o}, ax, ay, house), flat_overlap = volume_overlap({*flat}, ax, ay, house);
        std::printf("axis %d: pitched roof shares %.3f of the true volume, a flat top %.3f; silhouettes %.3f, %.3f\n", axis,
                    pitched, flat_overlap, silhouette_fit({o}, object), silhouette_fit({*flat}, object));
        EXPECT_GT(pitched, flat_overlap + 0.02) << axis;
        EXPECT_GT(silhouette_fit({o}, object), silhouette_fit({*flat}, object)) << axis;
    }
}

// The town's house (a stepped roof along ground x) gets its pitched roof
// through the rule; its long wall (crenellations) and its hedge do not.
TEST(SolidModels, theTownsHouseIsPitchedAndItsWallsAreNot) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    for (const char* name : {"house", "long_wall", "hedge", "fence"}) {
        const Sprite* s = find_sprite(town, name);
        ASSERT_NE(s, nullptr) << name;
        const auto objects = sprite_objects(town, *s, Params{});
        ASSERT_EQ(objects.size(), 1u) << name;
        EXPECT_EQ(objects[0].ridge_axis, std::string(name) == "house" ? 0 : -1) << name;
    }
}

// A heap (the town's boulder pile: three boulders with a fourth on top) is
// its mound's dome and its solid of revolution together: the dome's
// outline hides the summit standing over the pile's front, and both share
// more of the pile's true volume than the dome alone. The low rocks' right
// rock, whose solid of revolution shows past its dome, stays a dome alone.
TEST(SolidModels, aBoulderPileIsAHeapOfDomeAndSummit) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    const Sprite* pile = find_sprite(town, "boulder_pile");
    ASSERT_NE(pile, nullptr);
    const auto objects = sprite_objects(town, *pile, Params{});
    ASSERT_EQ(objects.size(), 2u);
    EXPECT_EQ(objects[0].model, ObjectModel::mound);
    EXPECT_EQ(objects[1].model, ObjectModel::revolution);
    EXPECT_GT(objects[1].height(), objects[0].height() + 8) << "the summit stands above the dome";
    EXPECT_GT(objects[1].center_y, objects[0].center_y) << "the summit stands over the pile's front";
    Sprite dome_only = *pile;
    dome_only.footprint.object_model = ObjectModel::mound;  // the user's mound: the dome alone
    const auto dome = sprite_objects(town, dome_only, Params{});
    ASSERT_EQ(dome.size(), 1u);
    const double heap = volume_overlap(objects, pile->anchor_x, pile->anchor_y, pile->shape),
                 alone = volume_overlap(dome, pile->anchor_x, pile->anchor_y, pile->shape);
    std::printf("boulder pile: the heap shares %.3f of the true volume, the dome alone %.3f\n", heap, alone);
    EXPECT_GT(heap, alone + 0.08);
    const Sprite* rocks = find_sprite(town, "low_rocks");
    ASSERT_NE(rocks, nullptr);
    int mounds = 0;
    for (const EstimatedObject& o : sprite_objects(town, *rocks, Params{})) mounds += o.model == ObjectModel::mound;
    EXPECT_EQ(mounds, 1);
    EXPECT_EQ(sprite_objects(town, *rocks, Params{}).size(), 2u);
}

// Boxes side by side (a town's houses): the prism steps with them, each
// column as tall as the box that tops it, and holds more of their volume
// than one height does. One box does not step.
TEST(SolidModels, boxesSideBySideGiveAStepPerColumn) {
    const int w = 200, h = 140, ax = 100, ay = 110;
    const std::vector<Solid> boxes{Solid{SolidKind::box, {-36, -12, 0}, {0, 12, 40}},
                                   Solid{SolidKind::box, {0, -12, 0}, {36, 12, 12}}};
    const Mask object = drawn(boxes, w, h, ax, ay);
    const std::optional<EstimatedObject> flat = fit_prism(object);
    ASSERT_TRUE(flat.has_value());
    EXPECT_FALSE(flat->flat_top);
    EstimatedObject stepped = *flat;
    step_prism(object, stepped);
    ASSERT_FALSE(stepped.steps.empty()) << "a tall box beside a low one steps";
    EXPECT_NEAR(stepped.height(), 40, 2);
    // Left of both (the tall box's columns alone) and right (the low one's).
    EXPECT_NEAR(stepped.step_at(-40), 40, 2);
    EXPECT_NEAR(stepped.step_at(40), 12, 2);
    EXPECT_TRUE(stepped.contains({-20, 0, 35}));
    EXPECT_FALSE(stepped.contains({30, 0, 20})) << "above the low box is empty";
    EXPECT_TRUE(stepped.contains({30, 0, 8}));
    const double overlap = volume_overlap({stepped}, ax, ay, boxes), flat_overlap = volume_overlap({*flat}, ax, ay, boxes);
    std::printf("stepped prism: %.3f of the boxes' volume, one height %.3f\n", overlap, flat_overlap);
    EXPECT_GT(overlap, flat_overlap + 0.1);
    EXPECT_GT(silhouette_fit({stepped}, object), silhouette_fit({*flat}, object));
    // One box's rises are alike: no steps.
    const Mask one = drawn({Solid{SolidKind::box, {-30, -12, 0}, {30, 12, 36}}}, w, h, ax, ay);
    std::optional<EstimatedObject> box = fit_prism(one);
    ASSERT_TRUE(box.has_value());
    step_prism(one, *box);
    EXPECT_TRUE(box->steps.empty());
}

// A low box set back beside a tall one (a town's): the rectangle both
// stand in holds ground in front of the low box, which the sprite shows
// bare. The stepped prism's ground ends at each column's lowest pixel, so
// it holds none of that ground, and more of the boxes' volume than the
// rectangle does.
TEST(SolidModels, aBoxSetBackLeavesTheGroundInFrontOfItEmpty) {
    const int w = 200, h = 140, ax = 100, ay = 110;
    const std::vector<Solid> boxes{Solid{SolidKind::box, {-36, -12, 0}, {0, 12, 40}},
                                   Solid{SolidKind::box, {0, -36, 0}, {36, -12, 12}}};
    const Mask object = drawn(boxes, w, h, ax, ay);
    const std::optional<EstimatedObject> flat = fit_prism(object);
    ASSERT_TRUE(flat.has_value());
    EstimatedObject stepped = *flat;
    step_prism(object, stepped);
    ASSERT_FALSE(stepped.steps.empty());
    ASSERT_FALSE(stepped.fronts.empty());
    // Ground frame relative to the prism's foot, from the anchor's.
    const Vec3 foot = ground_frame(stepped.center_x - ax, stepped.center_y - ay, 0);
    const auto at = [&](double x, double y, double z) { return stepped.contains({x - foot.x, y - foot.y, z}); };
    EXPECT_TRUE(at(18, -24, 6)) << "inside the low box";
    EXPECT_TRUE(at(-18, 0, 30)) << "inside the tall box";
    EXPECT_FALSE(at(18, 0, 0.5)) << "the bare ground in front of the low box";
    EXPECT_FALSE(at(30, 6, 0.5));
    EstimatedObject rectangle = stepped;
    rectangle.fronts.clear();
    EXPECT_TRUE(rectangle.contains({18 - foot.x, 0 - foot.y, 0.5})) << "the rectangle alone fills it";
    const double overlap = volume_overlap({stepped}, ax, ay, boxes), filled = volume_overlap({rectangle}, ax, ay, boxes);
    std::printf("fronts: %.3f of the boxes' volume, the rectangle's ground %.3f\n", overlap, filled);
    EXPECT_GT(overlap, filled + 0.05);
    EXPECT_GE(silhouette_fit({stepped}, object), silhouette_fit({rectangle}, object));
}

// A half ellipsoid on the ground: the mound's base and height are its own,
// where the largest solid of revolution stands far taller. (Its outline is
// filled about as well by that solid, which keeps such ties: a user picks
// the mound in the inspector.)
TEST(SolidModels, aLowDomeFitsAMoundOfItsHeight) {
    const int w = 160, h = 120, ax = 80, ay = 90;
    const Solid dome{SolidKind::ellipsoid, {0, 0, 0}, {26, 26, 12}};
    Mask object(Rect{0, 0, w, h});  // its half above the ground: the ground hides the rest
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (surface_height({dome}, x + 0.5 - ax, y + 0.5 - ay) >= 0) object.set(x, y);
    const std::optional<EstimatedObject> o = fit_mound(object);
    ASSERT_TRUE(o.has_value());
    EXPECT_EQ(o->model, ObjectModel::mound);
    EXPECT_NEAR(o->height(), 12, 3);
    EXPECT_NEAR(o->center_x, ax, 1.5);
    EXPECT_NEAR(o->center_y, ay, 2);
    FootprintSpec c;
    c.object_model = ObjectModel::mound;
    const auto chosen = estimate_objects(object, foot(w, h, ax, ay), &c);
    ASSERT_EQ(chosen.size(), 1u);
    EXPECT_EQ(chosen[0].model, ObjectModel::mound);
    c.object_model = ObjectModel::revolution;
    const auto round = estimate_objects(object, foot(w, h, ax, ay), &c);
    ASSERT_EQ(round.size(), 1u);
    const double mound_overlap = volume_overlap(chosen, ax, ay, {dome}), round_overlap = volume_overlap(round, ax, ay, {dome});
    std::printf("a dome: the mound shares %.3f of its volume, the solid of revolution %.3f (%.0f px high)\n",
                mound_overlap, round_overlap, round[0].height());
    EXPECT_GT(mound_overlap, 0.4);  // of the whole ellipsoid, half of which lies below the ground
    EXPECT_GT(mound_overlap, round_overlap);
    EXPECT_GT(round[0].height(), 1.5 * o->height());
    // A crown above the ground (a bush's equator high over its lowest rows) is no mound.
    const Mask floating = drawn({Solid{SolidKind::ellipsoid, {0, 0, 16}, {20, 20, 14}}}, w, h, ax, ay);
    EXPECT_FALSE(fit_mound(floating).has_value());
}

// The user's model (the manifest's object.model) is the one used, with
// their foot; a model that finds no fit falls back to the estimate's own.
TEST(SolidModels, theUsersModelAndFootAreKept) {
    const int w = 160, h = 140, ax = 80, ay = 110;
    const Mask object = drawn({Solid{SolidKind::box, {-30, -12, 0}, {30, 12, 36}}}, w, h, ax, ay);
    FootprintSpec c;
    c.object_model = ObjectModel::revolution;
    auto objects = estimate_objects(object, foot(w, h, ax, ay), &c);
    ASSERT_EQ(objects.size(), 1u);
    EXPECT_EQ(objects[0].model, ObjectModel::revolution);
    c.object_model = ObjectModel::prism;
    c.object_foot = std::pair{ax + 4, ay - 2};
    c.object_height = 20;
    objects = estimate_objects(object, foot(w, h, ax, ay), &c);
    ASSERT_EQ(objects.size(), 1u);
    EXPECT_EQ(objects[0].model, ObjectModel::prism);
    EXPECT_DOUBLE_EQ(objects[0].center_x, ax + 4.5);
    EXPECT_DOUBLE_EQ(objects[0].center_y, ay - 1.5);
    EXPECT_EQ(objects[0].height(), 20);
    // A trunk's round base holds no V: a prism asked of it is its solid of revolution.
    const Mask round = drawn({Solid{SolidKind::cylinder, {0, 0, 0}, {3, 3, 50}}}, w, h, ax, ay);
    FootprintSpec p;
    p.object_model = ObjectModel::prism;
    const auto kept = estimate_objects(round, foot(w, h, ax, ay), &p);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_TRUE(kept[0].model == ObjectModel::revolution || kept[0].model == ObjectModel::prism);
}

// Several things on one tile (docs/beyond.md, "Several objects in a
// sprite"): on the town tileset the low rocks, apart on the ground, are an
// object each, and the grove's trunks under its autumn crowns (as red as
// bark) a tree each; both share more of their true volume than one solid
// for the whole sprite does.
TEST(SolidModels, rocksApartAndTreesOfAGroveAreObjectsOfTheirOwn) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    for (const std::string name : {"low_rocks", "grove"}) {
        const Sprite* s = nullptr;
        for (const Sprite& c : town.sprites)
            if (c.name == name) s = &c;
        ASSERT_NE(s, nullptr) << name;
        FootprintReport r;
        const Mask fp = tileset_footprint(town, *s, Params{}, &r);
        const std::vector<EstimatedObject> objects = estimate_objects(r, fp, &s->footprint);
        const std::vector<EstimatedObject> whole = estimate_objects(r.estimate, fp);
        EXPECT_EQ(whole.size(), 1u) << name;
        EXPECT_GE(objects.size(), name == "grove" ? 3u : 2u) << name;
        const double split = volume_overlap(objects, s->anchor_x, s->anchor_y, s->shape),
                     one = volume_overlap(whole, s->anchor_x, s->anchor_y, s->shape);
        EXPECT_GT(split, one + 0.03) << name << ": " << split << " against " << one;
        EXPECT_GT(split, 0.25) << name;
    }
}

// The town's grove: six trees whose crowns merge, three of their trunks
// hidden behind the trees in front. Its crowns, told apart by colour, give
// a tree for each crown no trunk takes, standing where its crown's top says
// under the middle of its top (two crowns of one colour are one tree): five
// objects, each standing within 4 px of a true trunk's foot on screen,
// sharing far more of the true volume than the three trees the trunks
// alone give.
TEST(SolidModels, aGrovesHiddenTrunksStandUnderTheirCrowns) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    const Sprite& s = town.sprites[test::sprite_index(town, "grove")];
    FootprintReport r;
    const Mask fp = tileset_footprint(town, s, Params{}, &r);
    ASSERT_EQ(r.trunks.size(), 3u);
    const std::vector<EstimatedObject> objects = estimate_objects(r, fp, &s.footprint);
    const std::vector<EstimatedObject> by_trunks = estimate_objects(r.estimate, fp, nullptr, &r.trunks);
    ASSERT_EQ(by_trunks.size(), 3u);
    EXPECT_EQ(objects.size(), 5u);
    std::vector<std::pair<double, double>> feet;  // the true trunks' feet on screen
    for (const Solid& solid : s.shape)
        if (solid.kind == SolidKind::cylinder)
            feet.push_back({s.anchor_x + solid.a.x - solid.a.y, s.anchor_y + (solid.a.x + solid.a.y) / 2});
    ASSERT_EQ(feet.size(), 6u);
    for (const EstimatedObject& o : objects) {
        double nearest = 1e9;
        for (const auto& [x, y] : feet) nearest = std::min(nearest, std::hypot(o.center_x - x, o.center_y - y));
        EXPECT_LE(nearest, 4) << "the tree standing at " << o.center_x << ", " << o.center_y;
    }
    const double crowns = volume_overlap(objects, s.anchor_x, s.anchor_y, s.shape),
                 trunks = volume_overlap(by_trunks, s.anchor_x, s.anchor_y, s.shape);
    std::printf("grove: %zu trees share %.3f of the true volume, the trunks' %zu %.3f\n", objects.size(), crowns,
                by_trunks.size(), trunks);
    EXPECT_GT(crowns, trunks + 0.1);
}

// The town grove's trees are alike (crowns 12 px in radius): each estimated
// tree's widest disc within a fifth of its true tree's, the red crown left
// of the two orange ones among them, whose right half those hide though
// their foot (one tree for two crowns of one colour) stands behind its own;
// and the trees share more of the true volume than three fifths.
TEST(SolidModels, aGroveCrownKeepsItsWidthBesideACrownOfAnotherColour) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    const Sprite& s = town.sprites[test::sprite_index(town, "grove")];
    FootprintReport r;
    const Mask fp = tileset_footprint(town, s, Params{}, &r);
    const std::vector<EstimatedObject> objects = estimate_objects(r, fp, &s.footprint);
    ASSERT_EQ(objects.size(), 5u);
    for (const EstimatedObject& o : objects) {
        double nearest = 1e9, crown = 0;
        for (const Solid& trunk : s.shape) {
            if (trunk.kind != SolidKind::cylinder) continue;
            const double d = std::hypot(o.center_x - (s.anchor_x + trunk.a.x - trunk.a.y),
                                        o.center_y - (s.anchor_y + (trunk.a.x + trunk.a.y) / 2));
            if (d >= nearest) continue;
            nearest = d;
            for (const Solid& e : s.shape)
                if (e.kind == SolidKind::ellipsoid && e.a.x == trunk.a.x && e.a.y == trunk.a.y) crown = e.b.x;
        }
        ASSERT_GT(crown, 0);
        const double widest = *std::max_element(o.radius.begin(), o.radius.end());
        EXPECT_GE(widest, 0.8 * crown) << "the tree standing at " << o.center_x << ", " << o.center_y;
        EXPECT_LE(widest, 1.2 * crown) << "the tree standing at " << o.center_x << ", " << o.center_y;
    }
    EXPECT_GT(volume_overlap(objects, s.anchor_x, s.anchor_y, s.shape), 0.6);
}

// Two trees whose crowns overlap on screen, and no crowns the colours part
// (foliage textured pixel by pixel): each tree takes the pixels of the
// columns nearest its trunk, and the one behind may reach into the front
// one's, which hide the rest of its crown: its crown stays round instead
// of ending in a straight vertical edge halfway between the trunks.
TEST(SolidModels, aGroveTreeBehindReachesBehindTheTreeInFront) {
    const int w = 160, h = 140, ax = 80, ay = 110;
    // Screen x = X - Y: the back tree 12 px left of the anchor, the front one 12 px right, 10 rows lower.
    const Vec3 back{4, 16, 0}, front{20, 8, 0};
    std::vector<Solid> shape;
    for (const Vec3 at : {back, front}) {
        shape.push_back(Solid{SolidKind::cylinder, at, {2.5, 2.5, 30}});
        shape.push_back(Solid{SolidKind::ellipsoid, at + Vec3{0, 0, 38}, {12, 12, 11}});
    }
    const Mask object = drawn(shape, w, h, ax, ay);
    const std::vector<TrunkFoot> feet = {{ax + back.x - back.y - 0.5, int(ay + (back.x + back.y) / 2) - 1},
                                         {ax + front.x - front.y - 0.5, int(ay + (front.x + front.y) / 2) - 1}};
    const auto objects = estimate_objects(object, foot(w, h, ax, ay), nullptr, &feet);
    ASSERT_EQ(objects.size(), 2u);
    const EstimatedObject& behind = objects[0].center_y < objects[1].center_y ? objects[0] : objects[1];
    double widest = 0;
    for (std::size_t z = 0; z < behind.radius.size(); ++z) widest = std::max(widest, behind.across_at(z));
    // Halfway to the front trunk lies 12 screen px, 12 / sqrt(2) ground px, from the axis.
    std::printf("the tree behind: its widest cross-section %.1f px across (its crown 12, halfway %.1f)\n", widest,
                12 / std::sqrt(2.0));
    EXPECT_GT(widest, 10);
    EXPECT_GT(volume_overlap(objects, ax, ay, shape), 0.4);
}

// A mountain wider than a tile (the town tileset's: a cone with two side
// lobes): a mound with a peak's profile (a cone: its cross-section halfway
// up about half its base's), standing on its base's middle, sharing far
// more of its true volume than the solid of revolution standing at its
// base's front (its footprint) that a user could force.
TEST(SolidModels, aMountainIsAPeak) {
    const Tileset town = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json");
    const Sprite* s = find_sprite(town, "mountain");
    ASSERT_NE(s, nullptr);
    const auto objects = sprite_objects(town, *s, Params{});
    ASSERT_EQ(objects.size(), 1u);
    const EstimatedObject& o = objects[0];
    EXPECT_EQ(o.model, ObjectModel::mound);
    ASSERT_GE(o.radius.size(), 2u);
    EXPECT_NEAR(o.radius[o.radius.size() / 2] / o.radius[0], 0.5, 0.05);
    EXPECT_NEAR(o.center_y, s->anchor_y, 4);
    Sprite forced = *s;
    forced.footprint.object_model = ObjectModel::revolution;
    const double as_mound = volume_overlap(objects, s->anchor_x, s->anchor_y, s->shape),
                 as_revolution = volume_overlap(sprite_objects(town, forced, Params{}), s->anchor_x, s->anchor_y, s->shape);
    std::printf("mountain: a peak shares %.3f of the true volume, a solid of revolution %.3f\n", as_mound, as_revolution);
    EXPECT_GT(as_mound, 0.6);
    EXPECT_GT(as_mound, 3 * as_revolution);
}
