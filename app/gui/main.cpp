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
#include "gui/app_frame.hpp"
#include "gui/dialogs.hpp"
#include "gui/viewport.hpp"
#include "editor/overlays.hpp"
#include "gui/window.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
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
    if (scene.endless) {
        // Lit around its camera, or 1600x900 pixels at the origin.
        const WorldRect view = default_endless_view(scene);
        const EndlessWindow win = build_endless_window(scene, view, scene_name);
        FrameState st;
        const Rect v = rect_in_window(win, view);
        render_frame(st, win.world, scene_in_window(scene, win, view), Camera{double(v.x), double(v.y), v.w, v.h}, 0);
        save_image(out, st.final);
        std::cerr << "isolux: wrote " << out << " (" << st.final.width << "x" << st.final.height
                  << ", endless world). For more, run isolux-cli render --help.\n";
        return 0;
    }
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

}  // namespace

int main(int argc, char** argv) {
    CLI::App cli{"isolux: level editor and lighting previewer for seeded isometric maps"};
    std::string scene_file, seed, screenshot, script_file, size, tracer_choice, headless_out = "isolux.png";
    long frames = 0;
    int width = 1600, height = 900;
    cli.add_option("--scene", scene_file, "Scene JSON to open");
    cli.add_option("--seed", seed, "Map seed (default \"isolux\")");
    cli.add_option("--size", size, "Map size WxH in tiles, or endless (no edge)");
    cli.add_option("--frames", frames, "Render N frames, then quit (with --screenshot)")->check(CLI::Range(1L, 1000000L));
    cli.add_option("--screenshot", screenshot, "Write the final frame (the viewport, no panels) to this PNG");
    cli.add_option("--script", script_file, "Scripted input, one command a frame (see app/gui/script.hpp)");
    cli.add_option("--tracer", tracer_choice, "auto, cpu or gpu: which tracer to run (overrides View › Tracer)")
        ->check(CLI::IsMember({"auto", "cpu", "gpu"}));
    cli.add_option("--headless-out", headless_out, "With no display: where the headless render goes (default isolux.png)");
    // Without --width/--height: the size the window last closed at (else
    // 1600x900), fitted to the screen's work area.
    CLI::Option* width_opt = cli.add_option("--width", width, "Window width (default: the last size, else 1600)")
                                 ->check(CLI::Range(320, 8192));
    CLI::Option* height_opt = cli.add_option("--height", height, "Window height (default: the last size, else 900)")
                                  ->check(CLI::Range(240, 8192));
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
        if (size == "endless") {
            scene.endless = true;
        } else if (!size.empty()) {
            int w = 0, h = 0;
            if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || !map_size_ok(w, h))
                throw Error("--size \"" + size + "\": expected WxH, " + map_size_rule() + ", or endless");
            scene.width = w, scene.height = h;
            scene.endless = false;
        }
        if (scene_file.empty() && seed.empty() && size.empty()) {
            // The default: the default seed and assets, lit as the README
            // shows (the game preset's look; the paper's is one preset away).
            fs::path def = default_tileset_manifest();
            fs::path demo = def.empty() ? fs::path() : def.parent_path().parent_path() / "scenes" / "showcase.json";
            if (!demo.empty() && fs::exists(demo)) scene = load_scene(demo);
        }
    } catch (const Error& err) {
        std::cerr << "isolux: " << err.what() << "\n";
        return 2;
    }

    const bool screenshot_mode = !screenshot.empty();
    const bool size_given = width_opt->count() > 0 || height_opt->count() > 0;
    const fs::path config = config_dir();
    if (!size_given && !screenshot_mode) {
        const Settings remembered = load_settings(config);
        if (remembered.window_width > 0) width = remembered.window_width, height = remembered.window_height;
    }
    std::string why;
    GLFWwindow* window = open_window(width, height, !screenshot_mode, why, !size_given && !screenshot_mode);
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
    if (!screenshot_mode && !app.script && had_recovery) app.ui.dialogs.recovery_offered = true;

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
            if (screenshot_mode || app.script || app.ui.dialogs.quit_confirmed) break;
            glfwSetWindowShouldClose(window, GLFW_FALSE);
            guard_unsaved(app, "quitting", [&app] {
                app.ui.dialogs.quit_confirmed = true;
                app.quit = true;
            });
            if (app.quit) break;
        }
        const auto t = std::chrono::steady_clock::now();
        const double dt = std::chrono::duration<double>(t - last).count();
        last = t;
        app.now = std::chrono::duration<double>(t - start).count();
        if (app.script && app.script->resize_w > 0) {
            glfwSetWindowSize(window, app.script->resize_w, app.script->resize_h);
            app.script->resize_w = app.script->resize_h = 0;
        }
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
        const FrameReport rep = render_app_frame(app, screenshot_mode);
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
    // The window's size is remembered, unless it was a one-off: a size given
    // on the command line, or a screenshot's hidden window.
    if (!size_given && !screenshot_mode) glfwGetWindowSize(window, &app.editor.settings.window_width,
                                                           &app.editor.settings.window_height);
    try {
        save_settings(config, app.editor.settings);
    } catch (const std::exception&) {
    }
    // A clean exit: this window's unsaved work stays in its own autosave, and
    // its autosave goes when nothing is unsaved. Another window's autosave
    // (an earlier crash's) is never touched here: it goes only once its
    // recovery was offered and answered.
    if (app.editor.dirty) {
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
