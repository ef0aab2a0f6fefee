// Hard cases: the adapted Bresenham (Algorithm 2).
#include <set>

#include "isolux/hash.hpp"
#include "stability.hpp"

using namespace isolux;
using namespace isolux::stability;

namespace {
std::vector<std::pair<std::int64_t, std::int64_t>> ray(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
    std::vector<std::pair<std::int64_t, std::int64_t>> out;
    for (BresenhamRay r(x0, y0, x1, y1); !r.done(); r.step()) out.push_back({r.x, r.y});
    return out;
}
}  // namespace

TEST(StabilityBresenham, zeroLengthRaysVisitTheCentreOnce) {
    EXPECT_EQ(ray(5, -3, 5, -3).size(), 1u);
    Mask empty(Rect{-1, -1, 3, 3});
    LightMask m = trace_light(empty, 0, 0, 0, 0, Params{}, Rect{0, 0, 1, 1});
    EXPECT_EQ(m.value, std::vector<std::uint8_t>{255});
}

TEST(StabilityBresenham, everyOctantStepsOnePixelAtATimeAndEndsOnTheTarget) {
    for (int dx = -9; dx <= 9; ++dx)
        for (int dy = -9; dy <= 9; ++dy) {
            auto r = ray(0, 0, dx, dy);
            ASSERT_EQ(r.size(), std::size_t(std::max(std::abs(dx), std::abs(dy)) + 1));
            EXPECT_EQ(r.back(), (std::pair<std::int64_t, std::int64_t>{dx, dy}));
            for (std::size_t i = 1; i < r.size(); ++i) {
                EXPECT_LE(std::llabs(r[i].first - r[i - 1].first), 1);
                EXPECT_LE(std::llabs(r[i].second - r[i - 1].second), 1);
            }
        }
}

TEST(StabilityBresenham, mirrorSymmetricScenesGiveMirrorSymmetricLight) {
    const int a = 20, b = 14;
    Mask obstacles(Rect{-a, -b, 2 * a + 1, 2 * b + 1});
    Pcg32 rng(11);
    for (int y = -b; y <= b; ++y)
        for (int x = 1; x <= a; ++x)
            if (rng.below(100) < 8) obstacles.set(x, y), obstacles.set(-x, y);
    for (Rays rays : {Rays::border, Rays::every_pixel}) {
        Params p;
        p.rays = rays;
        LightMask m = trace_light(obstacles, 0, 0, a, b, p, obstacles.rect());
        for (int y = -b; y <= b; ++y)
            for (int x = 1; x <= a; ++x)
                EXPECT_EQ(m.value[(y + b) * (2 * a + 1) + (x + a)], m.value[(y + b) * (2 * a + 1) + (-x + a)])
                    << x << "," << y;
    }
}

TEST(StabilityBresenham, coordinatesNear2To31DoNotOverflow) {
    const std::int64_t big = (std::int64_t(1) << 31) - 3;
    auto r = ray(big, -big, big + 6, -big - 2);
    ASSERT_EQ(r.size(), 7u);
    EXPECT_EQ(r.back(), (std::pair<std::int64_t, std::int64_t>{big + 6, -big - 2}));
    // The tracer at such a centre: no obstacles out there, every pixel lit.
    Mask obstacles(Rect{0, 0, 4, 4});
    obstacles.set(1, 1);
    LightMask m = trace_light(obstacles, big, big, 3, 3, Params{}, Rect{0, 0, 0, 0});
    EXPECT_TRUE(m.value.empty());
    Rect clip{int(big - 3), int(big - 3), 7, 7};
    LightMask n = trace_light(obstacles, big, big, 3, 3, Params{}, clip);
    EXPECT_EQ(std::count(n.value.begin(), n.value.end(), 0), 0);  // all 49 lit
}

TEST(StabilityBresenham, cornerRaysAreNotCountedTwice) {
    for (int a = 0; a <= 6; ++a)
        for (int b = 0; b <= 6; ++b) {
            auto border = border_offsets(a, b);
            std::set<std::pair<int, int>> unique(border.begin(), border.end());
            EXPECT_EQ(unique.size(), border.size()) << a << "x" << b;
            for (int cx : {-a, a})
                for (int cy : {-b, b}) EXPECT_EQ(unique.count({cx, cy}), 1u);
        }
}

TEST(StabilityBresenham, lightPassesDiagonalGapsBetweenObstacles) {
    // Obstacles at (1,0) and (0,1) leave a diagonal gap: a diagonal step goes
    // from (0,0) to (1,1) without touching either, so light passes (8-connected).
    Mask m(Rect{-5, -5, 11, 11});
    m.set(1, 0);
    m.set(0, 1);
    LightMask t = trace_light(m, 0, 0, 5, 5, Params{}, m.rect());
    EXPECT_GT(t.value[(5 + 5) * 11 + (5 + 5)], 0);  // (5,5) beyond the gap is lit
    EXPECT_EQ(t.value[(0 + 5) * 11 + (1 + 5)], 0);  // the obstacles themselves are not
}
