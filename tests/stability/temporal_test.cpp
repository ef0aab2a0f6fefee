// Hard cases: the camera between retraces (paper 3.2's inverse translation).
#include "stability.hpp"

using namespace isolux;
using namespace isolux::stability;

TEST(StabilityTemporal, subPixelCameraStepsAccumulate) {
    Scene s = with_light(350, 220);
    s.params.trace_every = 1000;
    FrameState st;
    Camera cam{200, 100, 300, 200};
    render_frame(st, world(), s, cam, 0);
    for (int f = 1; f <= 10; ++f) {
        cam.x += 0.3;  // 3 pixels after 10 frames, not 0
        FrameReport r = render_frame(st, world(), s, cam, f);
        EXPECT_FALSE(r.ran_stage(Stage::trace));
    }
    EXPECT_EQ(st.light.rect.x, 203);
    FrameState fresh;
    render_frame(fresh, world(), s, cam, 0);
    EXPECT_EQ(st.light.texels, fresh.light.texels);
}

TEST(StabilityTemporal, largeCameraStepsLeaveUnlitTexelsUntilTheNextRetrace) {
    Scene s = with_light(350, 220);
    s.params.trace_every = 4;
    s.lights.push_back(Light{700, 420});
    FrameState st;
    Camera cam{200, 100, 300, 200};
    render_frame(st, world(), s, cam, 0);
    cam.x += 400;  // far beyond the margin: the view left the traced texture
    FrameReport r = render_frame(st, world(), s, cam, 1);
    EXPECT_FALSE(r.ran_stage(Stage::trace));  // l = 4: not yet
    EXPECT_EQ(lit_texels(st.light), 0);       // stale: nothing traced here
    for (int f = 2; f <= 4; ++f) r = render_frame(st, world(), s, cam, f);
    EXPECT_TRUE(r.ran_stage(Stage::trace));   // frame 4 retraces: the view moved out
    FrameState fresh;
    render_frame(fresh, world(), s, cam, 0);
    EXPECT_EQ(st.light.texels, fresh.light.texels);
    for (double huge : {1e7, -1e7}) {
        cam.x = huge;
        render_frame(st, world(), s, cam, 8);
        EXPECT_EQ(lit_texels(st.light), 0);
    }
}
