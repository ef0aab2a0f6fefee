// Hard cases: many lights on one spot never wrap around.
#include "stability.hpp"

using namespace isolux;
using namespace isolux::stability;

TEST(StabilityAccumulation, overlappingLightsSaturateAndNeverWrap) {
    const Rect b = world().placed.bounds;
    for (int n : {2, 255, 1000}) {
        Scene s;
        s.width = s.height = 8;
        s.params.area_a = s.params.area_b = 12;
        s.params.ray_skip = 4;
        s.params.mode = Mode::flat;  // the sum alone: no obstacle or sprite in the way
        s.params.blur_radius = 0;
        for (int i = 0; i < n; ++i) s.lights.push_back(Light{b.w / 2.0 + (i % 3), b.h / 2.0 + (i % 2)});
        const Camera cam{b.w / 2.0 - 20, b.h / 2.0 - 20, 40, 40};
        Frame f = stable_frame(s, cam);
        Scene one = s;
        one.lights.resize(1);
        Frame single = frame(one, cam);
        // Where one light gives v > 0, n lights give at least v, capped at 255.
        for (std::size_t i = 0; i < f.light.texels.size(); ++i) {
            EXPECT_GE(f.light.texels[i], single.light.texels[i]) << n << " lights, texel " << i / std::size_t(f.light.channels);
        }
        EXPECT_EQ(f.light.value(f.light.rect.x + 20, f.light.rect.y + 20, 0), 255);
    }
}

TEST(StabilityAccumulation, theSumDoesNotDependOnTheLightsOrder) {
    Scene s = with_light(300, 200, 50, 50);
    s.lights = {Light{300, 200}, Light{330, 210}, Light{310, 230}};
    s.lights[1].r = 30, s.lights[2].intensity = 2.5;
    Frame a = stable_frame(s);
    std::reverse(s.lights.begin(), s.lights.end());
    Frame b = stable_frame(s);
    EXPECT_EQ(a.light.texels, b.light.texels);
}
