// Hard cases: threads never change the output.
#include "isolux/hash.hpp"
#include "stability.hpp"

using namespace isolux;
using namespace isolux::stability;

TEST(StabilityParallel, oneThreadAndManyThreadsGiveIdenticalBytes) {
    Scene s;
    s.width = s.height = 8;
    s.params.falloff_scale = 6;
    s.params.area_a = s.params.area_b = 70;
    Pcg32 rng(21);
    const Rect b = world().placed.bounds;
    for (int i = 0; i < 24; ++i) {
        Light l{double(rng.below(b.w)), double(rng.below(b.h))};
        l.r = std::uint8_t(rng.below(256));
        l.intensity = 0.5 + rng.unit();
        s.lights.push_back(l);
    }
    Frame one = frame(s, Camera{}, 1);
    for (int t : {2, 3, 8, 0}) {
        Frame many = frame(s, Camera{}, t);
        EXPECT_EQ(one.light.texels, many.light.texels) << t << " threads";
        EXPECT_EQ(one.final.rgba, many.final.rgba) << t << " threads";
    }
}
