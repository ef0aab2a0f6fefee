// isolux: the desktop editor and live previewer. GLFW + OpenGL 3.3 core +
// Dear ImGui over isolux::core. With no display it says so and renders the
// scene with the headless renderer instead.
#include <CLI/CLI.hpp>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "common/assets.hpp"
#include "common/world.hpp"
#include "gui/app.hpp"
#include "gui/overlays.hpp"
#include "gui/window.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/truth.hpp"

using namespace isolux;
using namespace isolux::app;
namespace fs = std::filesystem;

namespace {

// No display: the same scene through core's CPU frame, written as a PNG.
int render_headless(const Scene& scene, const std::string& out, const std::string& why) {
    std::cerr << "isolux: " << why << ": the editor needs a display.\n"
              << "isolux: rendering the scene with the headless renderer instead (the same as isolux-cli render)\n";
    World w = build_world(scene);
    FrameState st;
    render_frame(st, w, scene, scene.camera, 0);
    save_image(out, st.final);
    std::cerr << "isolux: wrote " << out << " (" << st.final.width << "x" << st.final.height
              << "). For more, run isolux-cli render --help.\n";
    return 0;
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
        if (k.size() == 1 && std::isalpha(unsigned(k[0]))) code = GLFW_KEY_A + (std::toupper(unsigned(k[0])) - 'A');
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
        if (!start_sweep(app, a)) set_status(e, a.error, true);
    } else if (step.op == "wait-sweep") s.waiting_sweep = true;
    else if (step.op == "apply-point") apply_sweep_point(app, app.accuracy, std::size_t(num(0)));
    else if (step.op == "save-sweep") {
        try {
            write_file_atomic(step.args[0], sweep_csv(app.accuracy.result_axes, app.accuracy.results));
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    }
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
    s.last_ran = rep.ran;
    s.lights_traced = rep.lights_traced;
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
    FrameReport rep = render_frame(e.frame, e.world, scene, cam, e.frame_number);
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
    std::string scene_file, seed, screenshot, script_file, size, headless_out = "isolux.png";
    long frames = 0;
    int width = 1600, height = 900;
    cli.add_option("--scene", scene_file, "Scene JSON to open");
    cli.add_option("--seed", seed, "Map seed (default \"isolux\")");
    cli.add_option("--size", size, "Map size WxH in tiles");
    cli.add_option("--frames", frames, "Render N frames, then quit (with --screenshot)")->check(CLI::Range(1L, 1000000L));
    cli.add_option("--screenshot", screenshot, "Write the final frame (the viewport, no panels) to this PNG");
    cli.add_option("--script", script_file, "Scripted input, one command a frame (see app/gui/script.hpp)");
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
            return render_headless(scene, screenshot.empty() ? headless_out : screenshot, why);
        } catch (const Error& err) {
            std::cerr << "isolux: " << err.what() << "\n";
            return 2;
        }
    }

    App app;
    app.screenshot_frames = frames > 0 ? frames : 1;
    const fs::path config = config_dir();
    try {
        app.editor = make_editor(scene, config);
        if (!script_file.empty()) app.script = load_script(script_file);
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

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    static std::string ini;
    std::error_code ec;
    fs::create_directories(config, ec);
    ini = (config / "imgui.ini").string();
    io.IniFilename = (screenshot_mode || app.script) ? nullptr : ini.c_str();  // layout kept per user
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    auto start = std::chrono::steady_clock::now();
    auto last = start;
    double reload_check = 0;
    long frames_run = 0;
    while (!glfwWindowShouldClose(window) && !app.quit) {
        glfwPollEvents();
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
        run_script_step(app);
        ImGui::NewFrame();
        if (!screenshot_mode) handle_viewport_input(app, dt);
        const auto f0 = std::chrono::steady_clock::now();
        const FrameReport rep = render(app, screenshot_mode);
        push_stats(app, rep, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - f0).count(), dt);
        if (!screenshot_mode) draw_panels(app);
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
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    renderer_shutdown(app.renderer);
    close_window(window);
    return app.exit_code;
}
