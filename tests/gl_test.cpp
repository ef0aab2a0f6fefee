// The GPU's blur and composite held to core's CPU reference (box_blur,
// composite) within 2/255 per channel. Runs under Xvfb with Mesa's llvmpipe
// in CI (scripts/test.sh); needs a display.
#include <gtest/gtest.h>

#include <GLFW/glfw3.h>

#include "gui/renderer.hpp"
#include "gui/window.hpp"
#include "isolux/blur.hpp"
#include "isolux/frame.hpp"
#include "test_util.hpp"

using namespace isolux;
using namespace isolux::app;

namespace {

struct Gl {
    GLFWwindow* window = nullptr;
    Renderer renderer;
    std::string error;
};

Gl& gl() {
    static Gl g = [] {
        Gl g;
        g.window = open_window(64, 64, false, g.error);
        if (g.window && !renderer_init(g.renderer, g.error)) g.window = nullptr;
        return g;
    }();
    return g;
}

const World& world() {
    static World w = [] {
        Scene s;
        s.width = 7;
        s.height = 6;
        return make_world(test::default_tileset(), s);
    }();
    return w;
}

int max_diff(const Image& a, const Image& b, bool opaque_only = false) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    int worst = 0;
    for (std::size_t i = 0; i < std::min(a.rgba.size(), b.rgba.size()); i += 4) {
        if (opaque_only && b.rgba[i + 3] != 255) continue;
        for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(int(a.rgba[i + k]) - int(b.rgba[i + k])));
    }
    return worst;
}

struct Case {
    const char* name;
    void (*edit)(Scene&);
};

const Case cases[] = {
    {"paper defaults", [](Scene&) {}},
    {"no blur", [](Scene& s) { s.params.blur_radius = 0; }},
    {"blur 5", [](Scene& s) { s.params.blur_radius = 5; }},
    {"blur larger than the texture", [](Scene& s) { s.params.blur_radius = 200; }},
    {"ambient 0", [](Scene& s) { s.params.ambient_clarity = 0; }},
    {"ambient 1", [](Scene& s) { s.params.ambient_clarity = 1; }},
    {"light mix surface", [](Scene& s) { s.params.light_mix = LightMix::surface; }},
    {"light mix surface, shadow", [](Scene& s) { s.params.light_mix = LightMix::surface, s.params.mode = Mode::shadow; }},
    {"game preset", [](Scene& s) { s.params = builtin_preset("game"); }},
    {"dark unlit", [](Scene& s) { s.params.dark_unlit = true; }},
    {"shadow mode", [](Scene& s) { s.params.mode = Mode::shadow; }},
    {"coloured lights", [](Scene& s) {
         s.lights[0].r = 255, s.lights[0].g = 90, s.lights[0].b = 10;
         s.lights[1].intensity = 3;
     }},
};

Scene lit_scene() {
    Scene s;
    s.params.falloff_scale = 8;
    s.params.area_a = s.params.area_b = 90;
    s.lights = {Light{400, 250}, Light{560, 330}};
    return s;
}

}  // namespace

TEST(Gl, contextAndShadersAreAvailable) {
    ASSERT_NE(gl().window, nullptr) << "no GL 3.3 context (run under xvfb-run): " << gl().error;
    EXPECT_TRUE(gl().renderer.shader_error.empty()) << gl().renderer.shader_error;
}

TEST(Gl, blurAndCompositeMatchTheCpuReference) {
    ASSERT_NE(gl().window, nullptr) << gl().error;
    Renderer& r = gl().renderer;
    for (const Case& c : cases) {
        Scene s = lit_scene();
        c.edit(s);
        FrameState cpu;
        const Camera cam{100, 60, 600, 380};
        render_frame(cpu, world(), s, cam, 0);
        renderer_upload_light(r, cpu.traced, cpu.traced.rect);
        renderer_draw_with_colour(r, cpu.sprites, cpu.view, s.params, CompositeOptions{});
        // The blurred light texture: exactly box_blur's 8-bit values.
        const LightTexture ref = box_blur(cpu.traced, s.params.blur_radius);
        Image blurred = renderer_read_blurred(r);
        int worst_blur = 0;
        for (std::size_t i = 0; i < ref.rgb.size() / 3; ++i)
            for (int k = 0; k < 3; ++k)
                worst_blur = std::max(worst_blur, std::abs(int(blurred.rgba[i * 4 + k]) - int(ref.rgb[i * 3 + k])));
        EXPECT_EQ(worst_blur, 0) << c.name << ": the GPU blur differs from box_blur";
        const int worst = max_diff(renderer_read_final(r), cpu.final);
        EXPECT_LE(worst, 2) << c.name << ": GPU composite differs from core's by " << worst << "/255";
    }
}

TEST(Gl, theLightTextureShiftsWithTheCameraOnTheGpuToo) {
    ASSERT_NE(gl().window, nullptr) << gl().error;
    Renderer& r = gl().renderer;
    Scene s = lit_scene();
    s.params.trace_every = 4;
    FrameState cpu;
    Camera cam{100, 60, 600, 380};
    render_frame(cpu, world(), s, cam, 0);
    renderer_upload_light(r, cpu.traced, cpu.traced.rect);
    cam.x += 23;
    cam.y += 11;
    FrameReport rep = render_frame(cpu, world(), s, cam, 1);  // no retrace: the CPU shifts
    ASSERT_FALSE(rep.ran_stage(Stage::trace));
    renderer_draw_with_colour(r, cpu.sprites, cpu.view, s.params, CompositeOptions{});
    EXPECT_LE(max_diff(renderer_read_final(r), cpu.final), 2);
}

TEST(Gl, theWholeGpuFrameMatchesTheCpuFrame) {
    ASSERT_NE(gl().window, nullptr) << gl().error;
    Renderer& r = gl().renderer;
    Scene s = lit_scene();
    FrameState cpu;
    render_frame(cpu, world(), s, Camera{}, 0);
    renderer_set_world(r, world());
    renderer_upload_light(r, cpu.traced, cpu.traced.rect);
    renderer_draw(r, cpu.view, s.params, CompositeOptions{});
    // Sprites too: the atlas is straight alpha, premultiplied in float.
    EXPECT_LE(max_diff(renderer_read_final(r), cpu.final), 2);
}
