// The frame (paper Figure 4): when it retraces and shifts; a frame that
// redoes only what changed equals one built from nothing; the light's look
// options; long work's progress and cancel.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <cmath>

#include "isolux/accuracy.hpp"
#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "base/cpu.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/opacity_correction.hpp"
#include "test_util.hpp"
#include "isolux/opacity_map.hpp"
#include "frame/oracles.hpp"
#include "frame/frame_cache.hpp"

using namespace isolux;
using isolux::test::both_widths;
using isolux::test::random_texture;

namespace {

Scene moving_scene(const World& w, int lights) {
    Scene s;
    s.params.area_a = s.params.area_b = 90;
    s.params.blur_radius = 2;
    Pcg32 rng(21);
    const Rect b = w.placed.bounds;
    for (int i = 0; i < lights; ++i)
        s.lights.push_back(Light{b.x + double(rng.below(std::uint32_t(b.w))) + 0.5, b.y + double(rng.below(std::uint32_t(b.h))) + 0.5});
    return s;
}

}  // namespace

TEST(OnlyWhatChanged, OneMovedLightRedoesItsAreasAndEqualsAFreshFrame) {
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    // Against solids on two threads the one moved light's rays spread over
    // both (the fresh frame gives each thread whole lights): the same bytes.
    for (auto [threads, occluders] : {std::pair{1, Occluders::footprints}, std::pair{2, Occluders::footprints},
                                      std::pair{2, Occluders::solids}}) {
        Scene s = moving_scene(w, 12);
        s.params.occluders = occluders;
        const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 700, 400};
        for (int i = 0; i < 3; ++i) s.lights[std::size_t(i)] = Light{cam.x + 150 + 200.0 * i, cam.y + 100 + 90.0 * i};
        FrameState st;
        st.options.threads = threads;
        render_frame(st, w, s, cam, 0);
        for (long f = 1; f <= 6; ++f) {
            s.lights[std::size_t(f % 3)].x += 7;  // one light moves
            const FrameReport r = render_frame(st, w, s, cam, f);
            FrameState fresh;
            render_frame(fresh, w, s, cam, 0);
            ASSERT_EQ(st.traced.texels, fresh.traced.texels) << "frame " << f;
            ASSERT_EQ(st.light.texels, fresh.light.texels) << "frame " << f;
            ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "frame " << f << ", " << threads << " threads";
            EXPECT_EQ(r.lights_traced, 1);
            // The blur and composite touched a part, not the whole texture or view.
            const Rect blurred = r.touched[int(Stage::blur)], composited = r.touched[int(Stage::composite)];
            EXPECT_FALSE(blurred.empty());
            EXPECT_LT(double(blurred.w) * blurred.h, 0.8 * st.traced.rect.w * st.traced.rect.h);
            EXPECT_LT(double(composited.w) * composited.h, 0.8 * cam.width * cam.height);
            EXPECT_EQ(intersect(composited, r.touched[int(Stage::blur)]), composited);
        }
        // Nothing moved: nothing redone.
        const FrameReport still = render_frame(st, w, s, cam, 7);
        EXPECT_TRUE(still.touched[int(Stage::blur)].empty());
        EXPECT_TRUE(still.touched[int(Stage::composite)].empty());
    }
}

TEST(OnlyWhatChanged, TheLightsOrderByCostChangesNoByteNorRectangle) {
    // Lights are traced costliest first by what each took the frame before
    // (timings: they differ from run to run). Two states whose recorded
    // costs order the lights opposite ways draw the same frames and report
    // the same rectangles, and every traced light has its cost recorded.
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 10);
    const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 700, 400};
    for (std::size_t i = 0; i < s.lights.size(); ++i) s.lights[i] = Light{cam.x + 40 + 65.0 * double(i), cam.y + 40 + 33.0 * double(i)};
    FrameState a, b;
    a.options.threads = b.options.threads = 2;
    render_frame(a, w, s, cam, 0);
    render_frame(b, w, s, cam, 0);
    for (long f = 1; f <= 4; ++f) {
        ASSERT_EQ(a.cache->lights.size(), b.cache->lights.size());
        for (std::size_t i = 0; i < a.cache->lights.size(); ++i) {
            EXPECT_GT(a.cache->lights[i].cost_ms, 0) << "light " << i << " traced without its cost";
            a.cache->lights[i].cost_ms = 1.0 + double(i);
            b.cache->lights[i].cost_ms = 100.0 - double(i);
        }
        for (std::size_t i = 0; i < s.lights.size(); i += 2) s.lights[i].x += 3;  // half the lights move
        const FrameReport ra = render_frame(a, w, s, cam, f), rb = render_frame(b, w, s, cam, f);
        ASSERT_EQ(ra.lights_traced, rb.lights_traced);
        EXPECT_EQ(ra.lights_traced, 5);
        ASSERT_EQ(a.final.rgba, b.final.rgba) << "frame " << f;
        EXPECT_EQ(ra.dirty_parts, rb.dirty_parts) << "frame " << f;
        for (Stage stage : {Stage::trace, Stage::opacity_correction, Stage::blur, Stage::composite})
            EXPECT_EQ(ra.touched_parts[int(stage)], rb.touched_parts[int(stage)]) << "frame " << f << " stage " << int(stage);
    }
}

TEST(OnlyWhatChanged, TheDisjointUnionCoversEachPixelOfThePartsOnce) {
    Pcg32 rng(5);
    for (int round = 0; round < 300; ++round) {
        const int field = 40;
        std::vector<Rect> parts(rng.below(12));
        for (Rect& r : parts)  // some empty, some touching, some nested
            r = {int(rng.below(field)) - 5, int(rng.below(field)) - 5, int(rng.below(20)), int(rng.below(20))};
        std::vector<int> wanted(field * field * 9, 0), got(field * field * 9, 0);  // -field..2 field squared
        auto mark = [&](std::vector<int>& grid, Rect r) {
            for (int y = r.y; y < r.y + r.h; ++y)
                for (int x = r.x; x < r.x + r.w; ++x) grid.at(std::size_t(y + field) * field * 3 + std::size_t(x + field)) += 1;
        };
        for (const Rect& r : parts) mark(wanted, r);
        for (int& v : wanted) v = v > 0;
        const std::vector<Rect> out = disjoint_union(parts);
        for (const Rect& r : out) {
            ASSERT_FALSE(r.empty());
            mark(got, r);
        }
        ASSERT_EQ(got, wanted) << "round " << round;  // every pixel of the union once, nothing else
        for (std::size_t i = 1; i < out.size(); ++i) EXPECT_LE(out[i - 1].y, out[i].y) << "top to bottom";
    }
    // Runs that stay the same join downward: two stacked equal parts are one.
    EXPECT_EQ(disjoint_union({{0, 0, 10, 5}, {0, 5, 10, 5}}), (std::vector<Rect>{{0, 0, 10, 10}}));
}

TEST(OnlyWhatChanged, AGapJoinsCloseRunsOfABandAndNothingElse) {
    // Runs 6 apart join with a gap of 6 (the pixels between included), not
    // with 5; runs in other bands, and parts farther apart, stay apart.
    const std::vector<Rect> parts = {{0, 0, 10, 4}, {16, 0, 10, 4}, {100, 0, 5, 4}, {0, 10, 5, 2}};
    EXPECT_EQ(disjoint_union(parts, 5), disjoint_union(parts));
    EXPECT_EQ(disjoint_union(parts, 6), (std::vector<Rect>{{0, 0, 26, 4}, {100, 0, 5, 4}, {0, 10, 5, 2}}));
    // Random parts: disjoint, covering the union, and every pixel added lies
    // between two runs of its row at most `gap` apart.
    Pcg32 rng(6);
    for (int round = 0; round < 300; ++round) {
        std::vector<Rect> random(rng.below(10));
        for (Rect& r : random) r = {int(rng.below(60)), int(rng.below(30)), int(rng.below(15)), int(rng.below(15))};
        const int gap = int(rng.below(12));
        std::vector<int> in(100 * 50, 0), got(100 * 50, 0);
        for (const Rect& r : random)
            for (int y = r.y; y < r.y + r.h; ++y)
                for (int x = r.x; x < r.x + r.w; ++x) in[std::size_t(y) * 100 + std::size_t(x)] = 1;
        for (const Rect& r : disjoint_union(random, gap))
            for (int y = r.y; y < r.y + r.h; ++y)
                for (int x = r.x; x < r.x + r.w; ++x) got[std::size_t(y) * 100 + std::size_t(x)] += 1;
        for (int y = 0; y < 50; ++y)
            for (int x = 0; x < 100; ++x) {
                const std::size_t i = std::size_t(y) * 100 + std::size_t(x);
                ASSERT_LE(got[i], 1) << "round " << round << ": pixel twice";
                if (in[i]) {
                    ASSERT_EQ(got[i], 1) << "round " << round << ": pixel of the union left out";
                }
                if (got[i] && !in[i]) {  // added: the union's nearest pixels left and right are at most gap + 1 apart
                    int l = x, r = x;
                    while (l >= 0 && !in[std::size_t(y) * 100 + std::size_t(l)]) --l;
                    while (r < 100 && !in[std::size_t(y) * 100 + std::size_t(r)]) ++r;
                    ASSERT_TRUE(l >= 0 && r < 100 && r - l - 1 <= gap) << "round " << round << " at " << x << "," << y;
                }
            }
    }
}

TEST(OnlyWhatChanged, LightsFarApartAreRedoneApart) {
    // Two lights at opposite corners of the view move: the blur and the
    // composite redo their two areas, not the box spanning the view.
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    for (int threads : {1, 2}) {
        Scene s = moving_scene(w, 2);
        const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 900, 500};
        s.lights[0] = Light{cam.x + 120, cam.y + 110};
        s.lights[1] = Light{cam.x + 780, cam.y + 390};
        FrameState st;
        st.options.threads = threads;
        render_frame(st, w, s, cam, 0);
        for (long f = 1; f <= 4; ++f) {
            for (Light& l : s.lights) l.x += (f % 2) ? 3 : -2;
            const FrameReport r = render_frame(st, w, s, cam, f);
            FrameState fresh;
            fresh.options.threads = threads;
            render_frame(fresh, w, s, cam, 0);
            ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "frame " << f << ", " << threads << " threads";
            for (Stage stage : {Stage::trace, Stage::blur, Stage::composite}) {
                const std::vector<Rect>& parts = r.touched_parts[int(stage)];
                const Rect box = r.touched[int(stage)];
                double pixels = 0;
                for (const Rect& z : parts) pixels += double(z.w) * z.h;
                ASSERT_FALSE(parts.empty()) << to_string(stage);
                EXPECT_LT(pixels, 0.5 * box.w * box.h) << to_string(stage) << ": the parts, not their box";
                EXPECT_EQ(disjoint_union(parts).size(), parts.size()) << to_string(stage);
                for (const Rect& z : parts) EXPECT_EQ(intersect(z, box), z);
            }
            // The blur reaches its radius past what was traced; the composite stays in the blur's parts.
            for (const Rect& z : r.touched_parts[int(Stage::composite)]) {
                bool inside = false;
                for (const Rect& b : r.touched_parts[int(Stage::blur)]) inside = inside || intersect(z, b) == z;
                EXPECT_TRUE(inside);
            }
            EXPECT_EQ(r.dirty, r.touched[int(Stage::trace)]);
        }
    }
}

TEST(OnlyWhatChanged, LightsSharingAPlaceEachKeepTheirMask) {
    // Reused masks move out of the cache, one per cached light: two lights
    // at the same place must each find their own (the second one must not
    // get the first one's moved-from, empty mask).
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 3);
    const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 700, 400};
    const Light twin{cam.x + 300, cam.y + 200};
    s.lights = {twin, twin, Light{cam.x + 350, cam.y + 230}};  // its areas meet the twins': they are redrawn
    FrameState st;
    render_frame(st, w, s, cam, 0);
    for (long f = 1; f <= 4; ++f) {
        // Another light moves, and the list's order changes: the second twin
        // is looked for away from its old place.
        Light other = s.lights[f % 2 ? 2 : 1];
        other.y += 5;
        s.lights = f % 2 ? std::vector<Light>{twin, other, twin} : std::vector<Light>{twin, twin, other};
        const FrameReport r = render_frame(st, w, s, cam, f);
        EXPECT_EQ(r.lights_traced, 1);
        EXPECT_EQ(r.lights_reused, 2);
        FrameState fresh;
        render_frame(fresh, w, s, cam, 0);
        ASSERT_EQ(st.traced.texels, fresh.traced.texels) << "frame " << f;
        ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "frame " << f;
    }
}

TEST(OnlyWhatChanged, AgainstSolidsALightAtTheViewsEdgeIsTracedOnceAsTheCameraPans) {
    // Against solids a light keeps its whole area's mask (a clipped one walks
    // the same rays), so a panning camera reuses the lights its view cuts;
    // with footprints a light the view cuts is traced for its new clip.
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    const Camera start{double(w.placed.bounds.x + 300), double(w.placed.bounds.y + 200), 600, 360};
    for (Occluders o : {Occluders::solids, Occluders::footprints}) {
        Scene s = moving_scene(w, 0);
        s.params.occluders = o;
        s.lights = {Light{start.x + 20, start.y + 180},    // the view cuts it, then holds it
                    Light{start.x + 300, start.y + 180}};  // the view holds it, then cuts it
        FrameState st;
        EXPECT_EQ(render_frame(st, w, s, start, 0).lights_traced, 2);
        int traced = 0, reused = 0;
        for (long f = 1; f <= 4; ++f) {
            // Past the texture's margin each frame: the lights are planned anew.
            const Camera cam{start.x - 80.0 * double(f), start.y + 10.0 * double(f), start.width, start.height};
            const FrameReport r = render_frame(st, w, s, cam, f);
            traced += r.lights_traced;
            reused += r.lights_reused;
            FrameState fresh;
            render_frame(fresh, w, s, cam, f);
            ASSERT_EQ(st.traced.texels, fresh.traced.texels) << "frame " << f;
            ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "frame " << f;
        }
        if (o == Occluders::solids) {
            EXPECT_EQ(traced, 0);
            EXPECT_EQ(reused, 8);
        } else {  // the first light when the view stops cutting it, the second when it starts
            EXPECT_EQ(traced, 2);
        }
    }
}

TEST(OnlyWhatChanged, RadiusAndModeChangesRedoEverything) {
    Scene base;
    base.width = base.height = 10;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 5);
    FrameState st;
    render_frame(st, w, s, Camera{}, 0);
    for (int radius : {0, 3, 0, 1}) {
        s.params.blur_radius = radius;
        s.lights[0].y += 3;
        render_frame(st, w, s, Camera{}, 1);
        FrameState fresh;
        render_frame(fresh, w, s, Camera{}, 0);
        EXPECT_EQ(st.final.rgba, fresh.final.rgba) << "radius " << radius;
        EXPECT_EQ(st.light.texels, fresh.light.texels) << "radius " << radius;
    }
}

// Long work (TraceControl): progress in trace_work's steps, the same bytes
// with a control as without, and a cancel that stops within moments and
// leaves nothing half-traced behind.
TEST(LongWork, AControlChangesNoByteAndCountsEachLightsEstimate) {
    // Obstacles over every area below (the fast paths) and a few near the centre.
    Mask ob(Rect{-601, -521, 1203, 1043});
    for (auto [x, y] : {std::pair{2, 1}, {3, 1}, {-4, -2}, {1, -3}, {-2, 2}}) ob.set(x, y);
    const Mask clear_map(Rect{-601, -521, 1203, 1043});
    struct Case {
        Rays rays;
        int skip, a, b;
        Rect clip;  // empty: the whole area
    };
    const Case cases[] = {{Rays::every_pixel, 1, 6, 4, {}},  {Rays::border, 1, 7, 3, {}},
                          {Rays::border, 3, 600, 520, {}},   {Rays::border, 2, 5, 5, Rect{-2, -1, 4, 3}},
                          {Rays::every_pixel, 1, 3, 3, Rect{0, 0, 2, 2}}};
    for (const Case& c : cases)
        for (bool clear : {false, true}) {
            Params p;
            p.rays = c.rays;
            p.ray_skip = c.skip;
            const Rect area{-c.a, -c.b, 2 * c.a + 1, 2 * c.b + 1};
            const Rect clip = c.clip.empty() ? area : c.clip;
            const Mask& obstacles = clear ? clear_map : ob;
            std::atomic<bool> cancel{false};
            std::atomic<std::int64_t> done{0};
            const TraceControl control{&cancel, &done};
            const LightMask with = trace_light(obstacles, 0, 0, c.a, c.b, p, clip, clear, &control);
            const LightMask without = trace_light(obstacles, 0, 0, c.a, c.b, p, clip, clear);
            EXPECT_EQ(with.value, without.value) << c.a << "x" << c.b;
            EXPECT_EQ(done.load(), std::int64_t(light_trace_work(c.a, c.b, p))) << c.a << "x" << c.b << " clear " << clear;
        }
}

TEST(LongWork, ACancelledFrameThrowsKeepsNothingAndTheNextFrameIsAFreshOne) {
    Scene base;
    base.width = base.height = 24;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 3);
    s.params.area_a = s.params.area_b = 700;
    s.params.rays = Rays::every_pixel;  // about 3e9 steps: far beyond a test's time unless cancelled
    const Camera cam{};
    for (int threads : {1, 2}) {
        FrameState st;
        st.options.threads = threads;
        std::atomic<bool> cancel{false};
        std::atomic<std::int64_t> done{0};
        st.options.control = TraceControl{&cancel, &done};
        const double total = trace_work(s, camera_view(cam, w));
        // Cancel once the trace is under way, from another thread, as the app's Cancel button does.
        std::jthread user([&] {
            while (done.load() == 0) std::this_thread::yield();
            cancel = true;
        });
        const auto t0 = std::chrono::steady_clock::now();
        EXPECT_THROW(render_frame(st, w, s, cam, 0), Cancelled);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        user.join();
        EXPECT_GT(done.load(), 0);
        EXPECT_LT(double(done.load()), 0.5 * total) << "stopped late (" << seconds << " s)";
        EXPECT_FALSE(st.cache->has_trace);
        EXPECT_TRUE(st.cache->lights.empty());
        EXPECT_TRUE(st.traced.texels.empty());
        EXPECT_EQ(st.options.threads, threads);  // the options are kept
        // The same state, not cancelled, on a scene small enough to finish: a fresh frame's bytes.
        cancel = false;
        Scene small = s;
        small.params.area_a = small.params.area_b = 60;
        render_frame(st, w, small, cam, 1);
        FrameState fresh;
        fresh.options.threads = threads;
        render_frame(fresh, w, small, cam, 0);
        EXPECT_EQ(st.final.rgba, fresh.final.rgba);
        EXPECT_EQ(st.traced.texels, fresh.traced.texels);
    }
}

TEST(LongWork, ASweepCancelledMidFrameReturnsWhatItFinished) {
    Scene s;
    s.width = s.height = 12;
    const World w = make_world(test::default_tileset(), s);
    s.lights = {Light{double(w.placed.bounds.x + 200), double(w.placed.bounds.y + 150)}};
    s.params.mode = Mode::flat;  // rays never stop: the one combination traces about 1e10 steps a frame (the area is far larger than the view, so ray by ray)
    s.params.rays = Rays::every_pixel;
    s.camera = Camera{double(w.placed.bounds.x), double(w.placed.bounds.y), 400, 300};
    SweepOptions opt;
    opt.frames = 2;
    opt.repeats = 1;
    std::atomic<bool> cancel{false};
    std::jthread user([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        cancel = true;
    });
    const std::vector<SweepPoint> points =
        run_sweep(w, s, {parse_sweep_axis("area_a=1500", s.params, "test"), parse_sweep_axis("area_b=1500", s.params, "test")},
                  opt, {}, &cancel);
    EXPECT_TRUE(cancel.load());
    EXPECT_TRUE(points.empty());  // cancelled inside the first combination's frames
}

namespace {
const World& test_world() {
    static World w = [] {
        Scene s;
        s.width = s.height = 8;
        return make_world(test::default_tileset(), s);
    }();
    return w;
}
}  // namespace

TEST(Frame, retracesOnFrames0LAnd2LWhenLightsMove) {
    Scene s;
    s.params.trace_every = 3;
    s.params.area_a = s.params.area_b = 40;
    FrameState st;
    std::vector<long> traced;
    for (long f = 0; f < 10; ++f) {
        s.lights = {Light{500.0 + 2 * f, 300.0}};  // a light carried by a walking character
        FrameReport r = render_frame(st, test_world(), s, Camera{0, 0, 0, 0}, f);
        if (r.ran_stage(Stage::trace)) traced.push_back(f);
        EXPECT_TRUE(r.ran_stage(Stage::composite) || !r.ran_stage(Stage::trace));
    }
    EXPECT_EQ(traced, (std::vector<long>{0, 3, 6, 9}));
}

TEST(Frame, theShiftedTextureEqualsAFreshTraceOfTheMovedView) {
    for (int blur : {0, 2}) {
        Scene s;
        s.params.trace_every = 4;
        s.params.blur_radius = blur;
        s.params.area_a = s.params.area_b = 60;
        s.lights = {Light{520, 310}, Light{700, 380}};
        FrameState moving;
        Camera cam{300, 150, 400, 300};
        render_frame(moving, test_world(), s, cam, 0);
        ASSERT_GT(*std::max_element(moving.light.texels.begin(), moving.light.texels.end()), 100);
        for (long f = 1; f < 4; ++f) {
            cam.x += 7;
            cam.y += 4.5;  // sub-pixel steps too
            FrameReport r = render_frame(moving, test_world(), s, cam, f);
            EXPECT_FALSE(r.ran_stage(Stage::trace)) << f;
            EXPECT_TRUE(r.ran_stage(Stage::shift)) << f;
            FrameState fresh;
            render_frame(fresh, test_world(), s, cam, 0);
            EXPECT_EQ(moving.light.rect, fresh.light.rect);
            EXPECT_EQ(moving.light.texels, fresh.light.texels) << "blur " << blur << " frame " << f;
            EXPECT_EQ(moving.final.rgba, fresh.final.rgba);
        }
    }
}

TEST(Frame, aStillFrameRunsNoStage) {
    Scene s;
    s.lights = {Light{520, 310}};
    FrameState st;
    render_frame(st, test_world(), s, Camera{}, 0);
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 1);
    for (int k = 0; k < stage_count; ++k) EXPECT_FALSE(r.ran[k]) << to_string(Stage(k));
    s.params.ambient_clarity = 0.8;  // ambient clarity only re-composites
    r = render_frame(st, test_world(), s, Camera{}, 2);
    EXPECT_TRUE(r.ran_stage(Stage::composite));
    EXPECT_FALSE(r.ran_stage(Stage::trace));
    EXPECT_FALSE(r.ran_stage(Stage::obstacle_map));
    s.params.delta_y = 10;  // Δy rebuilds the obstacle map and retraces
    r = render_frame(st, test_world(), s, Camera{}, 3);
    EXPECT_TRUE(r.ran_stage(Stage::obstacle_map));
    EXPECT_TRUE(r.ran_stage(Stage::trace));
}

TEST(Frame, everyParameterChangesTheOutput) {
    Scene base;
    base.params.falloff_scale = 6;
    base.params.area_a = base.params.area_b = 100;
    base.lights = {Light{520, 330}, Light{760, 420}};
    auto render = [](const Scene& s) {
        FrameState st;
        render_frame(st, test_world(), s, Camera{}, 0);
        return st.final.rgba;
    };
    const auto reference = render(base);
    auto changed = [&](auto edit) {
        Scene s = base;
        edit(s.params);
        return render(s) != reference;
    };
    EXPECT_TRUE(changed([](Params& p) { p.delta_y = 6; }));
    EXPECT_TRUE(changed([](Params& p) { p.noise_window = 9; }));
    EXPECT_TRUE(changed([](Params& p) { p.ray_skip = 7; }));
    EXPECT_TRUE(changed([](Params& p) { p.area_a = 40; }));
    EXPECT_TRUE(changed([](Params& p) { p.area_b = 40; }));
    EXPECT_TRUE(changed([](Params& p) { p.ambient_clarity = 0.8; }));
    EXPECT_TRUE(changed([](Params& p) { p.opacity_threshold = 0.95; }));
    EXPECT_TRUE(changed([](Params& p) { p.blur_radius = 0; }));
    EXPECT_TRUE(changed([](Params& p) { p.falloff_scale = 1; }));
    EXPECT_TRUE(changed([](Params& p) { p.mode = Mode::shadow; }));
    EXPECT_TRUE(changed([](Params& p) { p.mode = Mode::flat; }));
    EXPECT_TRUE(changed([](Params& p) { p.dark_unlit = true; }));
    EXPECT_TRUE(changed([](Params& p) { p.rays = Rays::every_pixel; }));
}

TEST(Frame, lightsOutsideTheMapLightWhatTheyReach) {
    Scene s;
    s.params.area_a = s.params.area_b = 200;
    s.params.falloff_scale = 20;
    const Rect b = test_world().placed.bounds;
    s.lights = {Light{double(b.w + 50), double(b.h / 2)}};
    FrameState st;
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 0);
    EXPECT_EQ(r.lights_traced, 1);
    long lit = 0;
    for (std::uint8_t v : st.light.texels) lit += v > 0;
    EXPECT_GT(lit, 0);
    s.lights = {Light{1e8, 1e8}};  // far away: nothing to trace
    FrameState st2;
    r = render_frame(st2, test_world(), s, Camera{}, 0);
    EXPECT_EQ(r.lights_traced, 0);
}

TEST(Frame, anUnchangedLightIsNotTracedAgain) {
    Scene s;
    s.params.area_a = s.params.area_b = 50;
    s.params.falloff_scale = 6;
    s.lights = {Light{420, 260}, Light{600, 330}, Light{500, 300}};
    FrameState st;
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 0);
    EXPECT_EQ(r.lights_traced, 3);
    s.lights[1].x += 9;          // one light moves
    s.lights[2].r = 10;          // one changes colour only: no new rays needed
    r = render_frame(st, test_world(), s, Camera{}, 1);
    EXPECT_EQ(r.lights_traced, 1);
    EXPECT_EQ(r.lights_reused, 2);
    FrameState fresh;
    render_frame(fresh, test_world(), s, Camera{}, 0);
    EXPECT_EQ(st.final.rgba, fresh.final.rgba);
    s.params.ray_skip = 2;       // a tracing parameter: everything again
    r = render_frame(st, test_world(), s, Camera{}, 2);
    EXPECT_EQ(r.lights_traced, 3);
}

TEST(Frame, noLightsMeansNoTracingAndNoUpload) {
    Scene s;
    FrameState st;
    st.options.cpu_blur_and_composite = false;  // as the app runs it
    FrameReport r = render_frame(st, test_world(), s, Camera{}, 0);
    EXPECT_FALSE(r.ran_stage(Stage::trace));
    EXPECT_FALSE(r.retraced);
    s.lights = {Light{400, 250}};
    r = render_frame(st, test_world(), s, Camera{}, 1);
    EXPECT_TRUE(r.retraced);
    EXPECT_EQ(r.dirty, st.traced.rect);  // a new texture: all of it
    s.lights.push_back(Light{600, 300});
    r = render_frame(st, test_world(), s, Camera{}, 2);
    EXPECT_EQ(r.lights_traced, 1);
    // Only the new light's area changed: the upload can be that small.
    EXPECT_EQ(r.dirty, intersect(light_area(s.lights[1], s.params), st.traced.rect));
    s.lights.clear();
    r = render_frame(st, test_world(), s, Camera{}, 3);
    EXPECT_TRUE(r.retraced);  // the lights' areas go dark
    EXPECT_FALSE(r.dirty.empty());
    r = render_frame(st, test_world(), s, Camera{}, 4);
    EXPECT_FALSE(r.retraced);
}

// ---------------------------------------------------------------- lights that look right (not in the paper)


TEST(LightLook, euclideanFalloffMakesRoundLightsAndEdgeFadeReachesZeroAtTheBorder) {
    Params p;
    p.falloff_scale = 8;
    const Mask clear(Rect{-40, -40, 81, 81});
    const Rect area{-20, -20, 41, 41};
    p.falloff_shape = FalloffShape::euclidean;
    LightMask m = trace_light(clear, 0, 0, 20, 20, p, area, true);
    shape_light(m, p);
    auto at = [&](const LightMask& l, int x, int y) { return int(l.value[std::size_t(y + 20) * 41 + (x + 20)]); };
    EXPECT_EQ(at(m, 0, 0), 255);
    EXPECT_EQ(at(m, 10, 10), int(255.0 / (1.0 + std::sqrt(200.0) / 8)));  // round: by the straight-line distance
    EXPECT_EQ(at(m, 14, 0), int(255.0 / (1.0 + 14.0 / 8)));
    EXPECT_LT(at(m, 10, 10), at(m, 10, 0));  // round: the diagonal is further
    Params square;
    square.falloff_scale = 8;
    const LightMask sq = trace_light(clear, 0, 0, 20, 20, square, area, true);
    EXPECT_EQ(at(sq, 10, 10), at(sq, 10, 0));  // the paper's square lights: the same
    p.edge_fade = true;
    LightMask f = trace_light(clear, 0, 0, 20, 20, p, area, true);
    shape_light(f, p);
    EXPECT_EQ(at(f, 0, 0), 255);
    EXPECT_LE(at(f, 20, 0), 255.0 / (1 + 20.0 / 8) / 21 + 1);  // 1/21 of the way left at the border
    EXPECT_EQ(at(f, 20, 20), 0);                               // the corner lies outside the ellipse
    // The paper's settings leave the traced values as they are.
    Params paper;
    LightMask q = trace_light(clear, 0, 0, 20, 20, paper, area, true), q2 = q;
    shape_light(q2, paper);
    EXPECT_EQ(q.value, q2.value);
}

// fade_curve smooth: along every ray, for round and square lights, areas
// wider than tall, on the screen and on the ground (dy_scale 2), the unrounded intensity's slope is continuous for
// 0 < t <= 1 and 0 at the border; the linear fade's is not 0 there (the ring).
TEST(LightLook, theSmoothFadesSlopeIsContinuousAndZeroAtTheBorder) {
    for (FalloffShape shape : {FalloffShape::chebyshev, FalloffShape::euclidean})
        for (const auto& [a, b] : {std::pair{64, 64}, std::pair{90, 45}})
            for (FadeCurve curve : {FadeCurve::smooth, FadeCurve::linear})
            for (double dy_scale : {1.0, 2.0}) {
                Params p;
                p.falloff_space = dy_scale == 1.0 ? FalloffSpace::screen : FalloffSpace::ground;
                p.falloff_scale = 12;
                p.edge_fade = true;
                p.falloff_shape = shape;
                p.fade_curve = curve;
                for (int k = 0; k < 16; ++k) {
                    const double angle = 0.1 + k * 0.39, cx = std::cos(angle), cy = std::sin(angle);
                    // The ray's length to the border (t = 1), by bisection on t.
                    auto t_at = [&](double s) {
                        const double u = std::abs(s * cx) / (a + 1.0), v = std::abs(s * cy) / (b + 1.0);
                        return shape == FalloffShape::euclidean ? std::sqrt(u * u + v * v) : std::max(u, v);
                    };
                    double lo = 0, hi = 4.0 * (a + b);
                    for (int i = 0; i < 100; ++i) (t_at((lo + hi) / 2) < 1 ? lo : hi) = (lo + hi) / 2;
                    const double end = lo, h = end / 20000;
                    auto at = [&](double s) { return faded_intensity(s * cx, s * cy, a, b, p, dy_scale); };
                    double before = (at(2 * h) - at(h)) / h, worst_jump = 0;
                    for (int i = 2; i < 20000; ++i) {
                        const double slope = (at((i + 1) * h) - at(i * h)) / h;
                        worst_jump = std::max(worst_jump, std::abs(slope - before));
                        before = slope;
                    }
                    const std::string what = std::string(shape == FalloffShape::euclidean ? "round" : "square") + " " +
                                             std::to_string(a) + "x" + std::to_string(b) + " dy_scale " + std::to_string(dy_scale) +
                                             " angle " + std::to_string(angle);
                    // Near the centre the falloff's own slope changes fastest: 255 / s^2 per pixel at most,
                    // times dy_scale^2 on the ground (a ray's distance grows up to dy_scale per pixel).
                    EXPECT_LT(worst_jump, 0.05 * dy_scale * dy_scale) << what;
                    const double end_slope = (at(end) - at(end - h)) / h;
                    if (curve == FadeCurve::smooth) {
                        EXPECT_LT(std::abs(end_slope), 1e-3) << what;
                    } else {
                        EXPECT_GT(std::abs(end_slope), 0.05) << what << ": the linear fade meets the border sloped";
                    }
                }
            }
    // The linear curve is today's: edge_fade's bytes unchanged.
    Params p;
    p.edge_fade = true;
    p.falloff_scale = 8;
    EXPECT_EQ(shaped_falloff(10, 0, 20, 20, p, 1.0), std::uint8_t(255.0 / (1 + 10.0 / 8) * (1 - 10.0 / 21)));
}

TEST(LightLook, surfaceLightMixKeepsTheSpritesHue) {
    const double red[3] = {0.8, 0.0, 0.0}, white[3] = {1, 1, 1};
    double lum[3], surf[3];
    Params p;
    composite_pixel(red, white, p, lum);
    p.light_mix = LightMix::surface;
    composite_pixel(red, white, p, surf);
    EXPECT_GT(lum[1], 0.1);   // Algorithm 3 adds the light's white over a red sprite
    EXPECT_EQ(surf[1], 0.0);  // the sprite's own colour takes the light
    EXPECT_GT(surf[0], red[0] * std::sqrt(p.ambient_clarity));
    // In shadow mode a full shadow darkens by three quarters, never to black.
    p.mode = Mode::shadow;
    composite_pixel(red, white, p, surf);
    EXPECT_NEAR(surf[0], 0.8 * std::sqrt(p.ambient_clarity) * 0.25, 1e-12);
}

TEST(Frame, theViewsLightTextureAskedForAgainAfterFramesWithoutItIsTheCurrentOne) {
    Scene s;
    s.width = s.height = 8;
    s.lights = {Light{300.5, 200.5}};
    s.params.area_a = s.params.area_b = 64;
    const Camera cam{100, 50, 500, 400};
    FrameState st;
    render_frame(st, test_world(), s, cam, 0);  // with the view's light texture
    st.options.view_light_texture = false;
    s.lights[0].x = 420.5;
    render_frame(st, test_world(), s, cam, 1);  // the light moved, no copy wanted
    st.options.view_light_texture = true;
    render_frame(st, test_world(), s, cam, 2);  // nothing changed since: the copy is made now
    FrameState fresh;
    render_frame(fresh, test_world(), s, cam, 0);
    EXPECT_EQ(st.light.rect, fresh.light.rect);
    EXPECT_EQ(st.light.texels, fresh.light.texels);
}
