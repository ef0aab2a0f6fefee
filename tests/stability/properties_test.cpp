// Hard cases: properties over many random seeds.
#include "isolux/hash.hpp"
#include "stability.hpp"

using namespace isolux;

namespace {
Mask random_obstacles(Rect r, std::uint64_t seed, int percent) {
    Mask m(r);
    Pcg32 rng(seed);
    for (auto& b : m.bits) b = int(rng.below(100)) < percent;
    return m;
}
}  // namespace

TEST(StabilityProperties, nothingBehindAnObstacleAlongATracedRayIsLit) {
    // A pixel is lit exactly when some traced ray reaches it before that
    // ray's first obstacle: walked here ray by ray, independently of the tracer.
    for (std::uint64_t seed = 0; seed < 60; ++seed) {
        Pcg32 rng(seed * 7 + 1);
        const int a = 4 + int(rng.below(20)), b = 4 + int(rng.below(20));
        const Rect area{-a, -b, 2 * a + 1, 2 * b + 1};
        Mask obs = random_obstacles(area, seed, 3 + int(rng.below(12)));
        obs.set(0, 0, false);
        Params p;
        p.rays = seed % 2 ? Rays::every_pixel : Rays::border;
        p.ray_skip = 1 + int(seed % 3);
        LightMask m = trace_light(obs, 0, 0, a, b, p, area);
        std::vector<std::pair<int, int>> targets;
        if (p.rays == Rays::every_pixel) {
            for (int y = -b; y <= b; ++y)
                for (int x = -a; x <= a; ++x) targets.push_back({x, y});
        } else {
            auto border = border_offsets(a, b);
            for (std::size_t i = 0; i < border.size(); i += std::size_t(p.ray_skip)) targets.push_back(border[i]);
        }
        std::vector<std::uint8_t> expect(m.value.size(), 0);
        for (auto [tx, ty] : targets)
            for (BresenhamRay r(0, 0, tx, ty); !r.done(); r.step()) {
                if (obs.get(int(r.x), int(r.y))) break;  // behind it: not lit by this ray
                expect[std::size_t(r.y + b) * area.w + std::size_t(r.x + a)] = 1;
            }
        ASSERT_EQ(test::lit_of(m), expect) << "seed " << seed;
        for (std::size_t i = 0; i < m.value.size(); ++i)
            if (obs.bits[i]) {
                ASSERT_EQ(m.value[i], 0) << "an obstacle pixel is lit, seed " << seed;
            }
    }
}

TEST(StabilityProperties, intensityNeverIncreasesAlongARay) {
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
        const int a = 30, b = 20;
        const Rect area{-a, -b, 2 * a + 1, 2 * b + 1};
        Mask obs = random_obstacles(area, seed + 100, 4);
        obs.set(0, 0, false);
        Params p;
        p.falloff_scale = 1 + double(seed % 5);
        LightMask m = trace_light(obs, 0, 0, a, b, p, area);
        LightTexture t(area);
        accumulate_light(t, m, Light{}, p);
        for (auto [bx, by] : border_offsets(a, b)) {
            int last = 256;
            for (BresenhamRay r(0, 0, bx, by); !r.done(); r.step()) {
                const int v = t.at(int(r.x), int(r.y))[0];
                if (v == 0) break;
                ASSERT_LE(v, last) << "seed " << seed;
                last = v;
            }
        }
    }
}

TEST(StabilityProperties, translatingAWholeSceneTranslatesItsLight) {
    for (std::uint64_t seed = 0; seed < 30; ++seed) {
        Pcg32 rng(seed + 500);
        const int a = 15, b = 11;
        const int dx = int(rng.below(2000)) - 1000, dy = int(rng.below(2000)) - 1000;
        const Rect area{-a, -b, 2 * a + 1, 2 * b + 1};
        const Rect moved{area.x + dx, area.y + dy, area.w, area.h};
        Mask obs = random_obstacles(area, seed, 10);
        obs.set(0, 0, false);
        Mask obs2 = obs;
        obs2.x0 += dx;
        obs2.y0 += dy;
        Params p;
        p.ray_skip = 1 + int(rng.below(3));
        LightMask m1 = trace_light(obs, 0, 0, a, b, p, area);
        LightMask m2 = trace_light(obs2, dx, dy, a, b, p, moved);
        ASSERT_EQ(m1.value, m2.value) << "seed " << seed;
    }
}

TEST(StabilityProperties, theFastPathTheGeneralPathAndTheClosedFormAgree) {
    for (std::uint64_t seed = 0; seed < 48; ++seed) {
        Pcg32 rng(seed + 900);
        const int a = 1 + int(rng.below(25)), b = 1 + int(rng.below(25));
        const Rect area{100 - a, 50 - b, 2 * a + 1, 2 * b + 1};
        const bool clear = seed % 4 == 0;
        Mask big = random_obstacles(Rect{area.x - 3, area.y - 3, area.w + 6, area.h + 6}, seed, clear ? 0 : 9);
        big.set(100, 50, false);
        // The same obstacles in a mask that does not cover the area: the general path.
        Mask part(Rect{area.x + 1, area.y + 1, area.w - 2, area.h - 2});
        for (int y = part.y0; y < part.y0 + part.height; ++y)
            for (int x = part.x0; x < part.x0 + part.width; ++x) part.set(x, y, big.get(x, y));
        for (int x = area.x; x < area.x + area.w; ++x) big.set(x, area.y, false), big.set(x, area.y + area.h - 1, false);
        for (int y = area.y; y < area.y + area.h; ++y) big.set(area.x, y, false), big.set(area.x + area.w - 1, y, false);
        Params p;
        p.mode = Mode(seed % 3);
        p.rays = seed % 5 == 0 ? Rays::every_pixel : Rays::border;
        p.ray_skip = 1 + int(seed % 2);
        LightMask fast = trace_light(big, 100, 50, a, b, p, area, clear);
        LightMask general = trace_light(part, 100, 50, a, b, p, area);
        ASSERT_EQ(fast.value, general.value) << "seed " << seed;
        ASSERT_EQ(fast.reached, general.reached) << "seed " << seed;
    }
}
