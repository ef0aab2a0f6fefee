// Accuracy against time: the metrics and the sweep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "isolux/accuracy.hpp"
#include "isolux/error.hpp"
#include "isolux/frame.hpp"
#include "isolux/truth.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {
const World& small_world() {
    static World w = [] {
        Scene s;
        s.width = s.height = 6;
        return make_world(test::default_tileset(), s);
    }();
    return w;
}
Scene lit() {
    Scene s;
    s.width = s.height = 6;
    s.params.area_a = s.params.area_b = 60;
    s.params.falloff_scale = 6;
    s.lights = {Light{380, 200}, Light{300, 260}};
    s.camera = {100, 50, 400, 260};
    return s;
}
SweepOptions quick() {
    SweepOptions o;
    o.frames = 4;
    o.repeats = 1;
    return o;
}
}  // namespace

TEST(Accuracy, metricsCountWhatDiffers) {
    LightTexture a(Rect{0, 0, 4, 1}), b(Rect{0, 0, 4, 1});
    a.texels = {0, 0, 0, 10, 10, 10, 200, 200, 200, 5, 5, 5};
    b.texels = {0, 0, 0, 0, 0, 0, 190, 200, 200, 5, 5, 5};
    ErrorMetrics m = compare_light(a, b);
    EXPECT_DOUBLE_EQ(m.lit_mismatch, 0.25);  // texel 1 is lit in a only
    EXPECT_DOUBLE_EQ(m.differing, 0.5);      // texels 1 and 2
    EXPECT_EQ(m.max_abs, 10);
    EXPECT_NEAR(m.rmse, std::sqrt((3 * 100.0 + 100.0) / 12.0), 1e-3);
    EXPECT_NEAR(m.psnr, 20 * std::log10(255.0 / m.rmse), 1e-6);
    ErrorMetrics same = compare_light(a, a);
    EXPECT_EQ(same.rmse, 0);
    EXPECT_TRUE(std::isinf(same.psnr));
    EXPECT_THROW(compare_light(a, LightTexture(Rect{0, 0, 3, 1})), Error);
}

TEST(Accuracy, theReferenceSettingHasZeroError) {
    Scene s = lit();
    s.params = reference_params(s.params);
    auto points = run_sweep(small_world(), s, {{"rays", {"every_pixel"}}}, quick());
    ASSERT_EQ(points.size(), 1u);
    for (const ErrorMetrics* m : {&points[0].light, &points[0].final}) {
        EXPECT_EQ(m->lit_mismatch, 0);
        EXPECT_EQ(m->differing, 0);
        EXPECT_EQ(m->max_abs, 0);
        EXPECT_EQ(m->rmse, 0);
    }
}

TEST(Accuracy, skippingRaysAndStaleTexturesShowAsError) {
    auto points = run_sweep(small_world(), lit(),
                            {{"ray_skip", {"1", "16"}}, {"trace_every", {"1", "4"}}, {"blur_radius", {"0"}}}, quick());
    ASSERT_EQ(points.size(), 4u);  // first axis slowest: (1,1) (1,4) (16,1) (16,4)
    EXPECT_EQ(points[0].values, (std::vector<std::string>{"1", "1", "0"}));
    EXPECT_GT(points[2].light.lit_mismatch, points[0].light.lit_mismatch);  // skipped rays leave gaps
    EXPECT_GT(points[1].final.rmse, points[0].final.rmse);                  // the carried light goes stale
    bool any_pareto = false;
    for (const SweepPoint& p : points) {
        EXPECT_GE(p.lighting_ms, 0);
        EXPECT_GE(p.total_ms, p.lighting_ms);
        any_pareto = any_pareto || p.pareto;
    }
    EXPECT_TRUE(any_pareto);
    const std::string csv = sweep_csv({{"ray_skip", {}}, {"trace_every", {}}, {"blur_radius", {}}}, points);
    EXPECT_NE(csv.find("ray_skip,trace_every,blur_radius,ms_sprites"), std::string::npos);
    EXPECT_NE(csv.find("final_psnr,pareto"), std::string::npos);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
}

TEST(Accuracy, paretoKeepsOnlyPointsNoFasterPointBeats) {
    std::vector<SweepPoint> p(4);
    p[0].lighting_ms = 1, p[0].final.rmse = 5;
    p[1].lighting_ms = 2, p[1].final.rmse = 6;  // slower and worse: dominated
    p[2].lighting_ms = 3, p[2].final.rmse = 1;
    p[3].lighting_ms = 4, p[3].final.rmse = 1;  // slower, no better: dominated
    mark_pareto(p);
    EXPECT_TRUE(p[0].pareto);
    EXPECT_FALSE(p[1].pareto);
    EXPECT_TRUE(p[2].pareto);
    EXPECT_FALSE(p[3].pareto);
}

TEST(Accuracy, unknownParametersAndBadValuesAreErrors) {
    EXPECT_THROW(run_sweep(small_world(), lit(), {{"sparkle", {"1"}}}, quick()), Error);
    EXPECT_THROW(run_sweep(small_world(), lit(), {{"ray_skip", {"0"}}}, quick()), Error);
    EXPECT_THROW(run_sweep(small_world(), lit(), {{"ray_skip", {"x"}}}, quick()), Error);
}

TEST(Accuracy, aSweepHandsOverEachRowAsItIsMeasuredSoAStopKeepsThem) {
    SweepOptions o = quick();
    o.frames = 2;
    std::vector<std::size_t> sizes;
    std::string last_csv;
    const std::vector<SweepAxis> axes = {{"ray_skip", {"1", "2", "4"}}};
    o.rows_so_far = [&](const std::vector<SweepPoint>& so_far) {
        sizes.push_back(so_far.size());
        last_csv = sweep_csv(axes, so_far, false);
    };
    const auto points = run_sweep(small_world(), lit(), axes, o);
    EXPECT_EQ(sizes, (std::vector<std::size_t>{1, 2, 3}));
    // While under way the pareto column is empty (it is known at the end only).
    const std::size_t header_end = last_csv.find('\n');
    const std::string header = last_csv.substr(0, header_end);
    const std::string row = last_csv.substr(header_end + 1, last_csv.find('\n', header_end + 1) - header_end - 1);
    auto field = [](const std::string& line, std::size_t k) {
        std::size_t pos = 0;
        for (std::size_t i = 0; i < k; ++i) pos = line.find(',', pos) + 1;
        return line.substr(pos, line.find(',', pos) - pos);
    };
    std::size_t pareto = 0;
    while (field(header, pareto) != "pareto") ++pareto;
    EXPECT_EQ(field(row, pareto), "");
    const std::string final_csv = sweep_csv(axes, points);
    const std::string final_row = final_csv.substr(header_end + 1, final_csv.find('\n', header_end + 1) - header_end - 1);
    EXPECT_TRUE(field(final_row, pareto) == "0" || field(final_row, pareto) == "1") << final_row;
    EXPECT_EQ(std::count(last_csv.begin(), last_csv.end(), '\n'), 4);
}

// Sweeping occluders=footprints,shapes over a tileset with no shapes is
// refused, naming the sprite, before any combination runs.
TEST(Accuracy, aSweepOfShapesOverSpritesWithoutThemIsRefusedBeforeItsFirstCombination) {
    Scene s = lit();
    const World w = make_world(test::foreign_tileset(), s);
    s.camera = Camera{};  // the whole map in view
    int rows = 0;
    SweepOptions o = quick();
    o.rows_so_far = [&](const std::vector<SweepPoint>&) { ++rows; };
    const std::string m = test::error_of([&] { run_sweep(w, s, {{"occluders", {"footprints", "shapes"}}}, o); });
    EXPECT_NE(m.find("has no shape"), std::string::npos) << m;
    EXPECT_EQ(rows, 0) << "a combination ran before the refusal";
    // Without shapes asked for, the same sweep runs.
    EXPECT_EQ(run_sweep(w, s, {{"occluders", {"footprints", "solids"}}}, o).size(), 2u);
}

// A sprite without a shape that only a later frame needs, beyond the first
// frame's whole region: the sweep is refused before its first combination
// all the same, naming the sprite.
TEST(Accuracy, aSweepOfShapesIsRefusedForASpriteOnlyALaterFrameNeeds) {
    Scene s;
    s.width = s.height = 16;
    s.params.area_a = s.params.area_b = 40;
    s.camera = {200, 400, 160, 120};
    World w = make_world(test::default_tileset(), s);
    SweepOptions o = quick();
    o.frames = 12;
    o.step_x = 120, o.step_y = 0;
    auto needed_at = [&](int f) {
        const Camera c{s.camera.x + o.step_x * f, s.camera.y, s.camera.width, s.camera.height};
        return frame_region_needed(w, s, c, FrameOptions{}.margin);
    };
    const Rect first = obstacle_region_around(needed_at(0), w);
    std::vector<std::uint32_t> last, near_first;
    instances_in(w.placed, needed_at(o.frames - 1), true, last);
    instances_in(w.placed, first, true, near_first);
    std::uint32_t k = no_instance;
    for (std::uint32_t i : last)
        if (std::find(near_first.begin(), near_first.end(), i) == near_first.end()) k = i;
    ASSERT_NE(k, no_instance) << "no overlay the last frame needs lies beyond the first frame's region";
    // That instance alone shows a copy of its sprite with no shape.
    Sprite shapeless = w.tileset.sprites[std::size_t(w.placed.instances[k].sprite)];
    shapeless.name = "shapeless_copy";
    shapeless.shape.clear();
    w.tileset.sprites.push_back(shapeless);
    w.placed.instances[k].sprite = int(w.tileset.sprites.size()) - 1;
    ++w.revision;
    EXPECT_NO_THROW(require_shapes(w, first)) << "the first frame alone would not find it";
    int rows = 0;
    o.rows_so_far = [&](const std::vector<SweepPoint>&) { ++rows; };
    const std::string m = test::error_of([&] { run_sweep(w, s, {{"occluders", {"footprints", "shapes"}}}, o); });
    EXPECT_MENTIONS(m, "shapeless_copy");
    EXPECT_MENTIONS(m, "has no shape");
    EXPECT_EQ(rows, 0) << "a combination ran before the refusal";
}
