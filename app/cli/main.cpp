// isolux-cli: the headless front end. Everything here runs with no display and
// no GL context; it only parses arguments and calls isolux::core.
#include <chrono>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "cli/contact_sheet.hpp"
#include "cli/export_tiled.hpp"
#include "common/world.hpp"
#include "isolux/accuracy.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/frame.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"
#include <nlohmann/json.hpp>

#include "isolux/composite.hpp"
#include "isolux/footprint.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/tiled.hpp"
#include "isolux/solid_estimate.hpp"
#include "isolux/truth.hpp"

using namespace isolux;
using namespace isolux::app;

namespace {


// A preset and its overrides on the command line.
struct ParamArgs {
    std::string preset;  // a preset file or a built-in name
    // One per row of the parameter table, set only when given.
    std::vector<std::optional<std::string>> values = std::vector<std::optional<std::string>>(param_table().size());
    std::optional<std::string> area;  // --area A,B: area_a and area_b at once
};

struct RenderArgs {
    std::string seed, size, layout, tileset, scene, map, view, out;
    ParamArgs params;
    std::string layer = "final";
    std::string reference = "3d";
    std::vector<std::string> lights;
    int frames = 1;
    std::string camera_step;
    bool no_opacity_correction = false;
    bool allow_huge = false;
    bool stats = false;
    int threads = 1;
};

// Refuses work beyond what finishes in seconds, with the estimate and the
// flag that allows it anyway.
void check_work(double steps, bool allow, const std::string& what) {
    if (steps <= huge_trace_steps || allow) return;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2g", steps);
    throw Error(what + " would trace about " + std::string(buf) +
                " ray steps (minutes or more): use a smaller area or view, border rays or fewer frames, or --allow-huge");
}

// --preset, then one flag per row of the parameter table: --name-with-dashes
// (and its old name), help from the row, booleans as plain flags.
void add_param_flags(CLI::App& cmd, ParamArgs& pa) {
    cmd.add_option("--preset", pa.preset, "Preset JSON file, or a built-in: paper, fast, quality, game");
    const auto table = param_table();
    for (std::size_t i = 0; i < table.size(); ++i) {
        const ParamInfo& info = table[i];
        std::string names = info.flag;
        if (info.old_flag) names += std::string(",") + info.old_flag;
        std::string help = std::string(*info.symbol ? std::string(info.symbol) + ": " : "") + info.help + " " +
                           param_range_text(info) + ", default " + format_param(info, param_default(info)) + ".";
        if (info.type == ParamType::boolean)
            cmd.add_flag_callback(names, [&pa, i] { pa.values[i] = "true"; }, help);
        else
            cmd.add_option(names, pa.values[i], help);
    }
    cmd.add_option("--area", pa.area, "A,B: --area-a and --area-b at once");
}

// The preset (the scene's, a file or a built-in), then the overrides.
Params params_from_args(const ParamArgs& a, Params p) {
    if (!a.preset.empty()) {
        std::vector<std::string> warnings;
        std::error_code ec;
        bool builtin = !std::filesystem::exists(a.preset, ec) && a.preset.find('.') == std::string::npos;
        p = builtin ? builtin_preset(a.preset) : load_preset(a.preset, &warnings);
        for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << printable(w) << "\n";
    }
    if (a.area) {
        const std::size_t comma = a.area->find(',');
        if (comma == std::string::npos) throw Error("--area \"" + *a.area + "\": expected A,B (half-extents in pixels)");
        set_param(p, "area_a", a.area->substr(0, comma), "--area");
        set_param(p, "area_b", a.area->substr(comma + 1), "--area");
    }
    const auto table = param_table();
    for (std::size_t i = 0; i < table.size(); ++i)
        if (a.values[i]) set_param(p, table[i].name, *a.values[i], table[i].flag);
    validate(p, "parameters");
    return p;
}

bool parse_ints(const std::string& s, char sep, std::vector<long long>& out) {
    out.clear();
    std::size_t pos = 0;
    while (true) {
        std::size_t end = s.find(sep, pos);
        std::string part = s.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (part.empty() || part.size() > 20) return false;
        std::size_t used = 0;
        try {
            out.push_back(std::stoll(part, &used));
        } catch (...) {
            return false;
        }
        if (used != part.size()) return false;
        if (end == std::string::npos) return true;
        pos = end + 1;
    }
}

bool parse_reals(const std::string& s, std::vector<double>& out) {
    out.clear();
    std::size_t pos = 0;
    while (true) {
        std::size_t end = s.find(',', pos);
        std::string part = s.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        std::size_t used = 0;
        try {
            out.push_back(std::stod(part, &used));
        } catch (...) {
            return false;
        }
        if (used != part.size() || !std::isfinite(out.back())) return false;
        if (end == std::string::npos) return true;
        pos = end + 1;
    }
}

// --light X,Y[,A,B[,RRGGBB]][,h=H]
Light parse_light(const std::string& text) {
    const std::string where = "--light \"" + text + "\"";
    std::vector<std::string> parts;
    std::optional<std::string> height;
    for (std::size_t pos = 0;;) {
        std::size_t end = text.find(',', pos);
        std::string part = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (part.rfind("h=", 0) == 0) height = part.substr(2);
        else parts.push_back(part);
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    if (parts.size() != 2 && parts.size() != 4 && parts.size() != 5)
        throw Error(where + ": expected X,Y or X,Y,A,B or X,Y,A,B,RRGGBB, each optionally with ,h=HEIGHT");
    Light l;
    if (height) {
        Params p;
        set_param(p, "light_height", *height, where + " h");
        l.height = p.light_height;
    }
    std::vector<double> xy;
    if (!parse_reals(parts[0] + "," + parts[1], xy) || std::abs(xy[0]) > 1e15 || std::abs(xy[1]) > 1e15)
        throw Error(where + ": X and Y must be numbers within ±1e15 (an endless world's pixels reach that far)");
    l.x = xy[0];
    l.y = xy[1];
    if (parts.size() >= 4) {
        std::vector<long long> ab;
        if (!parse_ints(parts[2] + "," + parts[3], ',', ab) || ab[0] < 0 || ab[1] < 0 ||
            ab[0] > max_area || ab[1] > max_area)
            throw Error(where + ": A and B must be integers in [0, " + std::to_string(max_area) + "]");
        l.area_a = int(ab[0]);
        l.area_b = int(ab[1]);
    }
    if (parts.size() == 5 && !parse_hex_color(parts[4], l.r, l.g, l.b))
        throw Error(where + ": colour must be RRGGBB hex");
    return l;
}

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

// check-tileset: where each overlay's obstacle lands against its anchor.
struct CheckArgs {
    std::string manifest, sheet;
    bool json = false;
    ParamArgs params;
};

int run_check_tileset(const CheckArgs& a) {
    if (!a.sheet.empty()) check_image_output(a.sheet);  // before the work, not after it
    const Tileset ts = load_tileset(a.manifest);
    const Params p = params_from_args(a.params, Params{});
    nlohmann::json report = {{"sprites", nlohmann::json::array()}};
    std::vector<SheetSprite> drawn;
    int warnings = 0;
    for (const Sprite& s : ts.sprites) {
        if (s.kind != SpriteKind::overlay) continue;
        FootprintReport fr;
        Mask fp = tileset_footprint(ts, s, p, &fr);
        double cx = 0, cy = 0;
        Rect box;
        const bool any = mask_centre(fp, cx, cy, box);
        nlohmann::json detected = nlohmann::json::array();
        if (fr.baked_ground) detected.push_back("baked_ground");
        if (fr.baked_shadow) detected.push_back("baked_shadow");
        if (fr.whole_base) detected.push_back("whole_base");
        nlohmann::json e = {{"name", s.name}, {"anchor", {s.anchor_x, s.anchor_y}}, {"detected", detected}};
        std::string warning;
        if (any) {
            const double d = std::hypot(cx - (s.anchor_x + 0.5), cy - (s.anchor_y + 0.5));
            e["obstacle_center"] = {std::round(cx * 10) / 10, std::round(cy * 10) / 10};
            e["obstacle_rect"] = {box.x, box.y, box.w, box.h};
            e["distance"] = std::round(d * 10) / 10;
            if (d > ts.tile_width / 4.0)
                warning = "the obstacle's centre is " + std::to_string(int(std::lround(d))) +
                          " px from the anchor, over a quarter of the tile width (" + std::to_string(ts.tile_width / 4) +
                          "): check the footprint";
        } else {
            e["obstacle_center"] = nullptr;
            e["obstacle_rect"] = nullptr;
            e["distance"] = nullptr;
            if (s.footprint.mode != FootprintMode::none) warning = "no obstacle: light passes through this sprite";
        }
        // Beyond the paper: each object's solid, estimated from the alpha alone,
        // and how much of the manifest's shape it shares, where there is one.
        const std::vector<EstimatedObject> objects = estimate_objects(fr.estimate, fp, &s.footprint, &s.image, fr.whole_base);
        e["objects"] = nlohmann::json::array();
        for (const EstimatedObject& o : objects)
            e["objects"].push_back({{"center", {std::round(o.center_x * 10) / 10, std::round(o.center_y * 10) / 10}},
                                    {"rect", {o.rect.x, o.rect.y, o.rect.w, o.rect.h}},
                                    {"height", o.height()}});
        e["solid_overlap"] = s.shape.empty() ? nlohmann::json(nullptr)
                                             : nlohmann::json(std::round(volume_overlap(objects, s.anchor_x, s.anchor_y,
                                                                                        s.shape) * 1000) / 1000);
        e["warning"] = warning.empty() ? nlohmann::json(nullptr) : nlohmann::json(warning);
        warnings += !warning.empty();
        report["sprites"].push_back(e);
        drawn.push_back({&s, std::move(fp), objects});
    }
    if (a.json) {
        std::cout << report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    } else {
        std::cout << "sprite                obstacle centre     anchor        distance  detected\n";
        for (const auto& e : report["sprites"]) {
            char line[256];
            const auto& c = e["obstacle_center"];
            std::snprintf(line, sizeof line, "%-20s  %-18s  %-12s  %-8s  %s", e["name"].get<std::string>().c_str(),
                          c.is_null() ? "none" : (std::to_string(int(c[0].get<double>())) + ", " + std::to_string(int(c[1].get<double>()))).c_str(),
                          (std::to_string(e["anchor"][0].get<int>()) + ", " + std::to_string(e["anchor"][1].get<int>())).c_str(),
                          e["distance"].is_null() ? "-" : std::to_string(int(std::lround(e["distance"].get<double>()))).c_str(),
                          e["detected"].dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
            std::cout << line << "\n";
            if (!e["warning"].is_null()) std::cout << "  warning: " << e["warning"].get<std::string>() << "\n";
        }
        std::cout << warnings << " warning" << (warnings == 1 ? "" : "s") << "\n";
    }
    if (!a.sheet.empty()) {
        save_image(a.sheet, contact_sheet(drawn));
        if (!a.json) std::cout << "wrote " << a.sheet << "\n";
    }
    return 0;
}

// One line a row of the parameter table, tab-separated, with a header.
void print_param_table() {
    std::cout << "name\tflag\told_flag\ttype\tmin\tmax\tdefault\tsymbol\treruns\thelp\n";
    static const char* types[] = {"integer", "real", "choice", "boolean"};
    for (const ParamInfo& info : param_table()) {
        std::string reruns;
        for (int k = 0; k < stage_count; ++k)
            if (info.reruns.has(Stage(k))) reruns += (reruns.empty() ? "" : ",") + std::string(to_string(Stage(k)));
        const bool numeric = info.type == ParamType::integer || info.type == ParamType::real;
        std::cout << info.name << '\t' << info.flag << '\t' << (info.old_flag ? info.old_flag : "-") << '\t'
                  << types[int(info.type)] << '\t'
                  << (numeric ? format_param(info, info.min) : std::string(info.type == ParamType::boolean ? "false" : info.choices[0]))
                  << (info.min_open ? " (excluded)" : "") << '\t'
                  << (numeric ? format_param(info, info.max) : format_param(info, info.max)) << '\t'
                  << format_param(info, param_default(info)) << '\t' << (*info.symbol ? info.symbol : "-") << '\t'
                  << (reruns.empty() ? "-" : reruns) << '\t' << info.help << '\n';
    }
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

int run_render(const RenderArgs& a) {
    check_image_output(a.out);  // before the work, not after it
    Scene s;
    World w;
    if (!a.map.empty()) {
        std::tie(s, w) = tiled_from_args(a);
    } else {
        s = scene_from_args(a);
        if (!s.endless) w = build_world(s, a.scene.empty() ? "scene" : a.scene);
    }
    Rect view;
    WorldRect path;
    if (s.endless) {
        // No edge: the window of chunks around the view, the scene moved into it.
        // With --frames, the window holds the camera's whole straight path.
        const WorldRect v = endless_view_from_args(a, s);
        std::vector<double> step{0, 0};
        if (!a.camera_step.empty() && parse_reals(a.camera_step, step) && step.size() == 2 && a.frames > 1) {
            const double dx = step[0] * (a.frames - 1), dy = step[1] * (a.frames - 1);
            if (std::abs(dx) > 65536 || std::abs(dy) > 65536)
                throw Error("--camera-step with --frames: an endless render walks at most 65536 pixels each way");
            path = WorldRect{v.x + std::int64_t(std::floor(std::min(0.0, dx))), v.y + std::int64_t(std::floor(std::min(0.0, dy))),
                             v.w + int(std::ceil(std::abs(dx))) + 1, v.h + int(std::ceil(std::abs(dy))) + 1};
        } else {
            path = v;
        }
        EndlessWindow win = build_endless_window(s, path, a.scene.empty() ? "--size endless" : a.scene);
        s = scene_in_window(s, win, path);
        view = rect_in_window(win, v);
        w = std::move(win.world);
    } else {
        view = view_from_args(a, s, w);
    }
    // Every frame's trace and pixels, and the reference's own work where one is drawn.
    const bool reference_drawn = a.layer == "truth" || a.layer == "difference";
    check_work(render_work(s, view, a.frames) +
                   (reference_drawn ? reference_work(w, s, view, parse_reference(a.reference, "--reference")) : 0),
               a.allow_huge, "this render");
    Image out;
    if (a.layer == "map" || a.layer == "obstacles") {
        out = render_sprites(w.tileset, w.placed, view);
        if (a.layer == "obstacles") {
            // The paper's Figure 6: obstacle pixels in white over the map.
            static constexpr std::uint8_t white[4] = {255, 255, 255, 255};
            paint_mask(out, view, build_obstacle_map(w.tileset, w.placed, s.params, view), 0, 0, white);
        }
    } else if (a.layer == "light" || a.layer == "final") {
        std::vector<double> step{0, 0};
        if (!a.camera_step.empty() && (!parse_reals(a.camera_step, step) || step.size() != 2))
            throw Error("--camera-step \"" + a.camera_step + "\": expected DX,DY");
        FrameState st;
        st.options.opacity_correction = !a.no_opacity_correction;
        st.options.threads = a.threads;
        st.options.view_light_texture = a.layer == "light";  // the composite reads the blurred texture in place
        Camera cam = s.camera;
        cam.x = view.x;
        cam.y = view.y;
        cam.width = view.w;
        cam.height = view.h;
        for (int f = 0; f < a.frames; ++f) {
            Camera c = cam;
            c.x += step[0] * f;
            c.y += step[1] * f;
            const auto t0 = std::chrono::steady_clock::now();
            FrameReport rep = render_frame(st, w, s, c, f);
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
        out = a.layer == "final" ? st.final : light_texture_image(st.light);
    } else if (a.layer == "truth" || a.layer == "difference") {
        // The reference's lit frame, or where the model (unblurred, as traced
        // and corrected) and the reference disagree over the map.
        const Reference ref = parse_reference(a.reference, "--reference");
        const LightTexture truth = reference_texture(w, s, view, ref);
        if (a.layer == "truth") {
            out = composite(render_sprites(w.tileset, w.placed, view), view, truth, s.params);
        } else {
            FrameState st;
            st.options.opacity_correction = !a.no_opacity_correction;
            st.options.cpu_blur_and_composite = false;
            render_frame(st, w, s, Camera{double(view.x), double(view.y), view.w, view.h}, 0);
            out = render_sprites(w.tileset, w.placed, view);
            const Image diff = lit_difference(shift_light_texture(st.traced, view), truth);
            for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
                for (int k = 0; k < 3; ++k) out.rgba[i + k] = std::uint8_t(out.rgba[i + k] / 3);  // the map, dimmed
                out.rgba[i + 3] = 255;
                if (diff.rgba[i + 3]) std::copy_n(&diff.rgba[i], 4, &out.rgba[i]);
            }
        }
    } else if (a.layer == "opacity") {
        out = Image(view.w, view.h);
        for (std::size_t i = 3; i < out.rgba.size(); i += 4) out.rgba[i] = 255;
        std::vector<std::optional<Mask>> maps(w.tileset.sprites.size());
        for (std::uint32_t i : draw_order(w.placed, true)) {
            const SpriteInstance& in = w.placed.instances[i];
            const Sprite& sp = w.tileset.sprites[in.sprite];
            if (!maps[in.sprite]) maps[in.sprite] = opacity_map(sp.image, sprite_threshold(sp, s.params.opacity_threshold));
            static constexpr std::uint8_t white[4] = {255, 255, 255, 255};
            paint_mask(out, view, *maps[in.sprite], in.x, in.y, white);
        }
    }
    save_image(a.out, out);
    std::cout << "wrote " << a.out << " (" << view.w << "x" << view.h << ", layer " << a.layer << ", seed \""
              << s.seed << "\")\n";
    return 0;
}

struct SweepArgs {
    std::string scene, out, chart;
    std::vector<std::string> params;
    int frames = 8, repeats = 3;
    std::string step = "24,12";
    std::string references = "every_pixel";
    bool no_carry = false;
    bool allow_huge = false;
    bool no_opacity_correction = false;
};

int run_sweep_command(const SweepArgs& a) {
    // Outputs checked before the work, not after it.
    check_output_file(a.out);
    if (!a.chart.empty()) check_output_file(a.chart);
    std::vector<std::string> warnings;
    Scene s = load_scene(a.scene, &warnings);
    for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << printable(w) << "\n";
    std::vector<SweepAxis> axes;
    for (const std::string& text : a.params) axes.push_back(parse_sweep_axis(text, s.params, "--param"));
    std::vector<double> step;
    if (!parse_reals(a.step, step) || step.size() != 2) throw Error("--step \"" + a.step + "\": expected DX,DY");
    SweepOptions opt;
    opt.frames = a.frames;
    opt.repeats = a.repeats;
    opt.step_x = step[0];
    opt.step_y = step[1];
    opt.carry_light = !a.no_carry;
    opt.opacity_correction = !a.no_opacity_correction;
    opt.references.clear();
    for (std::size_t pos = 0;;) {
        const std::size_t end = a.references.find(',', pos);
        opt.references.push_back(parse_reference(a.references.substr(pos, end == std::string::npos ? end : end - pos),
                                                 "--reference"));
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    World w = build_world(s, a.scene);
    check_work(sweep_work(w, s, axes, opt), a.allow_huge, "this sweep");  // before any of it starts
    long combos = 1;
    for (const SweepAxis& ax : axes) combos *= long(ax.values.size());
    std::cerr << "isolux-cli: sweeping " << combos << " combinations x " << opt.repeats << " runs x " << opt.frames
              << " frames, against " << a.references << "\n";
    // Each row written as it is measured (the pareto column empty until the
    // end), so a sweep stopped midway keeps what it measured.
    opt.rows_so_far = [&](const std::vector<SweepPoint>& so_far) { write_file_atomic(a.out, sweep_csv(axes, so_far, false)); };
    auto points = run_sweep(w, s, axes, opt, [&](int done, int total) {
        std::cerr << "\r  [" << done << "/" << total << "] " << int(100.0 * done / total) << "%" << std::flush;
    });
    std::cerr << "\n";
    write_file_atomic(a.out, sweep_csv(axes, points));
    std::cout << "wrote " << a.out << "\n";
    if (!a.chart.empty()) {
        const Rect start = camera_view(s.camera, w);
        const std::string what = std::filesystem::path(a.scene).filename().string() + " (seed \"" + s.seed + "\"), " +
                                 std::to_string(opt.frames) + " frames from view " + std::to_string(start.x) + "," +
                                 std::to_string(start.y) + " " + std::to_string(start.w) + "x" + std::to_string(start.h) +
                                 " moving " + a.step + " px a frame, against " + a.references;
        write_file_atomic(a.chart, sweep_svg(axes, points, "Error against time\n" + what));
        std::cout << "wrote " << a.chart << "\n";
    }
    std::cout << "Pareto front (least final-frame RMSE for the time), per reference:\n";
    for (const SweepPoint* p : pareto_front(points)) {
        std::cout << "  [" << to_string(p->reference) << "] ";
        for (std::size_t i = 0; i < axes.size(); ++i) std::cout << axes[i].name << "=" << p->values[i] << " ";
        std::cout << " " << p->lighting_ms << " ms/frame lighting (" << p->total_ms << " in all), final RMSE " << p->final.rmse << ", lit mismatch "
                  << p->light.lit_mismatch * 100 << "%\n";
    }
    return 0;
}

}  // namespace

// The whole command line (tests/fuzz/fuzz_cli.cpp calls it too).
int isolux_cli_main(int argc, char** argv) {
    // What the saves had to do that the user should know (a hard link that
    // could not be kept), said once the command ends, however it ends.
    struct SayNotes {
        ~SayNotes() {
            for (const std::string& n : take_write_notes()) std::cerr << "isolux-cli: note: " << printable(n) << "\n";
        }
    } say_notes;
    CLI::App app{"isolux-cli: renders seeded isometric maps and the paper's lighting with no display."};
    app.require_subcommand(1);

    RenderArgs ra;
    CLI::App* render = app.add_subcommand("render", "Render a seeded map (or a scene) to an image");
    render->add_option("--seed", ra.seed, "Map seed text (default \"isolux\")");
    render->add_option("--size", ra.size, "Map size in tiles, WxH (default 16x16), or endless (needs --view or a scene camera with a size)");
    render->add_option("--layout", ra.layout, "paper, diamond or staggered (default diamond)");
    render->add_option("--tileset", ra.tileset, "Tileset manifest (default: assets/default/tileset.json)");
    render->add_option("--scene", ra.scene, "Scene JSON file; other flags override its fields");
    render->add_option("--map", ra.map, "A Tiled map (.tmx, isometric or staggered) to render and light in place of a seeded one");
    render->add_option("--layer", ra.layer,
                       "final (default), light, map, obstacles, opacity, truth (lit by --reference) or difference "
                       "(magenta: lit by the model only; cyan: by the reference only)")
        ->check(CLI::IsMember({"final", "light", "map", "obstacles", "opacity", "truth", "difference"}));
    render->add_option("--reference", ra.reference,
                       "For --layer truth and difference: 3d (default; the sprites' true shapes, lights at their "
                       "height), 3d_facing, exact_line or every_pixel");
    render->add_option("--light", ra.lights,
                       "A light X,Y[,A,B[,RRGGBB]][,h=HEIGHT] in world pixels: its ground point, own half-extents, "
                       "colour and height above the ground (default --light-height) (repeatable)");
    render->add_option("--frames", ra.frames, "Frames to run; the last is written (default 1)")
        ->check(CLI::Range(1, 100000));
    render->add_option("--camera-step", ra.camera_step, "Camera movement per frame DX,DY (pixels)");
    render->add_flag("--stats", ra.stats,
                     "Print each frame's stages: time (ms) and the world rectangle each wrote (WxH at X,Y)");
    render->add_option("--threads", ra.threads, "Threads for the frame's stages, 0: one per core (default 1); the "
                                                "pixels are the same for any count")
        ->check(CLI::Range(0, 256));
    render->add_flag("--no-opacity-correction", ra.no_opacity_correction,
                     "Skip the opacity-map correction (shows the paper's Figure 6 problem)");
    add_param_flags(*render, ra.params);
    render->add_flag("--allow-huge", ra.allow_huge, "Run even when the estimated work is beyond a few seconds");
    render->add_option("--view", ra.view, "World-pixel rectangle X,Y,W,H to render (default: the whole map)");
    render->add_option("--out", ra.out, "Output image (.png or .exr)")->required();

    ParamArgs pa;
    std::string preset_out;
    CLI::App* preset = app.add_subcommand("preset", "Write a preset: a built-in or file, with any parameter changed");
    add_param_flags(*preset, pa);
    preset->add_option("--out", preset_out, "Preset JSON to write (atomically)")->required();

    CheckArgs ca;
    CLI::App* check = app.add_subcommand("check-tileset",
                                         "For every overlay sprite: where its obstacle lands against its anchor, and "
                                         "what the footprint estimate detected (baked ground, baked shadow)");
    check->add_option("manifest", ca.manifest, "Tileset manifest")->required();
    check->add_flag("--json", ca.json, "Print one JSON object: {\"sprites\": [{\"name\", \"obstacle_center\", ...}]}");
    check->add_option("--sheet", ca.sheet,
                      "Write a contact sheet: every sprite with its obstacle (red), its estimated solid's outline "
                      "(yellow) and anchor (cyan)");
    add_param_flags(*check, ca.params);

    CLI::App* params = app.add_subcommand("params", "List the parameters: field, flag, type, range, default, what a change re-runs");

    std::string tileset_out;
    double tileset_scale = 1.0;
    CLI::App* tileset = app.add_subcommand("tileset", "Regenerate the default tileset (deterministic)");
    tileset->add_option("--out", tileset_out, "Folder to write tileset.json, sprites and height maps")->required();
    tileset->add_option("--scale", tileset_scale, "Sprite scale: 1 gives 128x128 sprites")
        ->check(CLI::Range(0.25, 4.0));

    SweepArgs sa;
    CLI::App* sweep = app.add_subcommand("sweep", "Accuracy against time: time and error of every parameter combination");
    sweep->add_option("--scene", sa.scene, "Scene JSON (its camera starts the path; size 0 = whole map)")->required();
    sweep->add_option("--param", sa.params, "NAME=V1,V2,... (repeatable): a preset parameter and its values");
    sweep->add_option("--out", sa.out, "CSV to write")->required();
    sweep->add_option("--chart", sa.chart, "SVG chart of error against time");
    sweep->add_option("--frames", sa.frames, "Frames per run (default 8)")->check(CLI::Range(1, 1000));
    sweep->add_option("--repeats", sa.repeats, "Runs per combination; times are medians (default 3)")
        ->check(CLI::Range(1, 100));
    sweep->add_option("--step", sa.step, "Camera movement per frame DX,DY (default 24,12)");
    sweep->add_flag("--no-carried-light", sa.no_carry, "No light moving with the camera");
    sweep->add_flag("--allow-huge", sa.allow_huge, "Run even when the estimated work is beyond a few minutes");
    sweep->add_flag("--no-opacity-correction", sa.no_opacity_correction,
                    "Measure the model without its opacity correction (the paper's Figure 6)");
    sweep->add_option("--reference", sa.references,
                      "What the error is measured against: every_pixel (default; the model's own 4ab rays), "
                      "exact_line, 3d (the sprites' true shapes) or 3d_facing; a comma list measures each");

    cli::ExportArgs ea;
    CLI::App* export_tiled_cmd = app.add_subcommand("export-tiled", "Write a scene's level as a Tiled map (TMX, TSX, images)");
    export_tiled_cmd->add_option("--scene", ea.scene, "Scene JSON file")->required();
    export_tiled_cmd->add_option("--out", ea.out, "The map to write: DIR/NAME.tmx")->required();
    export_tiled_cmd->add_flag("--images", ea.images, "Also the light texture and the final frame as (hidden) image layers");
    export_tiled_cmd->add_option("--view", ea.view,
                                 "An endless world's view, X,Y,W,H: the window of chunks it needs is the map written");
    export_tiled_cmd->add_option("--infinite", ea.chunk,
                                 "Write an infinite map: tile layers as chunks of N x N tiles (Tiled's own: 16)")
        ->check(CLI::Range(1, 1024))
        ->expected(0, 1)
        ->default_str("16");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "isolux-cli: " << e.what() << " (see isolux-cli --help)\n";
        return 2;
    }
    try {
        if (*render) return run_render(ra);
        if (*sweep) return run_sweep_command(sa);
        if (*check) return run_check_tileset(ca);
        if (*export_tiled_cmd) {
            ea.chunk = export_tiled_cmd->count("--infinite") ? (ea.chunk > 0 ? ea.chunk : 16) : 0;
            return cli::run_export_tiled(ea);
        }
        if (*preset) {
            save_preset(preset_out, params_from_args(pa, Params{}));
            std::cout << "wrote " << preset_out << "\n";
            return 0;
        }
        if (*params) {
            print_param_table();
            return 0;
        }
        if (*tileset) {
            save_generated_tileset(tileset_out, generate_default_tileset(tileset_scale));
            std::cout << "wrote " << tileset_out << "/tileset.json\n";
            return 0;
        }
    } catch (const Error& e) {
        std::cerr << "isolux-cli: " << e.what() << "\n";
        return 2;
    } catch (const std::bad_alloc&) {
        std::cerr << "isolux-cli: out of memory: try a smaller map or --view\n";
        return 2;
    } catch (const std::exception& e) {  // a library's own (a file system error, say): still one line, exit 2
        std::cerr << "isolux-cli: " << printable(e.what()) << "\n";
        return 2;
    }
    return 0;
}

#ifndef ISOLUX_CLI_NO_MAIN
int main(int argc, char** argv) { return isolux_cli_main(argc, argv); }
#endif
