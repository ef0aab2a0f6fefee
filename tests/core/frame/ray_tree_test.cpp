// Algorithm 2's fast paths held to the general path: clipped lights, and
// the ray tree walked or pruned from the obstacles.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "isolux/accuracy.hpp"
#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "base/cpu.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/opacity_correction.hpp"
#include "test_util.hpp"
#include "frame/trace_hooks.hpp"

using namespace isolux;

TEST(FastTrace, AClippedLightEqualsTheGeneralPath) {
    // The same obstacles twice: in a map covering every light's area (the
    // fast path, traced whole and cropped) and in a map of just their own
    // rectangle (which covers no area: the general path, ray by ray).
    const Rect own{-30, -25, 61, 51};
    Mask small(own), big(Rect{-200, -200, 401, 401});
    Pcg32 rng(31);
    for (int i = 0; i < 300; ++i) {
        const int x = own.x + int(rng.below(std::uint32_t(own.w))), y = own.y + int(rng.below(std::uint32_t(own.h)));
        if (std::abs(x) + std::abs(y) < 3) continue;  // keep the centres clear
        small.set(x, y), big.set(x, y);
    }
    int compared = 0;
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
        for (Rays rays : {Rays::border, Rays::every_pixel})
            for (int k : {1, 3})
                for (int t = 0; t < 6; ++t) {
                    if (rays == Rays::every_pixel && k != 1) continue;
                    Params p;
                    p.mode = mode;
                    p.rays = rays;
                    p.ray_skip = k;
                    const int a = 20 + int(rng.below(60)), b = 20 + int(rng.below(60));
                    const std::int64_t cx = int(rng.below(9)) - 4, cy = int(rng.below(9)) - 4;
                    const Rect area{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
                    const Rect clip = intersect(area, Rect{area.x + int(rng.below(std::uint32_t(a))), area.y - 5,
                                                           a + int(rng.below(std::uint32_t(a))), b + 10});
                    const LightMask fast = trace_light(big, cx, cy, a, b, p, clip);
                    const LightMask general = trace_light(small, cx, cy, a, b, p, clip);
                    ASSERT_EQ(fast.value, general.value) << to_string(mode) << " k " << k << " t " << t;
                    ASSERT_EQ(fast.reached, general.reached) << to_string(mode) << " k " << k << " t " << t;
                    ++compared;
                }
    EXPECT_EQ(compared, 54);
}

TEST(FastTrace, PrunedAndWalkedTreesEqualTheGeneralPath) {
    // From one obstacle to a dense field, so that the tree is both pruned
    // (few obstacles) and walked (many), against the general path, ray by
    // ray, on the same obstacles in a map that covers no area.
    const TreeTraces before = tree_traces();
    Pcg32 rng(77);
    int compared = 0;
    for (int obstacles : {0, 1, 4, 20, 120, 900, 4000})
        for (Mode mode : {Mode::light, Mode::shadow})
            for (int k : {1, 2, 5}) {
                const int a = 15 + int(rng.below(60)), b = 15 + int(rng.below(60));
                const Rect area{-a, -b, 2 * a + 1, 2 * b + 1};
                // `small` lacks the area's left column: it covers no area, so its light takes the general path.
                Mask small(Rect{area.x + 1, area.y, area.w - 1, area.h}), big(Rect{-100, -100, 201, 201});
                for (int i = 0; i < obstacles; ++i) {
                    const int x = area.x + 1 + int(rng.below(std::uint32_t(area.w - 1)));
                    const int y = area.y + int(rng.below(std::uint32_t(area.h)));
                    if (x == 0 && y == 0 && obstacles > 1) continue;  // the centre blocked only in the one-obstacle case below
                    small.set(x, y), big.set(x, y);
                }
                if (obstacles == 1) small.set(0, 0), big.set(0, 0);
                Params p;
                p.mode = mode;
                p.ray_skip = k;
                const LightMask fast = trace_light(big, 0, 0, a, b, p, area);
                const LightMask general = trace_light(small, 0, 0, a, b, p, area);
                ASSERT_EQ(fast.value, general.value) << obstacles << " obstacles, " << to_string(mode) << " k " << k;
                ASSERT_EQ(fast.reached, general.reached) << obstacles << " obstacles, " << to_string(mode) << " k " << k;
                ++compared;
            }
    EXPECT_EQ(compared, 42);
    // Both ways ran (a blocked centre, a dense field: walked; a few obstacles: pruned).
    EXPECT_GE(tree_traces().walked - before.walked, 6u);
    EXPECT_GE(tree_traces().pruned - before.pruned, 12u);
}
