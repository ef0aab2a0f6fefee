// Hard cases: where lights stand and how large their areas are.
#include "stability.hpp"

using namespace isolux;
using namespace isolux::stability;

TEST(StabilityGeometry, lightsOnTheMapsCornersAndEdges) {
    const Rect b = world().placed.bounds;
    for (auto [x, y] : {std::pair{0.0, 0.0}, {double(b.w - 1), 0.0}, {0.0, double(b.h - 1)},
                        {double(b.w - 1), double(b.h - 1)}, {b.w / 2.0, 0.0}, {0.0, b.h / 2.0}}) {
        Frame f = stable_frame(with_light(x, y));
        EXPECT_GT(lit_texels(f.light), 0) << x << "," << y;
    }
}

TEST(StabilityGeometry, lightsOutsideTheMapLightWhatTheyReach) {
    const Rect b = world().placed.bounds;
    Frame near = stable_frame(with_light(-30, b.h / 2.0));
    EXPECT_GT(lit_texels(near.light), 0);
    // Its 60-pixel area misses the map and the texture's 64-pixel margin.
    Frame beside = stable_frame(with_light(b.w + 200.0, b.h / 2.0));
    EXPECT_EQ(beside.report.lights_traced, 0);
}

TEST(StabilityGeometry, lightsFarOutsideBeyond16BitCoordinates) {
    for (double far : {70000.0, -70000.0, 3.0e6, -2.1e9, 1e18}) {
        Frame f = stable_frame(with_light(far, far, 4096, 4096));
        EXPECT_EQ(f.report.lights_traced, 0) << far;
        EXPECT_EQ(lit_texels(f.light), 0) << far;
    }
}

TEST(StabilityGeometry, aLightInsideAnObstacleLightsNothingButTheCorrection) {
    // Find an obstacle pixel of the world and put a light on it.
    FrameState st;
    Scene s = with_light(0, 0);
    render_frame(st, world(), s, Camera{}, 0);
    const Mask& m = st.obstacles;
    int ox = -1, oy = -1;
    for (int y = 0; y < m.height && ox < 0; ++y)
        for (int x = 0; x < m.width; ++x)
            if (m.bits[std::size_t(y) * m.width + x]) {
                ox = x + m.x0, oy = y + m.y0;
                break;
            }
    ASSERT_GE(ox, 0);
    LightMask t = trace_light(m, ox, oy, 30, 30, Params{}, Rect{ox - 30, oy - 30, 61, 61});
    EXPECT_EQ(std::count(t.value.begin(), t.value.end(), 0), long(t.value.size()));
    stable_frame(with_light(ox + 0.5, oy + 0.5, 30, 30));
}

TEST(StabilityGeometry, degenerateOddEvenAndNonSquareAreas) {
    const Rect b = world().placed.bounds;
    const double cx = b.w / 2.0, cy = b.h / 2.0;
    for (auto [a, bb] : {std::pair{0, 0}, {0, 40}, {40, 0}, {1, 1}, {7, 8}, {8, 7}, {100, 3}, {3, 100}}) {
        for (Rays rays : {Rays::border, Rays::every_pixel}) {
            Scene s = with_light(cx, cy, a, bb);
            s.params.rays = rays;
            s.params.blur_radius = 0;  // the blur would spread light past the area
            Frame f = stable_frame(s);
            EXPECT_LE(lit_texels(f.light), long(2 * a + 1) * (2 * bb + 1) + 0) << a << "x" << bb;
        }
    }
    // The 1x1 area: the centre alone, at full strength unless it is an obstacle.
    Scene one = with_light(cx, cy, 0, 0);
    one.params.blur_radius = 0;
    Frame f = stable_frame(one);
    EXPECT_LE(lit_texels(f.light), 1);
}

TEST(StabilityGeometry, areasLargerThanTheMap) {
    const Rect b = world().placed.bounds;
    Scene s = with_light(b.w / 2.0, b.h / 2.0, 4096, 4096);
    s.params.ray_skip = 64;  // 4(a+b)/64 rays: a large area stays quick
    Frame f = stable_frame(s);
    EXPECT_EQ(f.report.lights_traced, 1);
    EXPECT_GT(lit_texels(f.light), 0);
}

TEST(StabilityGeometry, falloffAtTheEdgesOfItsRange) {
    const std::int64_t ds[] = {0, 1, 127, 128, 254, 255};
    const int expected[] = {255, 127, 1, 1, 1, 0};  // 255 / (1 + d), truncated
    for (int i = 0; i < 6; ++i) EXPECT_EQ(falloff(ds[i], 1.0), expected[i]) << ds[i];
    std::uint8_t last = 255;
    for (std::int64_t d = 0; d < 100000; d += 7) {  // non-increasing, never wraps
        const std::uint8_t v = falloff(d, 3.7);
        EXPECT_LE(v, last);
        last = v;
    }
    EXPECT_EQ(falloff(std::int64_t(1) << 40, 1.0), 0);
    EXPECT_EQ(falloff(std::int64_t(1) << 40, 1e6), 0);
}
