// Shared by the hard-case tests (label "stability"): every output is checked
// for range and determinism.
#pragma once
#include <gtest/gtest.h>

#include <cmath>

#include "isolux/frame.hpp"
#include "isolux/light_trace.hpp"
#include "../test_util.hpp"

namespace isolux::stability {

inline const World& world() {
    static World w = [] {
        Scene s;
        s.width = 8;
        s.height = 8;
        return make_world(test::default_tileset(), s);
    }();
    return w;
}

struct Frame {
    Image final;
    LightTexture light;
    FrameReport report;
};

// One fresh CPU frame of `scene` through `camera`.
inline Frame frame(const Scene& scene, const Camera& camera = Camera{}, int threads = 1) {
    FrameState st;
    st.options.threads = threads;
    Frame f;
    f.report = render_frame(st, world(), scene, camera, 0);
    f.final = st.final;
    f.light = st.light;
    return f;
}

// Renders twice and checks the two are the same bytes and every time figure
// is finite (the pixel values are 8-bit: their range is their type).
inline Frame stable_frame(const Scene& scene, const Camera& camera = Camera{}) {
    Frame a = frame(scene, camera), b = frame(scene, camera);
    EXPECT_EQ(a.final.rgba, b.final.rgba) << "not deterministic";
    EXPECT_EQ(a.light.texels, b.light.texels) << "not deterministic";
    for (double ms : a.report.ms) EXPECT_TRUE(std::isfinite(ms) && ms >= 0);
    EXPECT_EQ(a.final.width, a.light.rect.w);
    EXPECT_EQ(a.final.height, a.light.rect.h);
    return a;
}

inline long lit_texels(const LightTexture& grey_or_rgb) {
    const LightTexture t = rgb_texture(grey_or_rgb);
    long n = 0;
    for (std::size_t i = 0; i < t.texels.size(); i += 3) n += (t.texels[i] | t.texels[i + 1] | t.texels[i + 2]) != 0;
    return n;
}

inline Scene with_light(double x, double y, int a = 60, int b = 60) {
    Scene s;
    s.width = s.height = 8;
    s.params.area_a = a;
    s.params.area_b = b;
    s.params.falloff_scale = 8;
    s.lights = {Light{x, y}};
    return s;
}

}  // namespace isolux::stability
