// The GPU's blur and composite held to core's CPU reference (box_blur,
// composite) within 2/255 per channel. Runs under Xvfb with Mesa's llvmpipe
// in CI (scripts/test.sh); needs a display.
#include <gtest/gtest.h>

#include <GLFW/glfw3.h>

#include <array>

#include "gpu/gpu_tracer.hpp"
#include "gpu/renderer.hpp"
#include "gui/window.hpp"
#include "isolux/blur.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/tileset_file.hpp"
#include "isolux/world.hpp"
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

// The town tileset's world (walls and houses as prisms, rocks and a mound,
// a grove and parts: docs/beyond.md, "Models").
const World& town_world() {
    static World w = [] {
        Scene s;
        s.width = 7;
        s.height = 6;
        s.seed = "isolux town";
        return make_world(load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json"), s);
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
    {"exposure 4, reinhard_knee", [](Scene& s) { s.params.exposure = 4, s.params.tone_map = ToneMap::reinhard_knee; }},
    {"reinhard_knee, surface, dark unlit, ambient 0.1", [](Scene& s) {
         s.params.tone_map = ToneMap::reinhard_knee, s.params.light_mix = LightMix::surface;
         s.params.dark_unlit = true, s.params.ambient_clarity = 0.1, s.params.exposure = 2.5;
     }},
    {"reinhard_knee, shadow mode, exposure 0.5", [](Scene& s) {
         s.params.tone_map = ToneMap::reinhard_knee, s.params.mode = Mode::shadow, s.params.exposure = 0.5;
     }},
    {"shadow mode", [](Scene& s) { s.params.mode = Mode::shadow; }},
    {"coloured lights", [](Scene& s) {
         s.lights[0].r = 255, s.lights[0].g = 90, s.lights[0].b = 10;
         s.lights[1].intensity = 3;
     }},
    {"coloured lights, reinhard_knee, surface", [](Scene& s) {
         s.lights[0].r = 40, s.lights[0].g = 90, s.lights[0].b = 255;
         s.lights[1].intensity = 3;
         s.params.tone_map = ToneMap::reinhard_knee, s.params.light_mix = LightMix::surface, s.params.exposure = 6;
         s.params.ambient_clarity = 0.1;
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
        renderer_upload_surface_ids(r, cpu.surface_ids, cpu.surface_ids_revision);
        renderer_draw_with_colour(r, cpu.sprites, cpu.view, s.params, CompositeOptions{});
        // The blurred light texture: exactly box_blur's 8-bit values (within
        // surfaces where the preset's occluders say so, as the game preset's).
        const LightTexture ref = rgb_texture(blur_within_surfaces(s.params)
                                                 ? box_blur_within(cpu.traced, s.params.blur_radius, cpu.surface_ids)
                                                 : box_blur(cpu.traced, s.params.blur_radius));
        Image blurred = renderer_read_blurred(r);
        int worst_blur = 0;
        for (std::size_t i = 0; i < ref.texels.size() / 3; ++i)
            for (int k = 0; k < 3; ++k)
                worst_blur = std::max(worst_blur, std::abs(int(blurred.rgba[i * 4 + k]) - int(ref.texels[i * 3 + k])));
        EXPECT_EQ(worst_blur, 0) << c.name << ": the GPU blur differs from box_blur";
        const int worst = max_diff(renderer_read_final(r), cpu.final);
        EXPECT_LE(worst, 2) << c.name << ": GPU composite differs from core's by " << worst << "/255";
    }
}

TEST(Gl, theGpuBlursWithinSurfacesAsTheCpuDoes) {
    // With occluders solids the frame's blur stays within the surface each
    // texel shows (box_blur_within): the GPU's blurred texture has its bytes,
    // at several radii and in shadow mode; footprints go back to box_blur.
    ASSERT_NE(gl().window, nullptr) << gl().error;
    Renderer& r = gl().renderer;
    int checked = 0;
    for (int radius : {1, 2, 5}) {
        for (Mode mode : {Mode::light, Mode::shadow}) {
            Scene s = lit_scene();
            s.params.occluders = Occluders::solids;
            s.params.blur_radius = radius;
            s.params.mode = mode;
            FrameState cpu;
            cpu.options.grey_when_lights_are = false;
            const Camera cam{100, 60, 600, 380};
            render_frame(cpu, world(), s, cam, 0);
            ASSERT_FALSE(cpu.surface_ids.id.empty());
            renderer_upload_light(r, cpu.traced, cpu.traced.rect);
            renderer_upload_surface_ids(r, cpu.surface_ids, cpu.surface_ids_revision);
            renderer_draw_with_colour(r, cpu.sprites, cpu.view, s.params, CompositeOptions{});
            const LightTexture want = box_blur_within(cpu.traced, radius, cpu.surface_ids);
            ASSERT_NE(want.texels, box_blur(cpu.traced, radius).texels);  // the case tells the two apart
            const Image blurred = renderer_read_blurred(r);
            int worst = 0;
            for (std::size_t i = 0; i < want.texels.size() / 3; ++i)
                for (int k = 0; k < 3; ++k)
                    worst = std::max(worst, std::abs(int(blurred.rgba[i * 4 + k]) - int(want.texels[i * 3 + k])));
            EXPECT_EQ(worst, 0) << "radius " << radius << ": the GPU blur differs from box_blur_within";
            EXPECT_LE(max_diff(renderer_read_final(r), cpu.final), 2) << "radius " << radius;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 6);
    // Back to footprints: the plain blur again.
    Scene s = lit_scene();
    FrameState cpu;
    render_frame(cpu, world(), s, Camera{100, 60, 600, 380}, 0);
    renderer_upload_light(r, cpu.traced, cpu.traced.rect);
    renderer_upload_surface_ids(r, cpu.surface_ids, cpu.surface_ids_revision);
    renderer_draw_with_colour(r, cpu.sprites, cpu.view, s.params, CompositeOptions{});
    const LightTexture want = rgb_texture(box_blur(cpu.traced, s.params.blur_radius));
    const Image blurred = renderer_read_blurred(r);
    int worst = 0;
    for (std::size_t i = 0; i < want.texels.size() / 3; ++i)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(int(blurred.rgba[i * 4 + k]) - int(want.texels[i * 3 + k])));
    EXPECT_EQ(worst, 0);
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

// ------------------------------------------------------------ the GPU tracer

namespace {

// The obstacle maps the tracer is held to: the default seed's map, a forest
// (every tile three trees) and hand-made walls with doorways.
struct TraceCase {
    std::string name;
    Mask obstacles;
};

std::vector<TraceCase> trace_cases() {
    std::vector<TraceCase> cases;
    const Tileset ts = test::default_tileset();
    for (const char* kind : {"default", "forest"}) {
        Scene s;
        s.width = s.height = 10;
        World w = make_world(ts, s);
        if (std::string(kind) == "forest") {
            const std::vector<int> trees = w.tileset.find(SpriteKind::overlay, "tree");
            for (std::size_t i = 0; i < w.map.tiles.size(); ++i) {
                Tile& t = w.map.tiles[i];
                t.overlay_count = 3;
                const int slots[3][2] = {{0, 0}, {-25, 0}, {25, 0}};
                for (int k = 0; k < 3; ++k) t.overlays[k] = {trees[(i + k) % trees.size()], slots[k][0], slots[k][1]};
            }
            w.placed = place_sprites(w.map, w.tileset);
        }
        cases.push_back({kind, build_obstacle_map(w.tileset, w.placed, Params{}, w.placed.bounds)});
    }
    Mask walls(Rect{-50, -30, 400, 300});
    for (int y = -20; y < 270; y += 40)
        for (int x = -50; x < 350; ++x)
            if (((x + 50) % 90) > 20) walls.set(x, y), walls.set(x, y + 1);
    cases.push_back({"walls", walls});
    return cases;
}

}  // namespace

TEST(Gl, theGpuTracerGivesTheCpuTracersBytes) {
    ASSERT_NE(gl().window, nullptr) << "no GL context (run under xvfb-run): " << gl().error;
    GpuTracer tracer;
    std::string error;
    ASSERT_TRUE(gpu_tracer_init(tracer, error)) << "compute shaders are required (Mesa's llvmpipe has them): " << error;
    int compared = 0, lit_pixels = 0;
    std::uint64_t revision = 0;
    for (const TraceCase& c : trace_cases()) {
        ++revision;  // a new obstacle map: uploaded again
        const Rect b = c.obstacles.rect();
        Pcg32 rng(3);
        for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
            for (int variant = 0; variant < 6; ++variant) {
                Params p;
                p.mode = mode;
                p.ray_skip = variant % 3 == 0 ? 1 : variant % 3 == 1 ? 2 : 5;
                if (variant == 5) p.rays = Rays::every_pixel;
                if (variant == 4) p.falloff_scale = 2.5;
                const int a = variant == 5 ? 15 + int(rng.below(20)) : 10 + int(rng.below(150));
                const int bb = variant == 5 ? 15 + int(rng.below(20)) : 10 + int(rng.below(150));
                // Centres inside the map, near its edge, and just outside it.
                const std::int64_t cx = b.x - 20 + std::int64_t(rng.below(std::uint32_t(b.w + 40)));
                const std::int64_t cy = b.y - 20 + std::int64_t(rng.below(std::uint32_t(b.h + 40)));
                Rect clip{int(cx) - a, int(cy) - bb, 2 * a + 1, 2 * bb + 1};
                if (variant == 3) clip = intersect(clip, {int(cx) - a / 3, int(cy) - bb, a, 2 * bb});  // a view cuts it
                const LightMask want = trace_light(c.obstacles, cx, cy, a, bb, p, clip);
                LightMask got;
                got.clip = clip, got.cx = cx, got.cy = cy, got.a = a, got.b = bb;
                const std::size_t n = std::size_t(clip.w) * clip.h;
                got.value.assign(n, 0);
                got.reached.assign(mode == Mode::shadow ? n : 0, 0);
                std::vector<LightMask*> masks{&got};
                ASSERT_TRUE(gpu_trace(tracer, c.obstacles, revision, masks, p));
                EXPECT_EQ(got.value, want.value) << c.name << " " << to_string(mode) << " variant " << variant << " at "
                                                 << cx << "," << cy << " a " << a << " b " << bb;
                EXPECT_EQ(got.reached, want.reached) << c.name << " " << to_string(mode) << " variant " << variant;
                for (std::uint8_t v : want.value) lit_pixels += v != 0;
                ++compared;
            }
    }
    EXPECT_EQ(compared, 54);
    EXPECT_GT(lit_pixels, 100000) << "the cases must light something";
    gpu_tracer_free(tracer);
}

namespace {

// Frames drawn with the GPU tracer against the CPU's, a light moving 9 px a frame.
void expect_gpu_frames_are_cpu_frames(GpuTracer& tracer, const World& w, Scene s, FrameState& cpu, FrameState& gpu) {
    gpu.options.tracer = [&tracer](const Mask& ob, std::uint64_t rev, const OccluderMap* occ,
                                   const std::vector<LightMask*>& masks, const std::vector<double>& heights,
                                   const Params& p, bool sprite_points) {
        return gpu_trace_frame(tracer, ob, rev, occ, masks, heights, p, sprite_points);
    };
    for (long f = 0; f < 3; ++f) {
        s.lights[0].x += 9;
        const FrameReport rc = render_frame(cpu, w, s, Camera{}, f);
        const FrameReport rg = render_frame(gpu, w, s, Camera{}, f);
        EXPECT_EQ(rc.tracer, "cpu");
        EXPECT_EQ(rg.tracer, "gpu");
        EXPECT_GT(std::count_if(cpu.traced.texels.begin(), cpu.traced.texels.end(), [](std::uint8_t v) { return v != 0; }), 5000)
            << "frame " << f << ": the lights must light something";
        EXPECT_EQ(gpu.traced.texels, cpu.traced.texels) << "frame " << f;
        EXPECT_EQ(gpu.final.rgba, cpu.final.rgba) << "frame " << f;
    }
}

}  // namespace

TEST(Gl, aFrameWithTheGpuTracerEqualsTheCpuFrame) {
    ASSERT_NE(gl().window, nullptr) << "no GL context (run under xvfb-run): " << gl().error;
    GpuTracer tracer;
    std::string error;
    ASSERT_TRUE(gpu_tracer_init(tracer, error)) << error;
    Scene s;
    s.lights = {Light{120.5, 90.5}, Light{300.5, 160.5, 60, 40}};
    FrameState cpu, gpu;
    expect_gpu_frames_are_cpu_frames(tracer, world(), s, cpu, gpu);
    // The game preset: solids, round lights measured on the ground, a smooth
    // fade (the GPU's rays, then the one intensity function on the CPU).
    Scene game = s;
    game.params = builtin_preset("game");
    FrameState cpu_game, gpu_game;
    expect_gpu_frames_are_cpu_frames(tracer, world(), game, cpu_game, gpu_game);
    // Sprite shading from the solids, in light and shadow modes: the GPU's
    // rays, then the shading on the CPU as each light is summed.
    for (Mode mode : {Mode::light, Mode::shadow}) {
        Scene shaded = game;
        shaded.params.sprite_shading = SpriteShading::solids;
        shaded.params.shading_strength = 0.75;
        shaded.params.mode = mode;
        FrameState cpu_shaded, gpu_shaded;
        expect_gpu_frames_are_cpu_frames(tracer, world(), shaded, cpu_shaded, gpu_shaded);
    }
    // The occluders at half and a third of full resolution (occluder_scale):
    // the GPU's passes over the coarse map, each mask taken back on the CPU.
    // The same frame states go on to scale 3: the coarse map changes with
    // the obstacle map's revision the same, and the GPU must see it.
    {
        FrameState cpu_coarse, gpu_coarse;
        for (int scale : {2, 3})
            for (Mode mode : {Mode::light, Mode::shadow}) {
                SCOPED_TRACE("occluder_scale " + std::to_string(scale) + " " + std::string(to_string(mode)));
                Scene coarse = game;
                coarse.params.occluder_scale = scale;
                coarse.params.mode = mode;
                expect_gpu_frames_are_cpu_frames(tracer, world(), coarse, cpu_coarse, gpu_coarse);
            }
        Scene shapes = game;
        shapes.params.occluders = Occluders::shapes;
        shapes.params.occluder_scale = 2;
        FrameState cpu_shapes, gpu_shapes;
        expect_gpu_frames_are_cpu_frames(tracer, world(), shapes, cpu_shapes, gpu_shapes);
        // Coarse differs from full: the knob is honoured, not ignored.
        Scene full = game, half = game;
        half.params.occluder_scale = 2;
        FrameState a, b;
        render_frame(a, world(), full, Camera{}, 0);
        render_frame(b, world(), half, Camera{}, 0);
        EXPECT_NE(a.traced.texels, b.traced.texels);
    }
    // A new frame state on another map, with the same tracer: its obstacle
    // map is uploaded again (revisions are unique in the process).
    Scene other;
    other.width = other.height = 9;
    other.seed = "another map";
    const World w2 = make_world(test::default_tileset(), other);
    FrameState cpu2, gpu2;
    gpu2.options.tracer = gpu.options.tracer;
    render_frame(cpu2, w2, s, Camera{}, 0);
    const FrameReport r2 = render_frame(gpu2, w2, s, Camera{}, 0);
    EXPECT_EQ(r2.tracer, "gpu");
    EXPECT_EQ(gpu2.traced.texels, cpu2.traced.texels) << "a second frame state";
    gpu_tracer_free(tracer);
}

// An occluder map edited in place carries padding in its sprite index
// (OccluderMap::unlisted entries where an edit's lists shrank): the GPU's
// sprite pass skips it as the CPU's does, the same bytes.
TEST(Gl, theGpuSkipsAnEditedMapsPaddingAsTheCpuDoes) {
    ASSERT_NE(gl().window, nullptr) << "no GL context (run under xvfb-run): " << gl().error;
    GpuTracer tracer;
    std::string error;
    ASSERT_TRUE(gpu_tracer_init(tracer, error)) << error;
    World w = world();
    const Rect b = w.placed.bounds;
    Params p;
    p.occluders = Occluders::solids;
    p.falloff_scale = 8;
    OccluderMap occ = build_occluders(w, p, b);
    const int reach = occluder_reach(w.tileset);
    std::uint64_t revision = 5000;
    int compared = 0;
    for (const char* overlay : {"oak", "", "pine", ""}) {
        TileEdit e;
        e.col = 4, e.row = 5;
        e.overlays = *overlay ? std::vector<std::string>{overlay} : std::vector<std::string>{};
        const Rect changed = set_edits(w, {e});
        ASSERT_EQ(w.placed.bounds, b);
        update_occluders(occ, w, p, b, Rect{changed.x - reach, changed.y - reach, changed.w + 2 * reach, changed.h + 2 * reach});
        ++revision;
        const std::int64_t cx = changed.x + changed.w / 2, cy = changed.y + changed.h;
        for (const double height : {8.0, 40.0}) {
            const int a = 90, bb = 90;
            const Rect clip{int(cx) - a, int(cy) - bb, 2 * a + 1, 2 * bb + 1};
            LightMask want = trace_light_solids(occ, cx, cy, a, bb, height, p, clip);
            light_sprite_points(want, occ, height, p);
            LightMask got;
            start_mask(got, cx, cy, a, bb, p, clip, false);
            std::vector<LightMask*> masks{&got};
            ASSERT_TRUE(gpu_trace_solids(tracer, occ, revision, masks, {height}, p, true));
            EXPECT_EQ(got.value, want.value) << (*overlay ? overlay : "cleared") << " at " << height;
            ++compared;
        }
        if (!*overlay) {
            EXPECT_GT(occ.padding, 0u) << "taking a tree away leaves padding";
        }
    }
    EXPECT_EQ(compared, 8);
}

// Beyond the paper: a frame's lights against solids go to the GPU together,
// one dispatch a pass (shaders/start_layers.comp, trace_solids.comp,
// sprite_points.comp) and one read-back:
// lights of different sizes, heights, clips and ray skips in one call, some
// standing past the map's edge (their sprite pixels whose ground point no ray
// walks tested along their own lines), each mask the CPU's bytes.
TEST(Gl, aFramesLightsTracedTogetherAgainstSolidsAreEachTheCpus) {
    ASSERT_NE(gl().window, nullptr) << "no GL context (run under xvfb-run): " << gl().error;
    GpuTracer tracer;
    std::string error;
    ASSERT_TRUE(gpu_tracer_init(tracer, error)) << error;
    std::uint64_t revision = 5000;
    int compared = 0, sprite_pixels_lit = 0, own_lines = 0;
    for (const World* wp : {&world(), &town_world()}) {
        // The map's top two thirds: sprites standing on its lower edge show
        // pixels whose ground point lies past it.
        const Rect b{wp->placed.bounds.x, wp->placed.bounds.y, wp->placed.bounds.w, wp->placed.bounds.h * 2 / 3};
        Params base;
        base.occluders = Occluders::solids;
        const OccluderMap occ = build_occluders(*wp, base, b);
        ++revision;
        for (Mode mode : {Mode::light, Mode::shadow}) {
            Params p = base;
            p.mode = mode;
            p.falloff_scale = 8;
            p.ray_skip = mode == Mode::light ? 1 : 3;
            Pcg32 rng(mode == Mode::light ? 11 : 12);
            std::vector<LightMask> got(12), want(12);
            std::vector<LightMask*> masks;
            std::vector<double> heights;
            for (std::size_t k = 0; k < got.size(); ++k) {
                const int a = 20 + int(rng.below(130)), bb = 20 + int(rng.below(130));
                const double height = std::array<double, 4>{0, 8, 32, 120}[k % 4];
                const bool edge = k % 3 == 0;  // at or past the map's edge
                const std::int64_t cx = edge ? b.x - 10 + std::int64_t(rng.below(20)) : b.x + std::int64_t(rng.below(std::uint32_t(b.w)));
                const std::int64_t cy = edge && k % 2 ? b.y + b.h - 30 + std::int64_t(rng.below(40))
                                                      : b.y + std::int64_t(rng.below(std::uint32_t(b.h)));
                Rect clip{int(cx) - a, int(cy) - bb, 2 * a + 1, 2 * bb + 1};
                if (k % 4 == 1) clip = intersect(clip, {int(cx) - a / 2, int(cy) - bb / 2, a, bb});  // a view cuts it
                want[k] = trace_light_solids(occ, cx, cy, a, bb, height, p, clip);
                light_sprite_points(want[k], occ, height, p);
                start_mask(got[k], cx, cy, a, bb, p, clip, mode == Mode::shadow);
                masks.push_back(&got[k]);
                heights.push_back(height);
            }
            ASSERT_TRUE(gpu_trace_solids(tracer, occ, revision, masks, heights, p, true)) << to_string(mode);
            for (std::size_t k = 0; k < got.size(); ++k) {
                EXPECT_EQ(got[k].value, want[k].value) << to_string(mode) << " light " << k;
                EXPECT_EQ(got[k].reached, want[k].reached) << to_string(mode) << " light " << k;
                const Rect c = want[k].clip;
                for (int y = 0; y < c.h; ++y)
                    for (int x = 0; x < c.w; ++x)
                        if (occ.surface.rect.contains(c.x + x, c.y + y)) {
                            const std::size_t at = std::size_t(c.y + y - occ.surface.rect.y) * occ.surface.rect.w +
                                                   std::size_t(c.x + x - occ.surface.rect.x);
                            if (occ.surface.instance[at] < 0) continue;
                            const bool lit = want[k].value[std::size_t(y) * c.w + x] != 0;
                            sprite_pixels_lit += lit;
                            // Lit along its own line: its ground point off the map.
                            own_lines += lit && !occ.surface.rect.contains(c.x + x, c.y + y + int(rows_above(occ.surface.height[at])));
                        }
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, 48);
    EXPECT_GT(sprite_pixels_lit, 10000) << "the lights must light sprite pixels";
    EXPECT_GT(own_lines, 100) << "and some whose ground point no ray walks";
    gpu_tracer_free(tracer);
}

// Beyond the paper: the ground pass against solids with height on the GPU
// (shaders/trace_solids.comp) gives trace_light_solids's bytes, and the
// sprite pass after it (shaders/sprite_points.comp) light_sprite_points's:
// estimated solids and the manifest's shapes, light and shadow modes, ray
// skips, every pixel, light heights from the ground to above every solid,
// clipped views and centres near and past the map's edge; and whole frames
// equal the CPU's.
TEST(Gl, theGpuTracesAgainstSolidsAsTheCpuDoes) {
    ASSERT_NE(gl().window, nullptr) << "no GL context (run under xvfb-run): " << gl().error;
    GpuTracer tracer;
    std::string error;
    ASSERT_TRUE(gpu_tracer_init(tracer, error)) << error;
    int compared = 0, lit_pixels = 0, shaded_pixels = 0, sprites_lit = 0, sprites_shaded = 0;
    std::uint64_t revision = 1000;
    for (const World* wp : {&world(), &town_world()}) {
    const World& w = *wp;
    const Rect b = w.placed.bounds;
    for (Occluders kind : {Occluders::solids, Occluders::shapes}) {
        Params base;
        base.occluders = kind;
        const OccluderMap occ = build_occluders(w, base, b);
        ++revision;
        Pcg32 rng(7);
        for (Mode mode : {Mode::light, Mode::shadow})
            for (int variant = 0; variant < 6; ++variant) {
                Params p = base;
                p.mode = mode;
                p.falloff_scale = 8;
                p.ray_skip = variant % 3 == 0 ? 1 : variant % 3 == 1 ? 2 : 5;
                if (variant == 5) p.rays = Rays::every_pixel;
                const int a = variant == 5 ? 20 + int(rng.below(30)) : 40 + int(rng.below(140));
                const int bb = variant == 5 ? 20 + int(rng.below(30)) : 40 + int(rng.below(140));
                const double height = std::array<double, 6>{0, 4, 16, 32, 64, 200}[std::size_t(variant)];
                const std::int64_t cx = b.x - 20 + std::int64_t(rng.below(std::uint32_t(b.w + 40)));
                const std::int64_t cy = b.y - 20 + std::int64_t(rng.below(std::uint32_t(b.h + 40)));
                Rect clip{int(cx) - a, int(cy) - bb, 2 * a + 1, 2 * bb + 1};
                if (variant == 3) clip = intersect(clip, {int(cx) - a / 3, int(cy) - bb, a, 2 * bb});  // a view cuts it
                const LightMask want = trace_light_solids(occ, cx, cy, a, bb, height, p, clip);
                LightMask got, got_points;
                start_mask(got, cx, cy, a, bb, p, clip, mode == Mode::shadow);
                start_mask(got_points, cx, cy, a, bb, p, clip, mode == Mode::shadow);
                std::vector<LightMask*> masks{&got}, with_points{&got_points};
                ASSERT_TRUE(gpu_trace_solids(tracer, occ, revision, masks, {height}, p, false)) << to_string(mode) << " " << variant;
                ASSERT_TRUE(gpu_trace_solids(tracer, occ, revision, with_points, {height}, p, true)) << to_string(mode) << " " << variant;
                const std::string where = std::string(wp == &world() ? "default " : "town ") + std::string(kind == Occluders::solids ? "solids " : "shapes ") + std::string(to_string(mode)) +
                                          " variant " + std::to_string(variant);
                EXPECT_EQ(got.value, want.value) << where;
                EXPECT_EQ(got.reached, want.reached) << where;
                LightMask want_points = want;
                light_sprite_points(want_points, occ, height, p);
                EXPECT_EQ(got_points.value, want_points.value) << where << " with the sprite pass";
                EXPECT_EQ(got_points.reached, want_points.reached) << where << " with the sprite pass";
                // The sprite pass both lights and unlights sprite pixels the ground pass left.
                for (std::size_t i = 0; i < want.value.size(); ++i) {
                    sprites_lit += want_points.value[i] != 0 && want.value[i] == 0;
                    sprites_shaded += want_points.value[i] == 0 && want.value[i] != 0;
                }
                // What the ground pass would light with nothing in the way: some of it is shaded.
                const LightMask open = trace_light_solids(OccluderMap{}, cx, cy, a, bb, height, p, clip);
                for (std::size_t i = 0; i < want.value.size(); ++i) {
                    lit_pixels += want.value[i] != 0;
                    shaded_pixels += open.value[i] != 0 && want.value[i] == 0;
                }
                ++compared;
            }
    }
    }
    EXPECT_EQ(compared, 48);
    EXPECT_GT(lit_pixels, 100000) << "the cases must light something";
    EXPECT_GT(shaded_pixels, 5000) << "and solids must shade some of it";
    EXPECT_GT(sprites_lit, 1000) << "the sprite pass must light sprite pixels the ground pass did not";
    EXPECT_GT(sprites_shaded, 1000) << "and shade some it did";

    for (const World* wp : {&world(), &town_world()}) {
        const Rect b = wp->placed.bounds;
        Scene s;
        s.params.occluders = Occluders::solids;
        s.params.falloff_scale = 8;
        s.lights = {Light{b.x + b.w / 3.0 + 0.5, b.y + b.h / 2.0 + 0.5}, Light{b.x + 2 * b.w / 3.0 + 0.5, b.y + b.h / 3.0 + 0.5}};
        FrameState cpu, gpu;
        expect_gpu_frames_are_cpu_frames(tracer, *wp, s, cpu, gpu);
    }
    gpu_tracer_free(tracer);
}
