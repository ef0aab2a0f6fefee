// Paper 3.2, Algorithm 2: the Bresenham rays, the falloff, the border and the
// traced light, pixel-exact where the paper is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "frame/trace_hooks.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "test_util.hpp"

using namespace isolux;
using P = std::pair<long, long>;

namespace {

std::vector<P> line(long x0, long y0, long x1, long y1) {
    std::vector<P> out;
    for (BresenhamRay r(x0, y0, x1, y1); !r.done(); r.step()) out.push_back({r.x, r.y});
    return out;
}

std::vector<P> flip(std::vector<P> v, int sx, int sy, bool swap_xy = false) {
    for (P& p : v) {
        if (swap_xy) std::swap(p.first, p.second);
        p.first *= sx;
        p.second *= sy;
    }
    return v;
}

Rect area_rect(int cx, int cy, int a, int b) { return {cx - a, cy - b, 2 * a + 1, 2 * b + 1}; }

Mask random_obstacles(Rect r, int percent, std::uint64_t seed) {
    Mask m(r);
    Pcg32 rng(seed);
    for (auto& b : m.bits) b = int(rng.below(100)) < percent;
    return m;
}

Params with(Mode mode, Rays rays = Rays::border, int k = 1) {
    Params p;
    p.mode = mode;
    p.rays = rays;
    p.ray_skip = k;
    return p;
}

}  // namespace

TEST(Bresenham, matchesHandWorkedLinesInEveryOctant) {
    // (0,0) -> (5,2): numerator starts at 5>>1 = 2 and gains 2 a step; a
    // diagonal step whenever it reaches 5 (then loses 5).
    const std::vector<P> shallow = {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}};
    // (0,0) -> (2,5): the steep case swaps the roles (dx2 = 0, dy2 = 1).
    const std::vector<P> steep = {{0, 0}, {0, 1}, {1, 2}, {1, 3}, {2, 4}, {2, 5}};
    EXPECT_EQ(line(0, 0, 5, 2), shallow);
    EXPECT_EQ(line(0, 0, -5, 2), flip(shallow, -1, 1));
    EXPECT_EQ(line(0, 0, 5, -2), flip(shallow, 1, -1));
    EXPECT_EQ(line(0, 0, -5, -2), flip(shallow, -1, -1));
    EXPECT_EQ(line(0, 0, 2, 5), steep);
    EXPECT_EQ(line(0, 0, -2, 5), flip(steep, -1, 1));
    EXPECT_EQ(line(0, 0, 2, -5), flip(steep, 1, -1));
    EXPECT_EQ(line(0, 0, -2, -5), flip(steep, -1, -1));
    EXPECT_EQ(line(10, 20, 13, 23), (std::vector<P>{{10, 20}, {11, 21}, {12, 22}, {13, 23}}));  // diagonal
    EXPECT_EQ(line(0, 0, 3, 0), (std::vector<P>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
    EXPECT_EQ(line(0, 0, 0, -2), (std::vector<P>{{0, 0}, {0, -1}, {0, -2}}));
    EXPECT_EQ(line(4, 4, 4, 4), (std::vector<P>{{4, 4}}));  // zero length: the centre alone
}

TEST(Falloff, isThePapersIntegerFunction) {
    EXPECT_EQ(falloff(0, 1.0), 255);
    EXPECT_EQ(falloff(1, 1.0), 127);
    EXPECT_EQ(falloff(2, 1.0), 85);
    EXPECT_EQ(falloff(254, 1.0), 1);
    EXPECT_EQ(falloff(255, 1.0), 0);
    EXPECT_EQ(falloff(2, 2.0), 127);   // 255 / (1 + 2/2)
    EXPECT_EQ(falloff(8, 8.0), 127);
    EXPECT_EQ(falloff(0, 0.5), 255);
}

TEST(Border, visitsEachBorderPixelOnce) {
    for (auto [a, b] : {std::pair{3, 2}, {0, 0}, {0, 4}, {5, 0}, {1, 1}, {10, 10}}) {
        auto border = border_offsets(a, b);
        std::set<std::pair<int, int>> unique(border.begin(), border.end());
        EXPECT_EQ(unique.size(), border.size()) << a << "x" << b << ": a corner counted twice";
        long expected = (a == 0 || b == 0) ? long(2 * a + 1) * (2 * b + 1) : 2L * (2 * a + 1) + 2L * (2 * b + 1) - 4;
        EXPECT_EQ(long(border.size()), expected) << a << "x" << b;
        for (auto [x, y] : border) EXPECT_TRUE(std::abs(x) == a || std::abs(y) == b);
    }
}

TEST(Trace, aWallStopsTheLight) {
    Rect area = area_rect(0, 0, 10, 10);
    Mask wall(area);
    for (int y = -10; y <= 10; ++y) wall.set(5, y);
    for (Rays rays : {Rays::border, Rays::every_pixel}) {
        LightMask m = trace_light(wall, 0, 0, 10, 10, with(Mode::light, rays), area);
        for (int y = -10; y <= 10; ++y)
            for (int x = -10; x <= 10; ++x)
                EXPECT_EQ(m.value[(y + 10) * 21 + (x + 10)] > 0, x < 5) << x << "," << y;
    }
}

TEST(Trace, equalsTheUnionOfThePapersRays) {
    // The tracer against a literal transcription of Algorithm 2, ray by ray:
    // nothing behind an obstacle along a traced ray is lit, and nothing else.
    for (int trial = 0; trial < 12; ++trial) {
        const int a = 3 + trial, b = 2 + (trial * 7) % 11, k = 1 + trial % 3;
        Rect area = area_rect(40, -7, a, b);
        Mask obstacles = random_obstacles(area, 8 + trial, trial);
        obstacles.set(40, -7, false);
        Params p = with(Mode::light, Rays::border, k);
        LightMask m = trace_light(obstacles, 40, -7, a, b, p, area);
        std::vector<std::uint8_t> ref(m.value.size(), 0);
        auto border = border_offsets(a, b);
        for (std::size_t i = 0; i < border.size(); i += k)
            trace_light_ray_paper(obstacles, 40, -7, 40 + border[i].first, -7 + border[i].second, area, ref);
        // The transcription writes the intensity: the same pixels, valued 255/(1+d).
        LightTexture tex(area);
        accumulate_light(tex, m, Light{}, p);
        for (std::size_t i = 0; i < ref.size(); ++i) {
            EXPECT_EQ(m.value[i], ref[i]) << "trial " << trial;  // the same intensities
            EXPECT_EQ(tex.texels[i * 3], ref[i]) << "trial " << trial;
        }
        for (std::size_t i = 0; i < m.value.size(); ++i)
            if (obstacles.bits[i]) {
                EXPECT_EQ(m.value[i], 0) << "an obstacle pixel is lit";
            }
    }
}

TEST(Trace, lightAndShadowAreComplementaryInsideTheArea) {
    for (Rays rays : {Rays::border, Rays::every_pixel}) {
        for (auto [a, b] : {std::pair{12, 12}, {20, 6}, {4, 17}}) {
            Rect area = area_rect(0, 0, a, b);
            Mask obstacles = random_obstacles(area, 6, a * 31 + b);
            obstacles.set(0, 0, false);
            LightMask lit = trace_light(obstacles, 0, 0, a, b, with(Mode::light, rays), area);
            LightMask shadow = trace_light(obstacles, 0, 0, a, b, with(Mode::shadow, rays), area);
            LightTexture tl(area), ts(area), tf(area);
            Light white;
            accumulate_light(tl, lit, white, with(Mode::light));
            accumulate_light(ts, shadow, white, with(Mode::shadow));
            LightMask flat = trace_light(obstacles, 0, 0, a, b, with(Mode::flat, rays), area);
            accumulate_light(tf, flat, white, with(Mode::flat));
            for (std::size_t i = 0; i < lit.value.size(); ++i) {
                const bool in_shadow = shadow.reached[i] && !shadow.lit(i);
                ASSERT_NE(lit.lit(i), in_shadow) << "pixel " << i << " is in both or neither";
                ASSERT_EQ(tl.texels[i * 3] + ts.texels[i * 3], tf.texels[i * 3]);
            }
        }
    }
}

TEST(Trace, flatModeIgnoresObstacles) {
    Rect area = area_rect(3, 3, 15, 9);
    Mask obstacles = random_obstacles(area, 30, 9);
    LightMask flat = trace_light(obstacles, 3, 3, 15, 9, with(Mode::flat), area);
    LightMask open = trace_light(Mask(area), 3, 3, 15, 9, with(Mode::light), area);
    EXPECT_EQ(flat.value, open.value);
}

TEST(Trace, borderRaysEqualTheEveryPixelReferenceOnAnEmptyMap) {
    for (auto [a, b] : {std::pair{128, 128}, {7, 3}, {3, 7}, {40, 1}, {0, 5}, {5, 0}, {0, 0}, {1, 1}, {64, 33}}) {
        Rect area = area_rect(0, 0, a, b);
        Mask empty(area);
        LightMask border = trace_light(empty, 0, 0, a, b, with(Mode::light, Rays::border, 1), area);
        LightMask every = trace_light(empty, 0, 0, a, b, with(Mode::light, Rays::every_pixel), area);
        EXPECT_EQ(border.value, every.value) << a << "x" << b;
        const auto lit = test::lit_of(every);
        EXPECT_EQ(std::count(lit.begin(), lit.end(), 1), long(area.w) * area.h);
    }
}

TEST(Trace, skippingRaysLightsASubset) {
    Rect area = area_rect(0, 0, 30, 30);
    Mask empty(area);
    LightMask all = trace_light(empty, 0, 0, 30, 30, with(Mode::light, Rays::border, 1), area);
    LightMask some = trace_light(empty, 0, 0, 30, 30, with(Mode::light, Rays::border, 4), area);
    long n_all = 0, n_some = 0;
    const auto all_lit = test::lit_of(all), some_lit = test::lit_of(some);
    for (std::size_t i = 0; i < all_lit.size(); ++i) {
        EXPECT_LE(some_lit[i], all_lit[i]);
        n_all += all_lit[i];
        n_some += some_lit[i];
    }
    EXPECT_LT(n_some, n_all);
    EXPECT_GT(n_some, n_all / 4);
}

TEST(Trace, aLightInsideAnObstacleLightsNothing) {
    Rect area = area_rect(0, 0, 5, 5);
    Mask m(area);
    m.set(0, 0);
    LightMask t = trace_light(m, 0, 0, 5, 5, with(Mode::light), area);
    EXPECT_EQ(std::count(t.value.begin(), t.value.end(), 0), long(t.value.size()));
}

