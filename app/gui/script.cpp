// Scripted input for tests and demos (script.hpp): the parser, and the
// interpreter that runs a command a frame as a user's input would.
#include "gui/script.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "gui/app.hpp"
#include "gui/dialogs.hpp"
#include "gui/viewport.hpp"
#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"

namespace isolux::app {

Script load_script(const std::filesystem::path& path) {
    std::istringstream f(read_text_file(path));  // checked as every input is
    Script s;
    std::string text;
    int line = 0;
    while (std::getline(f, text)) {
        ++line;
        if (auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
        std::istringstream in(text);
        ScriptStep step;
        step.line = line;
        if (!(in >> step.op)) continue;
        for (std::string a; in >> a;) step.args.push_back(a);
        // -1: one or more.
        static const std::pair<const char*, int> arity[] = {
            {"wait", 1}, {"click", 2}, {"rclick", 2}, {"drag", 4}, {"key", 1}, {"param", 2},
            {"type", 1}, {"window-shot", 1}, {"resize", 2}, {"inspect", 1}, {"footprint", 2}, {"save-footprints", 0}, {"save-preset", 1}, {"save-scene", 1}, {"load-scene", 1}, {"load-preset", 1}, {"quit", 0},
            {"overlay", 2}, {"sweep", -1}, {"sweep-resolution", 0}, {"wait-sweep", 0}, {"long-work", 1}, {"apply-point", 1}, {"save-sweep", 1},
            {"tool", 1}, {"brush", 2}, {"view", 3}, {"click-tile", 2}, {"drag-tiles", 4}, {"new", 0}, {"fit", 0},
            {"open-dropped", 1}, {"check-glyphs", 1}, {"dump-panels", 1}, {"export-final", 1}, {"select", 1},
            {"character", -1}, {"show", 1}, {"export-tiled", 1}, {"move-lights", 1}, {"save-stats", 1}, {"save-controls", 1},
            {"pan", 3}};
        bool known = false;
        for (auto [op, n] : arity)
            if (step.op == op) {
                known = true;
                if (n < 0 ? step.args.empty() : step.args.size() != std::size_t(n))
                    throw Error(path.string() + ":" + std::to_string(line) + ": " + step.op + " takes " +
                                (n < 0 ? std::string("one or more") : std::to_string(n)) + " arguments");
            }
        if (!known) throw Error(path.string() + ":" + std::to_string(line) + ": unknown command \"" + step.op + "\"");
        // Numbers are checked here, so a bad one is a message, not a crash mid-run.
        const bool numeric = step.op == "wait" || step.op == "click" || step.op == "rclick" || step.op == "drag" ||
                             step.op == "apply-point" || step.op == "view" || step.op == "click-tile" ||
                             step.op == "drag-tiles" || step.op == "move-lights" || step.op == "pan";
        if (step.op == "character" && step.args.size() != 1 && step.args.size() != 3)
            throw Error(path.string() + ":" + std::to_string(line) + ": character takes on|off [X Y]");
        if (step.op == "view" && step.args.size() == 3) {
            const double z = std::strtod(step.args[2].c_str(), nullptr);
            if (!(z > 0))
                throw Error(path.string() + ":" + std::to_string(line) + ": view: zoom \"" + step.args[2] +
                            "\" must be a number above 0");
        }
        for (std::size_t k = 0; numeric && k < step.args.size(); ++k) {
            const std::string& a = step.args[k];
            char* end = nullptr;
            const double v = std::strtod(a.c_str(), &end);
            const double limit = step.op == "wait" || step.op == "apply-point" ? 1e6 : 1e5;
            if (a.empty() || *end != '\0' || !std::isfinite(v) || v < (step.op == "wait" ? 0 : -limit) || v > limit)
                throw Error(path.string() + ":" + std::to_string(line) + ": " + step.op + ": \"" + a +
                            "\" is not a number in [" + (step.op == "wait" ? "0" : "-" + std::to_string(int(limit))) +
                            ", " + std::to_string(int(limit)) + "]");
        }
        s.steps.push_back(step);
    }
    return s;
}

// ---------------------------------------------------------------- running a script

namespace {

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
    nlohmann::json j = {{"frames", n}, {"frame_ms", s.frame_ms}, {"loop_ms", s.loop_ms}, {"fps", s.fps()}, {"tracer", s.tracer}, {"lights_traced", s.lights_traced},
                        {"cpu_ms", cpu}, {"gpu_ms", gpu}};
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace

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
    if (s.pan_frames > 0) {
        // The view moves as a held pan would, a frame at a time.
        app.editor.view.x += s.pan_dx;
        app.editor.view.y += s.pan_dy;
        --s.pan_frames;
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
            app.ui.inspector.open = true;
            app.ui.inspector.sprite = found;
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
        // Window pixels of a tile's centre in the current view (tiles as the
        // status bar shows them: an endless world's own).
        auto tile_screen = [&](int col, int row) {
            int cx = 0, cy = 0;
            const Map& m = e.world.map;
            const WorldOffset o = world_offset(e);
            tile_center(m.layout, m.tile_width, m.tile_height, int(col - o.col), int(row - o.row), cx, cy);
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
        else if (n == "inspector") app.ui.inspector.open = true;
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
    } else if (step.op == "pan") {
        s.pan_dx = num(0);
        s.pan_dy = num(1);
        s.pan_frames = int(num(2));
    } else if (step.op == "save-stats") {
        try {
            write_file_atomic(step.args[0], stats_json(app.stats));
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    } else if (step.op == "save-controls") {
        // Where the last frame drew each recorded panel and control.
        nlohmann::json j = {{"window", {app.window_w, app.window_h}}, {"panels", nlohmann::json::object()},
                            {"controls", nlohmann::json::array()}};
        for (const PanelRects& p : app.ui.panels)
            j["panels"][p.name] = {{"rect", {p.x, p.y, p.w, p.h}}, {"scroll_y", p.scroll_y}, {"scroll_max_y", p.scroll_max_y}};
        for (const ControlRect& c : app.ui.controls)
            j["controls"].push_back({{"panel", c.panel}, {"name", c.name}, {"rect", {c.x, c.y, c.w, c.h}}});
        try {
            write_file_atomic(step.args[0], j.dump(2) + "\n");
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    } else if (step.op == "export-final") {
        export_image(app, "final", step.args[0]);
    } else if (step.op == "export-tiled") {
        try {
            export_tiled(e.world, e.scene, step.args[0], editor_export);
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
    } else if (step.op == "resize") {
        s.resize_w = std::clamp(std::atoi(step.args[0].c_str()), 320, 8192);
        s.resize_h = std::clamp(std::atoi(step.args[1].c_str()), 240, 8192);
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
        else if (n == "normals") o.normals = on;
        else if (n == "inspector_normals") app.ui.inspector.normals = on;
        else if (n == "raw_light") o.raw_light = on;
        else if (n == "split_view") o.split_view = on;
        else if (n == "split_with_3d") o.split_with_3d = on;
        else if (n == "truth_light") o.truth_light = on;
        else if (n == "truth_difference") o.truth_difference = on;
        else if (n == "heatmap") app.accuracy.heatmap = on, app.accuracy.heatmap_stale = true;
    } else if (step.op == "sweep" || step.op == "sweep-resolution") {
        AccuracyPanel& a = app.accuracy;
        if (step.op == "sweep")
            for (std::size_t i = 0; i < 4; ++i) a.axes[i] = i < step.args.size() ? step.args[i] : "";
        else
            set_occluder_resolution_axes(app, a);
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

}  // namespace isolux::app
