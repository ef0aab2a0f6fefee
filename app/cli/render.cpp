#include "cli/render.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "common/world.hpp"
#include "isolux/accuracy.hpp"
#include "isolux/composite.hpp"
#include "isolux/endless.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/tiled.hpp"
#include "isolux/truth.hpp"

namespace isolux::cli {

using namespace isolux::app;

namespace {

Scene scene_from_args(const RenderArgs& a) {
    Scene s;
    if (!a.scene.empty()) {
        std::vector<std::string> warnings;
        s = load_scene(a.scene, &warnings);
        for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << printable(w) << "\n";
    }
    if (!a.seed.empty()) s.seed = a.seed;
    if (a.size == "endless") {
        s.endless = true;
    } else if (!a.size.empty()) {
        std::vector<long long> v;
        if (!parse_ints(a.size, 'x', v) || v.size() != 2)
            throw Error("--size \"" + a.size + "\": expected WxH, e.g. 16x16, or endless");
        if (!map_size_ok(v[0], v[1])) throw Error("--size " + a.size + ": " + map_size_rule());
        s.width = int(v[0]);
        s.height = int(v[1]);
    }
    if (!a.layout.empty()) s.layout = parse_layout(a.layout, "--layout");
    if (!a.tileset.empty()) s.tileset = a.tileset;
    s.params = params_from_args(a.params, s.params);
    for (const std::string& text : a.lights) s.lights.push_back(parse_light(text));
    note_overridden_flags(a.params, s.lights);
    return s;
}

// An endless world's view, in its 64-bit pixels: --view, else the scene's
// camera with a size.
WorldRect endless_view_from_args(const RenderArgs& a, const Scene& s) {
    if (a.view.empty()) {
        if (s.camera.width < 1 || s.camera.height < 1)
            throw Error("an endless world has no whole picture: give --view X,Y,W,H (or a scene camera with a size)");
        if (!(std::abs(s.camera.x) <= 1e15 && std::abs(s.camera.y) <= 1e15))
            throw Error((a.scene.empty() ? std::string("camera") : a.scene + ": camera") +
                        ": x and y must be within ±1e15 pixels in an endless world");
        return WorldRect{std::int64_t(std::floor(s.camera.x)), std::int64_t(std::floor(s.camera.y)), s.camera.width,
                         s.camera.height};
    }
    return parse_endless_view(a.view);
}

Rect view_from_args(const RenderArgs& a, const Scene& s, const World& w) {
    Rect view = camera_view(s.camera, w);  // the whole map when the camera has no size
    if (!a.view.empty()) {
        std::vector<long long> v;
        if (!parse_ints(a.view, ',', v) || v.size() != 4 || v[2] < 1 || v[3] < 1 || v[2] > max_image_side ||
            v[3] > max_image_side || std::abs(v[0]) > 1e9 || std::abs(v[1]) > 1e9)
            throw Error("--view \"" + a.view + "\": expected X,Y,W,H with W and H in [1, " +
                        std::to_string(max_image_side) + "]");
        view = {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
    }
    if ((long long)view.w * view.h > max_render_pixels)
        throw Error("the view is " + std::to_string(view.w) + "x" + std::to_string(view.h) +
                    " pixels, over the 256-megapixel limit: render part of the map with --view X,Y,W,H");
    return view;
}

// A Tiled map's world and scene, with the render flags applied over them.
std::pair<Scene, World> tiled_from_args(const RenderArgs& a) {
    if (!a.scene.empty() || !a.seed.empty() || !a.size.empty() || !a.layout.empty() || !a.tileset.empty())
        throw Error("--map: the map is the level; --scene, --seed, --size, --layout and --tileset do not apply to it");
    TiledMap t = load_tiled(a.map);
    for (const auto& w : t.warnings) std::cerr << "isolux-cli: warning: " << printable(w) << "\n";
    std::cout << "map " << a.map << ": " << t.world.placed.instances.size() << " sprites, " << t.scene.lights.size()
              << " lights; Tiled's pixel (0, 0) is world (" << t.origin_x << ", " << t.origin_y << ")\n";
    Scene s = t.scene;
    s.params = params_from_args(a.params, s.params);
    for (const std::string& text : a.lights) s.lights.push_back(parse_light(text));
    note_overridden_flags(a.params, s.lights);
    return {s, std::move(t.world)};
}

// --stats: each stage that ran, its time and the world rectangles it wrote
// (their bounding box; the count and pixels when they are several).
void print_frame_stats(std::ostream& out, int frame, const FrameReport& rep, double wall_ms) {
    char line[200];
    std::snprintf(line, sizeof line, "frame %d: %.2f ms; %d lights traced, %d reused\n", frame, wall_ms,
                  rep.lights_traced, rep.lights_reused);
    out << line;
    for (int k = 0; k < stage_count; ++k) {
        if (!rep.ran[std::size_t(k)]) continue;
        const Rect r = rep.touched[std::size_t(k)];
        const std::vector<Rect>& parts = rep.touched_parts[std::size_t(k)];
        std::string where = r.empty() ? "nothing"
                                      : std::to_string(r.w) + "x" + std::to_string(r.h) + " at " + std::to_string(r.x) +
                                            "," + std::to_string(r.y);
        if (parts.size() > 1) {
            long long pixels = 0;
            for (const Rect& z : parts) pixels += (long long)z.w * z.h;
            where += " in " + std::to_string(parts.size()) + " rectangles, " + std::to_string(pixels) + " pixels";
        }
        std::snprintf(line, sizeof line, "  %-19s %8.2f ms  touched %s\n", std::string(to_string(Stage(k))).c_str(),
                      rep.ms[std::size_t(k)], where.c_str());
        out << line;
    }
}

// What is rendered: the scene, its world, and the view in the world's pixels.
struct RenderTarget {
    Scene scene;
    World world;
    Rect view;
};

// An endless world's window of chunks around the view (with --frames, around
// the camera's whole straight path), the scene moved into it.
RenderTarget endless_target(const RenderArgs& a, Scene s) {
    const WorldRect v = endless_view_from_args(a, s);
    WorldRect path = v;
    std::vector<double> step{0, 0};
    if (!a.camera_step.empty() && parse_reals(a.camera_step, step) && step.size() == 2 && a.frames > 1) {
        const double dx = step[0] * (a.frames - 1), dy = step[1] * (a.frames - 1);
        if (std::abs(dx) > 65536 || std::abs(dy) > 65536)
            throw Error("--camera-step with --frames: an endless render walks at most 65536 pixels each way");
        path = WorldRect{v.x + std::int64_t(std::floor(std::min(0.0, dx))), v.y + std::int64_t(std::floor(std::min(0.0, dy))),
                         v.w + int(std::ceil(std::abs(dx))) + 1, v.h + int(std::ceil(std::abs(dy))) + 1};
    }
    EndlessWindow win = build_endless_window(s, path, a.scene.empty() ? "--size endless" : a.scene);
    RenderTarget t;
    t.scene = scene_in_window(s, win, path);
    t.view = rect_in_window(win, v);
    t.world = std::move(win.world);
    return t;
}

// A Tiled map, an endless world, or a seeded map (a scene's or the flags').
RenderTarget render_target(const RenderArgs& a) {
    RenderTarget t;
    if (!a.map.empty()) {
        std::tie(t.scene, t.world) = tiled_from_args(a);
    } else {
        t.scene = scene_from_args(a);
        if (t.scene.endless) return endless_target(a, std::move(t.scene));
        t.world = build_world(t.scene, a.scene.empty() ? "scene" : a.scene);
    }
    t.view = view_from_args(a, t.scene, t.world);
    return t;
}

// map, obstacles: the sprites, and the paper's Figure 6 (obstacle pixels in
// white over them).
Image draw_map(const RenderArgs& a, const RenderTarget& t) {
    Image out = render_sprites(t.world.tileset, t.world.placed, t.view);
    if (a.layer == "obstacles") {
        static constexpr std::uint8_t white[4] = {255, 255, 255, 255};
        paint_mask(out, t.view, build_obstacle_map(t.world.tileset, t.world.placed, t.scene.params, t.view), 0, 0, white);
    }
    return out;
}

// final, light: --frames frames of the camera moving --camera-step a frame;
// the last frame's picture or its light texture.
Image draw_lit(const RenderArgs& a, const RenderTarget& t) {
    std::vector<double> step{0, 0};
    if (!a.camera_step.empty() && (!parse_reals(a.camera_step, step) || step.size() != 2))
        throw Error("--camera-step \"" + a.camera_step + "\": expected DX,DY");
    FrameState st;
    st.options.opacity_correction = !a.no_opacity_correction;
    st.options.threads = a.threads;
    st.options.view_light_texture = a.layer == "light";  // the composite reads the blurred texture in place
    Camera cam = t.scene.camera;
    cam.x = t.view.x;
    cam.y = t.view.y;
    cam.width = t.view.w;
    cam.height = t.view.h;
    for (int f = 0; f < a.frames; ++f) {
        Camera c = cam;
        c.x += step[0] * f;
        c.y += step[1] * f;
        const auto t0 = std::chrono::steady_clock::now();
        FrameReport rep = render_frame(st, t.world, t.scene, c, f);
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (a.stats) {
            print_frame_stats(std::cout, f, rep, wall);
        } else if (a.frames > 1) {
            std::cout << "frame " << f << ":";
            for (int k = 0; k < stage_count; ++k)
                if (rep.ran[k]) std::cout << " " << to_string(Stage(k));
            std::cout << " (" << rep.lights_traced << " lights traced)\n";
        }
    }
    return a.layer == "final" ? st.final : light_texture_image(st.light);
}

// truth, difference: the reference's lit frame, or where the model
// (unblurred, as traced and corrected) and the reference disagree over the
// map, dimmed.
Image draw_reference(const RenderArgs& a, const RenderTarget& t) {
    const Reference ref = parse_reference(a.reference, "--reference");
    const LightTexture truth = reference_texture(t.world, t.scene, t.view, ref);
    if (a.layer == "truth") return composite(render_sprites(t.world.tileset, t.world.placed, t.view), t.view, truth, t.scene.params);
    FrameState st;
    st.options.opacity_correction = !a.no_opacity_correction;
    st.options.cpu_blur_and_composite = false;
    render_frame(st, t.world, t.scene, Camera{double(t.view.x), double(t.view.y), t.view.w, t.view.h}, 0);
    Image out = render_sprites(t.world.tileset, t.world.placed, t.view);
    const Image diff = lit_difference(shift_light_texture(st.traced, t.view), truth);
    for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
        for (int k = 0; k < 3; ++k) out.rgba[i + k] = std::uint8_t(out.rgba[i + k] / 3);  // the map, dimmed
        out.rgba[i + 3] = 255;
        if (diff.rgba[i + 3]) std::copy_n(&diff.rgba[i], 4, &out.rgba[i]);
    }
    return out;
}

// opacity: every overlay's opacity map in white on black.
Image draw_opacity(const RenderArgs&, const RenderTarget& t) {
    Image out(t.view.w, t.view.h);
    for (std::size_t i = 3; i < out.rgba.size(); i += 4) out.rgba[i] = 255;
    std::vector<std::optional<Mask>> maps(t.world.tileset.sprites.size());
    for (std::uint32_t i : draw_order(t.world.placed, true)) {
        const SpriteInstance& in = t.world.placed.instances[i];
        const Sprite& sp = t.world.tileset.sprites[in.sprite];
        if (!maps[in.sprite]) maps[in.sprite] = opacity_map(sp.image, sprite_threshold(sp, t.scene.params.opacity_threshold));
        static constexpr std::uint8_t white[4] = {255, 255, 255, 255};
        paint_mask(out, t.view, *maps[in.sprite], in.x, in.y, white);
    }
    return out;
}

// The layers: each name, how it is drawn, and whether it draws the reference
// (whose work counts against --allow-huge).
struct Layer {
    const char* name;
    Image (*draw)(const RenderArgs&, const RenderTarget&);
    bool reference;
    bool lit;  // holds a lit frame's textures (render_memory), not only the sprites
};
constexpr Layer layers[] = {
    {"final", draw_lit, false, true},      {"light", draw_lit, false, true},
    {"map", draw_map, false, false},       {"obstacles", draw_map, false, false},
    {"opacity", draw_opacity, false, false}, {"truth", draw_reference, true, true},
    {"difference", draw_reference, true, true},
};

const Layer& find_layer(const std::string& name) {
    for (const Layer& l : layers)
        if (name == l.name) return l;
    throw Error("--layer \"" + name + "\": not a layer");
}

}  // namespace

std::vector<std::string> render_layer_names() {
    std::vector<std::string> names;
    for (const Layer& l : layers) names.push_back(l.name);
    return names;
}

int run_render(const RenderArgs& a) {
    check_image_output(a.out);  // before the work, not after it
    const Layer& layer = find_layer(a.layer);
    const RenderTarget t = render_target(a);
    // Every frame's trace and pixels, and the reference's own work where one is drawn.
    check_work(render_work(t.scene, t.view, a.frames) +
                   (layer.reference ? reference_work(t.world, t.scene, t.view, parse_reference(a.reference, "--reference")) : 0),
               a.allow_huge, "this render", layer.lit ? render_memory(t.view) : 0);
    save_image(a.out, layer.draw(a, t));
    std::cout << "wrote " << a.out << " (" << t.view.w << "x" << t.view.h << ", layer " << a.layer << ", seed \""
              << t.scene.seed << "\")\n";
    return 0;
}

}  // namespace isolux::cli
