// isolux: the desktop editor and live previewer. GLFW + OpenGL 3.3 core +
// Dear ImGui over isolux::core. With no display it says so and renders the
// scene with the headless renderer instead.
#include <CLI/CLI.hpp>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <thread>

#include "common/assets.hpp"
#include "common/world.hpp"
#include "gui/app.hpp"
#include "gui/overlays.hpp"
#include "gui/window.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/edits.hpp"
#include "isolux/tiled.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/truth.hpp"

using namespace isolux;
using namespace isolux::app;
namespace fs = std::filesystem;

namespace {

// Files dropped on the window, picked up by the frame loop.
std::vector<std::string>* g_dropped = nullptr;
void on_drop(GLFWwindow*, int count, const char** paths) {
    for (int i = 0; g_dropped && i < count; ++i) g_dropped->push_back(paths[i]);
}

// The labels' font: one with the glyphs they use (Δ, ×, ², arrows), from
// Debian's fonts-dejavu-core; ISOLUX_FONT names another. Without it ImGui's
// built-in font draws those as '?', and the status bar says so.
std::string load_label_font(ImGuiIO& io) {
    static const ImWchar ranges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x206F, 0x2190, 0x21FF, 0x2200, 0x22FF, 0};
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("ISOLUX_FONT")) candidates.push_back(env);
    candidates.push_back("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
    for (const std::string& path : candidates) {
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) continue;
        if (io.Fonts->AddFontFromFileTTF(path.c_str(), 15.0f, nullptr, ranges)) return "";
    }
    return "no label font found (install fonts-dejavu-core or set ISOLUX_FONT): symbols such as Δ show as '?'";
}

// The character's sprite as a GL texture (straight alpha, as ImGui draws).
void upload_character(App& app) {
    const Sprite s = generate_character_sprite();
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, s.image.width, s.image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 s.image.rgba.data());
    app.character_tex = tex;
    app.character_w = s.image.width;
    app.character_h = s.image.height;
    app.character_ax = s.anchor_x;
    app.character_ay = s.anchor_y;
}

// No display: the same scene through core's CPU frame, written as a PNG.
int render_headless(const Scene& scene, const std::string& scene_name, const std::string& out, const std::string& why) {
    std::cerr << "isolux: " << why << ": the editor needs a display.\n"
              << "isolux: rendering the scene with the headless renderer instead (the same as isolux-cli render)\n";
    World w = build_world(scene);
    // isolux-cli's budgets: the view's pixels and the tracing work.
    const Rect view = camera_view(scene.camera, w);
    if ((long long)view.w * view.h > max_render_pixels)
        throw Error(scene_name + ": camera: the view is " + std::to_string(view.w) + "x" + std::to_string(view.h) +
                    " pixels, over the 256-megapixel limit: render parts with isolux-cli --view X,Y,W,H");
    if (trace_work(scene, view) > huge_trace_steps)
        throw Error(scene_name + ": this render would trace minutes or more: isolux-cli render --allow-huge runs it anyway");
    FrameState st;
    render_frame(st, w, scene, scene.camera, 0);
    save_image(out, st.final);
    std::cerr << "isolux: wrote " << out << " (" << st.final.width << "x" << st.final.height
              << "). For more, run isolux-cli render --help.\n";
    return 0;
}

// save-stats: each stage's mean time over the frames the Stats panel keeps
// (the last Stats::frames), as the panel plots them: the core's CPU stages
// by Stage name, the renderer's GPU stages apart.
std::string stats_json(const Stats& s) {
    const int n = int(std::min<long>(s.recorded, Stats::frames));
    auto mean = [&](int series) {
        double sum = 0;
        for (int i = 0; i < n; ++i) sum += s.ms[std::size_t(series)][std::size_t((s.head - 1 - i + Stats::frames) % Stats::frames)];
        return n > 0 ? sum / n : 0.0;
    };
    nlohmann::json cpu = nlohmann::json::object(), gpu = nlohmann::json::object();
    for (int k = 0; k < stage_count; ++k) cpu[std::string(to_string(Stage(k)))] = mean(k);
    const char* gpu_names[] = {"upload", "sprites", "blur", "composite"};
    for (int k = 0; k < 4; ++k) gpu[gpu_names[k]] = mean(stage_count + k);
    nlohmann::json j = {{"frames", n}, {"frame_ms", s.frame_ms}, {"tracer", s.tracer}, {"lights_traced", s.lights_traced},
                        {"cpu_ms", cpu}, {"gpu_ms", gpu}};
    return j.dump(2) + "\n";
}

void run_script_step(App& app) {
    if (!app.script) return;
    Script& s = *app.script;
    ImGuiIO& io = ImGui::GetIO();
    // The GLFW backend reads the real pointer every frame: put the scripted
    // one back, so a press and its release land on the same widget.
    if (s.has_mouse) io.MousePos = ImVec2(s.mouse_x, s.mouse_y);
    auto move_to = [&](double x, double y) {
        s.has_mouse = true;
        s.mouse_x = float(x);
        s.mouse_y = float(y);
        io.MousePos = ImVec2(s.mouse_x, s.mouse_y);
    };
    if (s.release >= 0) {
        io.MouseDown[s.release] = false;
        s.release = -1;
    }
    if (s.key_up >= 0) {
        io.KeysDown[s.key_up] = false;
        io.KeyCtrl = false;
        io.KeyShift = false;
        s.key_up = -1;
    }
    if (!s.drag_path.empty()) {
        // The GLFW backend resets the buttons from the real mouse each frame:
        // hold the button for the whole drag.
        io.MouseDown[0] = true;
        move_to(s.drag_path.front().first, s.drag_path.front().second);
        s.drag_path.erase(s.drag_path.begin());
        if (s.drag_path.empty()) s.release = 0;
        return;
    }
    if (s.move_lights > 0) {
        // The document's lights themselves move (no undo step per frame: an animation, not an edit).
        const double dx = s.move_lights % 2 ? 1 : -1;
        for (Light& l : app.editor.scene.lights) l.x += dx;
        --s.move_lights;
        return;
    }
    if (s.wait > 0) {
        --s.wait;
        return;
    }
    if (s.waiting_sweep) {
        if (app.accuracy.running) return;
        s.waiting_sweep = false;
    }
    if (s.next >= s.steps.size()) return;
    const ScriptStep& step = s.steps[s.next++];
    auto num = [&](int i) { return std::stod(step.args[i]); };
    Editor& e = app.editor;
    if (step.op == "wait") s.wait = int(num(0));
    else if (step.op == "click" || step.op == "rclick") {
        const int button = step.op == "click" ? 0 : 1;
        move_to(num(0), num(1));
        io.MouseDown[button] = true;
        s.release = button;
    } else if (step.op == "drag") {
        move_to(num(0), num(1));
        io.MouseDown[0] = true;
        for (int i = 1; i <= 4; ++i)
            s.drag_path.push_back({num(0) + (num(2) - num(0)) * i / 4, num(1) + (num(3) - num(1)) * i / 4});
    } else if (step.op == "key") {
        std::string k = step.args[0];
        if (k.rfind("ctrl+", 0) == 0) {
            io.KeyCtrl = true;
            k = k.substr(5);
        }
        int code = -1;
        if (k.rfind("shift+", 0) == 0) {
            io.KeyShift = true;
            k = k.substr(6);
        }
        if (k.size() == 1 && std::isalpha(unsigned(k[0]))) code = GLFW_KEY_A + (std::toupper(unsigned(k[0])) - 'A');
        else if (k.size() == 1 && std::isdigit(unsigned(k[0]))) code = GLFW_KEY_0 + (k[0] - '0');
        else if (k == "f1") code = GLFW_KEY_F1;
        else if (k == "escape") code = GLFW_KEY_ESCAPE;
        else if (k == "delete") code = GLFW_KEY_DELETE;
        else if (k == "home") code = GLFW_KEY_HOME;
        else if (k == "enter") code = GLFW_KEY_ENTER;
        else if (k == "tab") code = GLFW_KEY_TAB;
        if (code >= 0) {
            io.KeysDown[code] = true;
            s.key_up = code;
        }
    } else if (step.op == "inspect" || step.op == "footprint") {
        int found = -1;
        for (int i = 0; i < int(e.world.tileset.sprites.size()); ++i)
            if (e.world.tileset.sprites[std::size_t(i)].name == step.args[0]) found = i;
        if (found < 0) {
            set_status(e, "script: no sprite \"" + step.args[0] + "\"", true);
        } else if (step.op == "inspect") {
            app.ui.inspector_open = true;
            app.ui.inspector_sprite = found;
        } else {
            try {
                set_sprite_footprint(e, found, parse_footprint(step.args[1], "script footprint"));
            } catch (const Error& err) {
                set_status(e, err.what(), true);
            }
        }
    } else if (step.op == "tool") {
        bool found = false;
        for (const ToolInfo& t : tool_table())
            if (step.args[0] == t.name) e.brush.tool = t.tool, found = true;
        if (!found) set_status(e, "script: no tool \"" + step.args[0] + "\"", true);
    } else if (step.op == "brush") {
        // brush floor NAME | brush overlay NAME | brush tag TAG
        if (step.args[0] == "tag") {
            e.brush.overlay_tag = step.args[1];
        } else {
            int found = -1;
            for (int i = 0; i < int(e.world.tileset.sprites.size()); ++i)
                if (e.world.tileset.sprites[std::size_t(i)].name == step.args[1] && found < 0) found = i;
            if (found < 0) set_status(e, "script: no sprite \"" + step.args[1] + "\"", true);
            else if (step.args[0] == "floor") e.brush.floor = found;
            else e.brush.overlay = found, e.brush.overlay_tag.clear();
        }
    } else if (step.op == "view") {
        e.view.x = num(0);
        e.view.y = num(1);
        e.view.zoom = std::clamp(num(2), min_zoom, max_zoom);
        e.fit_pending = false;
    } else if (step.op == "click-tile" || step.op == "drag-tiles") {
        // Window pixels of a tile's centre in the current view.
        auto tile_screen = [&](int col, int row) {
            int cx = 0, cy = 0;
            const Map& m = e.world.map;
            tile_center(m.layout, m.tile_width, m.tile_height, col, row, cx, cy);
            return std::pair<double, double>{(cx + e.world.placed.shift_x - e.view.x) * e.view.zoom,
                                             (cy + e.world.placed.shift_y - e.view.y) * e.view.zoom};
        };
        const auto [x0, y0] = tile_screen(int(num(0)), int(num(1)));
        move_to(x0, y0);
        io.MouseDown[0] = true;
        if (step.op == "click-tile") {
            s.release = 0;
        } else {
            const auto [x1, y1] = tile_screen(int(num(2)), int(num(3)));
            for (int i = 1; i <= 8; ++i) s.drag_path.push_back({x0 + (x1 - x0) * i / 8, y0 + (y1 - y0) * i / 8});
        }
    } else if (step.op == "show") {
        const std::string& n = step.args[0];
        if (n == "accuracy") app.accuracy.open = true;
        else if (n == "inspector") app.ui.inspector_open = true;
        else if (n == "help") app.ui.help_open = true;
        else if (n == "stats") e.settings.show_stats = true;
        else set_status(e, "script: no panel \"" + n + "\"", true);
    } else if (step.op == "new") {
        new_scene(e, app.now);
    } else if (step.op == "fit") {
        e.fit_pending = true;
    } else if (step.op == "open-dropped") {
        app.ui.dropped.push_back(step.args[0]);
    } else if (step.op == "check-glyphs") {
        // Every character of the argument must have a glyph in the label font.
        const ImFont* font = ImGui::GetFont();
        const std::string& t = step.args[0];
        for (std::size_t i = 0; i < t.size();) {
            unsigned int c = 0;
            const int n = ImTextCharFromUtf8(&c, t.c_str() + i, t.c_str() + t.size());
            i += std::size_t(std::max(1, n));
            if (!font->FindGlyphNoFallback(ImWchar(c))) {
                std::cerr << "isolux: the label font has no glyph for U+" << std::hex << c << std::dec << "\n";
                app.exit_code = 3;
            }
        }
    } else if (step.op == "dump-panels") {
        // Every ImGui window's rectangle, as JSON lines: what the layout test reads.
        std::string out;
        ImGuiContext& g = *ImGui::GetCurrentContext();
        for (ImGuiWindow* w : g.Windows) {
            if (!w->Active || w->Hidden || (w->Flags & ImGuiWindowFlags_ChildWindow) || w->Name[0] == '#') continue;
            out += "{\"name\": \"" + std::string(w->Name) + "\", \"x\": " + std::to_string(w->Pos.x) +
                   ", \"y\": " + std::to_string(w->Pos.y) + ", \"w\": " + std::to_string(w->Size.x) +
                   ", \"h\": " + std::to_string(w->Size.y) + "}\n";
        }
        out += "{\"window\": [" + std::to_string(app.window_w) + ", " + std::to_string(app.window_h) + "]}\n";
        try {
            write_file_atomic(step.args[0], out);
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    } else if (step.op == "move-lights") {
        s.move_lights = int(num(0));
    } else if (step.op == "save-stats") {
        try {
            write_file_atomic(step.args[0], stats_json(app.stats));
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    } else if (step.op == "export-final") {
        export_image(app, "final", step.args[0]);
    } else if (step.op == "export-tiled") {
        try {
            export_tiled(e.world, e.scene, step.args[0]);
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    } else if (step.op == "select") {
        // select I[,J...] (1-based, as the panel numbers them)
        select_light(e, -1);
        std::string list = step.args[0];
        for (std::size_t pos = 0; pos <= list.size();) {
            const std::size_t end = std::min(list.find(',', pos), list.size());
            const int i = std::atoi(list.substr(pos, end - pos).c_str()) - 1;
            select_light(e, i, true);
            pos = end + 1;
        }
    } else if (step.op == "character") {
        e.character.enabled = step.args[0] == "on";
        if (step.args.size() > 2) e.character.x = num(1), e.character.y = num(2);
        e.character.follow = false;
    } else if (step.op == "save-footprints") {
        save_footprints(e);
    } else if (step.op == "window-shot") {
        s.window_shot = step.args[0];
    } else if (step.op == "type") {
        for (char c : step.args[0]) io.AddInputCharacter(unsigned(c));
    } else if (step.op == "param") {
        // A widget moved and released: the same edit the panel makes. Any
        // row of the parameter table, by its field name and value text.
        Params p = e.scene.params;
        try {
            set_param(p, step.args[0], step.args[1], "script param");
            set_params(e, p, app.now);
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    } else if (step.op == "save-preset") export_preset(e, step.args[0]);
    else if (step.op == "save-scene") save_scene_to(e, step.args[0]);
    else if (step.op == "load-scene") load_scene_from(e, step.args[0], app.now);
    else if (step.op == "load-preset") import_preset(e, step.args[0], app.now);
    else if (step.op == "quit") s.quit = true;
    else if (step.op == "overlay") {
        const bool on = step.args[1] == "on";
        Overlays& o = e.overlays;
        const std::string& n = step.args[0];
        if (n == "obstacles") o.obstacles = on;
        else if (n == "opacity_maps") o.opacity_maps = on;
        else if (n == "delta_y_bands") o.delta_y_bands = on;
        else if (n == "light_areas") o.light_areas = on;
        else if (n == "raw_light") o.raw_light = on;
        else if (n == "split_view") o.split_view = on;
        else if (n == "split_with_3d") o.split_with_3d = on;
        else if (n == "truth_light") o.truth_light = on;
        else if (n == "truth_difference") o.truth_difference = on;
        else if (n == "heatmap") app.accuracy.heatmap = on, app.accuracy.heatmap_stale = true;
    } else if (step.op == "sweep") {
        AccuracyPanel& a = app.accuracy;
        for (std::size_t i = 0; i < 4; ++i) a.axes[i] = i < step.args.size() ? step.args[i] : "";
        a.frames = 2;
        a.repeats = 1;
        a.open = true;
        if (!start_sweep(app, a)) {
            set_status(e, a.error, true);
            std::cerr << "isolux: " << a.error << "\n";  // a script has no one to read the status bar
        }
    } else if (step.op == "wait-sweep") s.waiting_sweep = true;
    else if (step.op == "long-work") {
        if (step.args[0] == "undo" || step.args[0] == "trace" || step.args[0] == "cancel") app.huge.script_answer = step.args[0];
        else set_status(e, "script line " + std::to_string(step.line) + ": long-work undo|trace|cancel", true);
    }
    else if (step.op == "apply-point") apply_sweep_point(app, app.accuracy, std::size_t(num(0)));
    else if (step.op == "save-sweep") {
        try {
            write_file_atomic(step.args[0], sweep_csv(app.accuracy.result_axes, app.accuracy.results));
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    }
}

// The tracer the setting asks for (config.hpp: Settings::tracer): the GPU's
// compute shader for "gpu", and for "auto" when the driver is not a software
// rasteriser; the CPU otherwise, or when the GPU one is not available.
bool gpu_tracer_chosen(const App& app) {
    const std::string& want = app.tracer_override.empty() ? app.editor.settings.tracer : app.tracer_override;
    if (!app.gpu_tracer.program || want == "cpu") return false;
    return want == "gpu" || !gpu_tracer_is_software(app.gpu_tracer);
}

LightTracer chosen_tracer(App& app) {
    if (!gpu_tracer_chosen(app)) return {};
    return [&app](const Mask& obstacles, std::uint64_t revision, const std::vector<LightMask*>& masks, const Params& p) {
        return gpu_trace(app.gpu_tracer, obstacles, revision, masks, p) ? std::string_view("gpu") : std::string_view();
    };
}

// One frame's figures: the stages that ran, their times, and the frame's own
// time (the pipeline's, `frame_ms`) and rate (the whole loop's, `dt`).
void push_stats(App& app, const FrameReport& rep, double frame_ms, double dt) {
    Stats& s = app.stats;
    for (int k = 0; k < stage_count; ++k) s.ms[k][s.head] = float(rep.ms[k]);
    const GpuTimes& g = app.renderer.times;
    const Renderer::Ran& ran = app.renderer.ran;
    s.ms[stage_count + 0][s.head] = rep.retraced ? float(g.upload) : 0.0f;
    s.ms[stage_count + 1][s.head] = ran.sprites ? float(g.sprites) : 0.0f;
    s.ms[stage_count + 2][s.head] = ran.blur ? float(g.blur) : 0.0f;
    s.ms[stage_count + 3][s.head] = ran.composite ? float(g.composite) : 0.0f;
    s.gpu_ran = {rep.retraced, ran.sprites, ran.blur, ran.composite};
    s.head = (s.head + 1) % Stats::frames;
    ++s.recorded;
    s.last_ran = rep.ran;
    s.lights_traced = rep.lights_traced;
    if (!rep.tracer.empty()) s.tracer = std::string(rep.tracer);
    if (!rep.rebuilt.empty()) s.last_rebuilt = rep.rebuilt;
    s.frame_ms = s.frame_ms * 0.9f + float(frame_ms) * 0.1f;
    if (dt > 0) s.fps = s.fps * 0.9f + float(1.0 / dt) * 0.1f;
}

// The 3D reference over the view (truth.hpp), kept while the scene's
// parameters, lights, view and world are the same. Null (and the status
// says why) when it cannot be made, e.g. a tileset without shapes.
const LightTexture* update_truth(App& app, const Scene& scene) {
    App::Truth& t = app.truth;
    const Editor& e = app.editor;
    if (t.valid && t.params == scene.params && t.lights == scene.lights && t.view == app.view &&
        t.revision == e.world.revision)
        return &t.texture;
    try {
        t.texture = reference_texture(e.world, scene, app.view, Reference::three_d);
    } catch (const Error& err) {
        set_status(app.editor, err.what(), true);
        app.editor.overlays.truth_light = app.editor.overlays.truth_difference = false;
        app.editor.overlays.split_with_3d = false;
        t.valid = false;
        return nullptr;
    }
    t.valid = true;
    t.params = scene.params;
    t.lights = scene.lights;
    t.view = app.view;
    t.revision = e.world.revision;
    app.split_texture_holds = 0;  // upload it again
    return &t.texture;
}

// The CLI's budget in the app: a frame whose tracing is estimated beyond
// huge_trace_steps is not traced until the user says so (the prompt in
// panels.cpp: trace it, or undo the change). A script undoes the change and
// says why; a screenshot run stops with the CLI's message and exit code 2.
bool work_allowed(App& app, const Scene& scene, bool screenshot_mode) {
    App::HugeWork& h = app.huge;
    const double steps = trace_work(scene, app.view);
    if (steps <= huge_trace_steps) return true;
    if (h.approved && h.approved_params == scene.params && scene.lights.size() <= h.approved_lights) return true;
    if (h.declined && h.declined_params == scene.params) return false;
    char text[200];
    std::snprintf(text, sizeof text, "this frame would trace about %.2g ray steps (minutes or more)", steps);
    if (screenshot_mode) {
        std::cerr << "isolux: " << text << ": use a smaller area, border rays or fewer lights (isolux-cli has --allow-huge)\n";
        app.exit_code = 2;
        app.quit = true;
        return false;
    }
    if (app.script && h.script_answer != "undo") {  // as if "Trace it" were pressed
        h.approved = true;
        h.approved_params = scene.params;
        h.approved_lights = scene.lights.size();
        return true;
    }
    if (app.script) {
        undo(app.editor, app.now);
        set_status(app.editor, std::string(text) + ": the change was undone", true);
        std::cerr << "isolux: " << text << ": the change was undone\n";
        return false;
    }
    h.asking = true;
    h.steps = steps;
    return false;
}

// Approved long work (work_allowed): render_frame on a worker thread with
// the CPU tracer, which Cancel can stop. Returns true with the frame's report
// once it is done; false while it runs (the main loop then draws only its
// progress) and when it was cancelled or failed (the last frame stays, and
// these parameters are not traced again until they change). A frame that
// reuses its cached trace ends at once: the first moments are waited for
// here, so such frames never show the progress.
bool run_long_trace(App& app, const Scene& scene, const Camera& cam, FrameReport& rep) {
    App::LongTrace& job = app.long_trace;
    Editor& e = app.editor;
    if (!job.worker.joinable()) {
        job.cancel = false;
        job.finished = false;
        job.done = 0;
        job.total = trace_work(scene, app.view);
        job.started = app.now;
        job.cancelled = false;
        job.error.clear();
        e.frame.options.tracer = {};  // the CPU's, which checks for Cancel
        e.frame.options.control = TraceControl{&job.cancel, &job.done};
        job.worker = std::thread([&app, scene, cam, frame = e.frame_number] {
            App::LongTrace& j = app.long_trace;
            const auto t0 = std::chrono::steady_clock::now();
            try {
                j.report = render_frame(app.editor.frame, app.editor.world, scene, cam, frame);
            } catch (const Cancelled&) {
                j.cancelled = true;
            } catch (const Error& err) {
                j.error = err.what();
            } catch (const std::bad_alloc&) {
                j.error = "out of memory tracing this frame: use a smaller area or fewer lights";
            }
            j.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            j.finished = true;
        });
        for (int ms = 0; ms < 200 && !job.finished; ++ms) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (!job.finished) return false;
    job.worker.join();
    e.frame.options.control = {};
    const double seconds = job.seconds;
    char text[200];
    if (job.cancelled || !job.error.empty()) {
        App::HugeWork& h = app.huge;
        h.approved = false;
        h.declined = true;
        h.declined_params = scene.params;
        if (job.cancelled)
            std::snprintf(text, sizeof text, "long work cancelled at %.0f%% after %.1f s: the last frame stays until the parameters change",
                          100 * std::min(1.0, double(job.done) / std::max(1.0, job.total)), seconds);
        set_status(e, job.cancelled ? text : job.error, true);
        std::cerr << "isolux: " << (job.cancelled ? text : job.error) << "\n";
        return false;
    }
    if (job.report.lights_traced > 0)
        std::cout << "isolux: long work done: " << job.report.lights_traced << " lights traced in " << std::fixed << std::setprecision(2) << seconds << std::defaultfloat << " s\n";
    rep = job.report;
    return true;
}

// Stops a long trace the window is closing on (its work is thrown away).
void stop_long_trace(App& app) {
    App::LongTrace& job = app.long_trace;
    if (!job.worker.joinable()) return;
    job.cancel = true;
    job.worker.join();
    app.editor.frame.options.control = {};
}

// A screenshot's view is the scene's camera: as in isolux-cli, at most
// max_render_pixels, and no side beyond what the GPU's textures hold.
bool screenshot_view_fits(App& app) {
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    const Rect v = app.view;
    if ((long long)v.w * v.h <= max_render_pixels && v.w <= max_side && v.h <= max_side) return true;
    const std::string scene = !app.scene_arg.empty()                ? app.scene_arg
                              : !app.editor.scene_path.empty() ? app.editor.scene_path.string()
                                                               : std::string("the scene");
    std::cerr << "isolux: " << scene << ": camera: shows " << v.w << "x" << v.h << " pixels, over the 256-megapixel limit or "
              << "this GPU's " << max_side << "-pixel texture side: set a smaller camera, or render parts with "
              << "isolux-cli --view X,Y,W,H\n";
    app.exit_code = 2;
    app.quit = true;
    return false;
}

// One frame of the pipeline: core traces (CPU), the renderer does the rest.
FrameReport render(App& app, bool screenshot_mode) {
    Editor& e = app.editor;
    renderer_set_world(app.renderer, e.world);
    const Scene scene = render_scene(e);
    Camera cam;
    if (screenshot_mode) {
        cam = scene_to_save(e).camera;  // width 0: the whole map, as isolux-cli renders it
        app.view = camera_view(cam, e.world);
        app.view_x = app.view_y = 0;
    } else {
        const double vw = std::ceil(app.window_w / e.view.zoom) + 1, vh = std::ceil(app.window_h / e.view.zoom) + 1;
        cam = {e.view.x, e.view.y, int(vw), int(vh)};
        app.view = camera_view(cam, e.world);
        app.view_x = (app.view.x - e.view.x) * e.view.zoom;
        app.view_y = (app.view.y - e.view.y) * e.view.zoom;
    }
    if (screenshot_mode && !screenshot_view_fits(app)) return FrameReport{};
    if (!work_allowed(app, scene, screenshot_mode)) return FrameReport{};  // the last frame stays
    e.frame.options.tracer = chosen_tracer(app);
    FrameReport rep;
    if (app.long_trace.worker.joinable() || trace_work(scene, app.view) > huge_trace_steps) {
        if (!run_long_trace(app, scene, cam, rep)) return FrameReport{};
    } else {
        rep = render_frame(e.frame, e.world, scene, cam, e.frame_number);
    }
    if (rep.retraced) renderer_upload_light(app.renderer, e.frame.traced, rep.dirty);  // only what changed
    CompositeOptions opts;
    opts.show_light = e.overlays.raw_light;
    const Overlays& ov = e.overlays;
    const bool want_truth = ov.truth_light || ov.truth_difference || (ov.split_view && ov.split_with_3d);
    const LightTexture* truth = want_truth ? update_truth(app, scene) : nullptr;
    // The renderer's second light texture: the 3D reference, or flat lighting.
    auto hold_truth = [&] {
        if (app.split_texture_holds != 2) renderer_upload_flat_light(app.renderer, *truth);
        app.split_texture_holds = 2;
    };
    if (truth && ov.truth_light) {
        hold_truth();
        opts.show_light = true;
        opts.split = 0;  // all of the view reads the second texture
    } else if (ov.split_view && truth && ov.split_with_3d) {
        hold_truth();
        opts.split = int(app.view.w * ov.split);
    } else if (ov.split_view) {
        Scene flat = scene;
        flat.params.mode = Mode::flat;
        app.flat_frame.options = e.frame.options;
        if (app.split_texture_holds != 1) app.flat_frame = FrameState{e.frame.options};  // retrace into it
        FrameReport fr = render_frame(app.flat_frame, e.world, flat, cam, e.frame_number);
        if (fr.retraced || app.split_texture_holds != 1) renderer_upload_flat_light(app.renderer, app.flat_frame.traced);
        app.split_texture_holds = 1;
        opts.split = int(app.view.w * ov.split);
    }
    // Overlays: rebuilt only when what they show changed.
    const Rect region = {app.view.x - 64, app.view.y - 64, app.view.w + 128, app.view.h + 128};
    const bool overlay_stale = !(app.overlay_key == e.overlays) || !(app.overlay_params == scene.params) ||
                               (ov.truth_difference && rep.retraced) ||
                               app.overlay_lights != scene.lights || rep.ran_stage(Stage::obstacle_map) ||
                               !(intersect(app.overlay_region, app.view) == app.view) || app.overlay_dirty;
    AccuracyPanel& acc = app.accuracy;
    const bool settings_changed = !(app.overlay_params == scene.params) || app.overlay_lights != scene.lights;
    if (acc.heatmap) {
        // The heat map replaces the other overlays while it is on; it is
        // recomputed (two CPU frames) only when the settings or view change.
        if (acc.heatmap_stale || settings_changed || !(acc.heat.rect == app.view)) {
            acc.heat = error_heatmap(e.world, scene, app.view, acc.reference, &acc.heat_metrics);
            acc.heatmap_stale = false;
            renderer_upload_overlay(app.renderer, acc.heat.image, acc.heat.rect);
        }
        app.overlay_params = scene.params;
        app.overlay_lights = scene.lights;
        app.overlay_dirty = true;  // rebuild the others when it is turned off
    } else if (overlay_stale) {
        OverlayImage o = build_overlays(e.world, e.frame, scene, e.overlays, region, truth);
        renderer_upload_overlay(app.renderer, o.image, o.rect);
        app.overlay_key = e.overlays;
        app.overlay_params = scene.params;
        app.overlay_lights = scene.lights;
        app.overlay_region = region;
        app.overlay_dirty = false;
    }
    renderer_draw(app.renderer, app.view, scene.params, opts);
    renderer_present(app.renderer, app.window_w, app.window_h, app.view_x, app.view_y, e.view.zoom, app.view);
    ++e.frame_number;
    return rep;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App cli{"isolux: level editor and lighting previewer for seeded isometric maps"};
    std::string scene_file, seed, screenshot, script_file, size, tracer_choice, headless_out = "isolux.png";
    long frames = 0;
    int width = 1600, height = 900;
    cli.add_option("--scene", scene_file, "Scene JSON to open");
    cli.add_option("--seed", seed, "Map seed (default \"isolux\")");
    cli.add_option("--size", size, "Map size WxH in tiles");
    cli.add_option("--frames", frames, "Render N frames, then quit (with --screenshot)")->check(CLI::Range(1L, 1000000L));
    cli.add_option("--screenshot", screenshot, "Write the final frame (the viewport, no panels) to this PNG");
    cli.add_option("--script", script_file, "Scripted input, one command a frame (see app/gui/script.hpp)");
    cli.add_option("--tracer", tracer_choice, "auto, cpu or gpu: which tracer to run (overrides View › Tracer)")
        ->check(CLI::IsMember({"auto", "cpu", "gpu"}));
    cli.add_option("--headless-out", headless_out, "With no display: where the headless render goes (default isolux.png)");
    cli.add_option("--width", width, "Window width")->check(CLI::Range(320, 8192));
    cli.add_option("--height", height, "Window height")->check(CLI::Range(240, 8192));
    try {
        cli.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return cli.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "isolux: " << e.what() << " (see isolux --help)\n";
        return 2;
    }

    Scene scene;
    try {
        if (!scene_file.empty()) scene = load_scene(scene_file);
        if (!seed.empty()) scene.seed = seed;
        if (!size.empty()) {
            int w = 0, h = 0;
            if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > max_map_side ||
                h > max_map_side)
                throw Error("--size \"" + size + "\": expected WxH with sides in [1, " +
                            std::to_string(max_map_side) + "]");
            scene.width = w, scene.height = h;
        }
        if (scene_file.empty() && seed.empty() && size.empty()) {
            // The default: the default seed and assets, lit as the README shows.
            fs::path def = default_tileset_manifest();
            fs::path demo = def.empty() ? fs::path() : def.parent_path().parent_path() / "scenes" / "default.json";
            if (!demo.empty() && fs::exists(demo)) scene = load_scene(demo);
        }
    } catch (const Error& err) {
        std::cerr << "isolux: " << err.what() << "\n";
        return 2;
    }

    const bool screenshot_mode = !screenshot.empty();
    std::string why;
    GLFWwindow* window = open_window(width, height, !screenshot_mode, why);
    if (!window) {
        try {
            return render_headless(scene, scene_file.empty() ? "the default scene" : scene_file,
                                   screenshot.empty() ? headless_out : screenshot, why);
        } catch (const Error& err) {
            std::cerr << "isolux: " << err.what() << "\n";
            return 2;
        }
    }

    App app;
    app.scene_arg = scene_file;
    app.screenshot_frames = frames > 0 ? frames : 1;
    const fs::path config = config_dir();
    try {
        app.editor = make_editor(scene, config);
        if (!script_file.empty()) app.script = load_script(script_file);
        // Scripts place their clicks in a known view: it starts at the scene's
        // camera (the origin, zoom 1) until the script says `fit` or `view`.
        if (app.script) app.editor.fit_pending = false;
    } catch (const Error& err) {
        std::cerr << "isolux: " << err.what() << "\n";
        close_window(window);
        return 2;
    }
    const bool had_recovery = has_recovery(app.editor);  // an earlier session's unsaved work
    if (!screenshot_mode && !app.script && had_recovery) app.ui.recovery_offered = true;

    std::string error;
    if (!renderer_init(app.renderer, error)) {
        std::cerr << "isolux: " << error << "\n";
        close_window(window);
        return 1;
    }
    app.tracer_override = tracer_choice;
    if (!gpu_tracer_init(app.gpu_tracer, app.gpu_tracer_error)) gpu_tracer_free(app.gpu_tracer);
    std::cout << "isolux: tracer: " << (gpu_tracer_chosen(app) ? "gpu" : "cpu") << " (setting "
              << (tracer_choice.empty() ? app.editor.settings.tracer : tracer_choice) << "; GPU tracer "
              << (app.gpu_tracer.program ? "on " + app.gpu_tracer.renderer : "unavailable: " + app.gpu_tracer_error)
              << ")\n";

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    static std::string ini;
    std::error_code ec;
    fs::create_directories(config, ec);
    ini = (config / "imgui.ini").string();
    io.IniFilename = (screenshot_mode || app.script) ? nullptr : ini.c_str();  // layout kept per user
    ImGui::StyleColorsDark();
    app.font_warning = load_label_font(io);
    if (!app.font_warning.empty()) set_status(app.editor, app.font_warning, true);
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    g_dropped = &app.ui.dropped;
    glfwSetDropCallback(window, on_drop);
    upload_character(app);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    auto start = std::chrono::steady_clock::now();
    auto last = start;
    double reload_check = 0;
    long frames_run = 0;
    while (!app.quit) {
        glfwPollEvents();
        if (glfwWindowShouldClose(window)) {
            stop_long_trace(app);  // its work is thrown away; the last frame stays
            // Closing the window asks about unsaved work first (scripted
            // and screenshot runs close at once).
            if (screenshot_mode || app.script || app.ui.quit_confirmed) break;
            glfwSetWindowShouldClose(window, GLFW_FALSE);
            guard_unsaved(app, "quitting", [&app] {
                app.ui.quit_confirmed = true;
                app.quit = true;
            });
            if (app.quit) break;
        }
        const auto t = std::chrono::steady_clock::now();
        const double dt = std::chrono::duration<double>(t - last).count();
        last = t;
        app.now = std::chrono::duration<double>(t - start).count();
        glfwGetFramebufferSize(window, &app.window_w, &app.window_h);
        if (app.now >= reload_check) {
            renderer_reload_shaders(app.renderer);  // hot reload; errors show in the status bar
            reload_check = app.now + 0.5;
        }
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        // While approved long work runs, its worker reads the document: the
        // window shows only its progress, and input, scripts and dropped
        // files wait.
        const bool busy = app.long_trace.running();
        if (!busy) run_script_step(app);
        ImGui::NewFrame();
        if (busy) {
            renderer_present(app.renderer, app.window_w, app.window_h, app.view_x, app.view_y, app.editor.view.zoom,
                             app.view);
            long_work_prompt(app);
            ImGui::Render();
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            glfwSwapBuffers(window);
            autosave_tick(app.editor, app.now);
            continue;
        }
        for (const std::string& path : std::vector<std::string>(std::move(app.ui.dropped))) {
            FileKind kind;
            try {
                kind = detect_file_kind(path);
            } catch (const Error& err) {
                set_status(app.editor, err.what(), true);
                continue;
            }
            const RecentFile file{path, kind};
            // A dropped scene replaces the document: ask first when it is unsaved.
            if (kind == FileKind::scene)
                guard_unsaved(app, "opening " + fs::path(path).filename().string(),
                              [&app, file] { open_recent(app.editor, file, app.now); });
            else
                open_recent(app.editor, file, app.now);
        }
        app.ui.dropped.clear();
        if (!screenshot_mode) {
            fit_map(app);
            handle_viewport_input(app, dt);
        }
        const auto f0 = std::chrono::steady_clock::now();
        const FrameReport rep = render(app, screenshot_mode);
        if (app.quit) {  // refused (work beyond the budget in a screenshot run)
            ImGui::EndFrame();
            break;
        }
        if (app.long_trace.running()) long_work_prompt(app);  // just started: nothing else edits the document now
        else {
            push_stats(app, rep, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - f0).count(), dt);
            if (!screenshot_mode) draw_panels(app);
        }
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (app.script && !app.script->window_shot.empty()) {
            try {
                save_image(app.script->window_shot, renderer_read_window(app.window_w, app.window_h));
            } catch (const Error& err) {
                set_status(app.editor, err.what(), true);
            }
            app.script->window_shot.clear();
        }
        glfwSwapBuffers(window);
        const std::string title = window_title(app.editor);
        if (title != app.ui.title) {
            glfwSetWindowTitle(window, title.c_str());
            app.ui.title = title;
        }
        autosave_tick(app.editor, app.now);
        ++frames_run;
        if (screenshot_mode && frames_run >= app.screenshot_frames) {
            try {
                save_image(screenshot, renderer_read_final(app.renderer));
                std::cout << "isolux: wrote " << screenshot << " after " << frames_run << " frames\n";
            } catch (const Error& err) {
                std::cerr << "isolux: " << err.what() << "\n";
                app.exit_code = 2;
            }
            break;
        }
        if (app.script && app.script->quit) break;
        if (app.script && app.script->next >= app.script->steps.size() && app.script->wait == 0 &&
            app.script->release < 0 && app.script->drag_path.empty() && frames > 0 && frames_run >= frames)
            break;
    }
    stop_long_trace(app);
    try {
        save_settings(config, app.editor.settings);
    } catch (const Error&) {
    }
    // A clean exit: unsaved work stays in the autosave only if it was dirty.
    // An autosave from an earlier crash is deleted only once its recovery was
    // offered and answered: never by a screenshot or script run, nor when the
    // window closes with the prompt still showing.
    const bool recovery_unanswered = app.ui.recovery_offered || ((screenshot_mode || app.script) && had_recovery);
    if (recovery_unanswered) {
        // Leave the earlier session's work where the next start offers it.
    } else if (app.editor.dirty) {
        app.editor.autosave_due = 0;
        autosave_tick(app.editor, 1e300);
    } else {
        discard_autosave(app.editor);
    }
    if (!app.stats.tracer.empty()) std::cout << "isolux: the last traced frame was traced by the " << app.stats.tracer << "\n";
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    if (app.character_tex) glDeleteTextures(1, &app.character_tex);
    renderer_shutdown(app.renderer);
    gpu_tracer_free(app.gpu_tracer);
    close_window(window);
    return app.exit_code;
}
