// Rays over low obstacles (height_rays.cpp): a light on the ground is the
// paper's, a low obstacle under a high light casts a short shadow.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "isolux/hash.hpp"
#include "isolux/height_rays.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/truth.hpp"
#include "test_util.hpp"
#include "frame/trace_hooks.hpp"

using namespace isolux;

namespace {

bool lit(const LightMask& m, int x, int y) {
    return m.value[std::size_t(y - m.clip.y) * m.clip.w + (x - m.clip.x)] != 0;
}

}  // namespace

TEST(HeightRays, aLightOnTheGroundTracesExactlyThePapersRays) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
        for (Rays rays : {Rays::border, Rays::every_pixel}) {
            const Rect area{-24, -16, 49, 33};
            Mask obstacles(area);
            Pcg32 rng(seed);
            for (auto& b : obstacles.bits) b = rng.below(100) < 10;
            ObstacleHeights heights{area, std::vector<std::uint16_t>(obstacles.bits.size(), 7)};
            Params p;
            p.rays = rays;
            p.ray_skip = 2;
            const LightMask paper = trace_light(obstacles, 0, 0, 24, 16, p, area);
            const LightMask over = trace_light_over(obstacles, heights, 0, 0, 24, 16, 0.0, p, area);
            EXPECT_EQ(over.value, paper.value) << "seed " << seed;
        }
}

TEST(HeightRays, aLowObstacleUnderAHighLightCastsAShortShadow) {
    // One obstacle 10 steps right of the light, 5 px high; the light 20 px up:
    // it shades steps 11 to 10 / (1 - 5/20) = 13.3, and step 14 on is lit.
    const Rect area{-20, -20, 41, 41};
    Mask obstacles(area);
    obstacles.set(10, 0);
    ObstacleHeights heights{area, std::vector<std::uint16_t>(obstacles.bits.size(), 0)};
    heights.height[std::size_t(20) * 41 + 30] = 5;
    Params p;
    p.rays = Rays::every_pixel;
    const LightMask m = trace_light_over(obstacles, heights, 0, 0, 20, 20, 20.0, p, area);
    EXPECT_TRUE(lit(m, 9, 0));
    EXPECT_FALSE(lit(m, 10, 0));  // the obstacle itself
    EXPECT_FALSE(lit(m, 11, 0));
    EXPECT_FALSE(lit(m, 13, 0));
    EXPECT_TRUE(lit(m, 14, 0));
    EXPECT_TRUE(lit(m, 20, 0));
    // As high as the light: the paper's shadow, to the border.
    heights.height[std::size_t(20) * 41 + 30] = 20;
    const LightMask n = trace_light_over(obstacles, heights, 0, 0, 20, 20, 20.0, p, area);
    EXPECT_FALSE(lit(n, 20, 0));
}
