// The app's panels, viewport input and exports. Thin: each reads the state
// and calls the editor's actions (gui/editor.hpp).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "gui/app.hpp"
#include "isolux/blur.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"

namespace isolux::app {

namespace {

// The "(?)" marker beside each parameter: the paper's symbol, meaning, range.
void help(const char* text) {
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
        ImGui::TextUnformatted(text);
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

// Wraps a widget that edits the document live: the first change snapshots
// the document, the end of the drag commits one undo step.
void track_edit(App& app, const Scene& before_widget) {
    Ui& ui = app.ui;
    if (ImGui::IsItemActivated() && !ui.editing) {
        ui.editing = true;
        ui.edit_before = before_widget;
    }
    if (ImGui::IsItemDeactivated() && ui.editing) {
        ui.editing = false;
        if (ImGui::IsItemDeactivatedAfterEdit()) commit_edit(app.editor, ui.edit_before, app.now);
    }
}

void open_file_popup(App& app, const std::string& action, const std::string& suggestion) {
    app.ui.file_action = action;
    app.ui.path = suggestion;
}

void menu_bar(App& app) {
    Editor& e = app.editor;
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Open scene...")) open_file_popup(app, "open-scene", e.scene_path.string());
        if (ImGui::MenuItem("Save scene", "Ctrl+S")) {
            if (e.scene_path.empty()) open_file_popup(app, "save-scene", "scene.json");
            else save_scene_to(e, e.scene_path);
        }
        if (ImGui::MenuItem("Save scene as...")) open_file_popup(app, "save-scene", e.scene_path.string());
        ImGui::Separator();
        if (ImGui::MenuItem("Load preset...")) open_file_popup(app, "load-preset", "preset.json");
        if (ImGui::MenuItem("Export preset...")) open_file_popup(app, "save-preset", "preset.json");
        if (ImGui::BeginMenu("Built-in preset")) {
            for (const std::string& name : builtin_preset_names())
                if (ImGui::MenuItem(name.c_str())) {
                    set_params(e, builtin_preset(name), app.now);
                    set_status(e, builtin_preset_summary(name));
                }
            ImGui::EndMenu();
        }
        ImGui::Separator();
        if (ImGui::BeginMenu("Export image")) {
            if (ImGui::MenuItem("Final frame...")) open_file_popup(app, "export-final", "final.png");
            if (ImGui::MenuItem("Light texture...")) open_file_popup(app, "export-light", "light.png");
            if (ImGui::MenuItem("Obstacle map...")) open_file_popup(app, "export-obstacles", "obstacles.png");
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Recent", !e.settings.recent.empty())) {
            const std::vector<RecentFile> recent = e.settings.recent;  // opening one reorders the list
            for (const RecentFile& r : recent)
                if (ImGui::MenuItem(r.path.c_str(), std::string(to_string(r.kind)).c_str())) open_recent(e, r, app.now);
            ImGui::EndMenu();
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Quit")) app.quit = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        if (ImGui::MenuItem("Undo", "Ctrl+Z", false, !e.undo_stack.empty())) undo(e, app.now);
        if (ImGui::MenuItem("Redo", "Ctrl+Y", false, !e.redo_stack.empty())) redo(e, app.now);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        if (ImGui::MenuItem("Reset view", "Home")) reset_view(e);
        ImGui::MenuItem("Stats", nullptr, &e.settings.show_stats);
        ImGui::MenuItem("Accuracy", nullptr, &app.accuracy.open);
        ImGui::MenuItem("Tileset inspector", nullptr, &app.ui.inspector_open);
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void file_popup(App& app) {
    Ui& ui = app.ui;
    if (ui.file_action.empty()) return;
    ImGui::OpenPopup("File");
    ImGui::SetNextWindowSize(ImVec2(520, 0), ImGuiCond_Appearing);
    if (ImGui::BeginPopupModal("File", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("%s", ui.file_action.c_str());
        ImGui::SetNextItemWidth(480);
        bool enter = ImGui::InputText("##path", &ui.path, ImGuiInputTextFlags_EnterReturnsTrue);
        if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere(-1);
        if (ImGui::Button("OK") || enter) {
            Editor& e = app.editor;
            const std::string& a = ui.file_action;
            if (a == "open-scene") load_scene_from(e, ui.path, app.now);
            else if (a == "save-scene") save_scene_to(e, ui.path);
            else if (a == "load-preset") import_preset(e, ui.path, app.now);
            else if (a == "save-preset") export_preset(e, ui.path);
            else if (a == "load-tileset") load_tileset_from(e, ui.path, app.now);
            else if (a == "export-final") export_image(app, "final", ui.path);
            else if (a == "export-light") export_image(app, "light", ui.path);
            else if (a == "export-obstacles") export_image(app, "obstacles", ui.path);
            ui.file_action.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) {
            ui.file_action.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
}

void recovery_popup(App& app) {
    Editor& e = app.editor;
    if (!app.ui.recovery_offered) return;
    ImGui::OpenPopup("Recover unsaved work?");
    if (ImGui::BeginPopupModal("Recover unsaved work?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("isolux did not close cleanly last time.");
        ImGui::Text("An autosaved scene is waiting in %s", autosave_path(e).string().c_str());
        if (ImGui::Button("Recover")) {
            recover_autosave(e, app.now);
            app.ui.recovery_offered = false;
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Discard")) {
            discard_autosave(e);
            app.ui.recovery_offered = false;
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
}

// Shows the document's map fields; an edit applies (regenerates, one undo
// step) when the field is left or Enter is pressed. While a field is active
// ImGui edits `ui.map_edit`, which is refreshed from the document otherwise.
void map_panel(App& app) {
    Editor& e = app.editor;
    Ui& ui = app.ui;
    ImGui::SetNextWindowPos(ImVec2(10, 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(320, 190), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Map")) return ImGui::End();
    const MapFields shown = map_fields(e);
    if (!ui.map_editing) ui.map_edit = shown;
    MapFields& m = ui.map_edit;
    bool apply = false, active = false;
    ImGui::InputText("seed", &m.seed);
    active |= ImGui::IsItemActive();
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    help("Any text. The same seed gives the same map, pixel for pixel, on every machine. Enter regenerates.");
    int size[2] = {m.width, m.height};
    if (ImGui::InputInt2("size", size)) m.width = size[0], m.height = size[1];
    active |= ImGui::IsItemActive();
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    help("Map size in tiles, each side 1 to 1024. Enter regenerates.");
    int layout = int(m.layout);
    if (ImGui::Combo("layout", &layout, "paper\0diamond\0staggered\0")) {
        m.layout = Layout(layout);
        apply = true;
    }
    help("paper: section 3's assembly rule (a parallelogram); diamond and staggered: Tiled's isometric layouts.");
    ui.map_editing = active;
    if (ImGui::Button("Regenerate")) apply = true;
    ImGui::SameLine();
    if (ImGui::Button("Random seed")) {
        static const char* words[] = {"amber", "birch", "cedar", "dune", "ember", "fern", "grove", "heath",
                                      "isle", "juniper", "kelp", "lichen", "moss", "nettle", "oak", "pine"};
        const auto t = std::uint64_t(app.now * 1000) ^ std::uint64_t(e.undo_stack.size() * 7919);
        m.seed = std::string(words[t % 16]) + "-" + std::to_string((t / 16) % 10000);
        apply = true;
    }
    if (apply) {
        if (m.width < 1 || m.height < 1 || m.width > max_map_side || m.height > max_map_side)
            set_status(e, "size: each side must be in [1, " + std::to_string(max_map_side) + "] tiles", true);
        else if (!(m == shown))
            regenerate(e, m.seed, m.width, m.height, m.layout, app.now);
        ui.map_editing = false;
    }
    ImGui::Text("tileset: %s", shown.tileset.empty() ? "default" : shown.tileset.c_str());
    if (ImGui::Button("Load tileset...")) open_file_popup(app, "load-tileset", shown.tileset);
    ImGui::SameLine();
    if (ImGui::Button("Inspect")) app.ui.inspector_open = true;
    if (e.footprints_unsaved) {
        ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "footprints changed");
        ImGui::SameLine();
        if (ImGui::Button("Save into the manifest")) save_footprints(e);
    }
    ImGui::SameLine();
    if (ImGui::Button("Default tileset") && !e.scene.tileset.empty()) {
        Scene before = e.scene;
        e.scene.tileset.clear();
        if (sync_world(e)) commit_edit(e, before, app.now);
    }
    ImGui::End();
}

// The "(?)" text for a parameter: symbol, help, range and what it re-runs.
std::string param_tooltip(const ParamInfo& info) {
    std::string t = *info.symbol ? std::string(info.symbol) + ": " : "";
    t += std::string(info.help) + "\nRange " + param_range_text(info) + ", default " +
         format_param(info, param_default(info)) + ". ";
    if (info.reruns == StageSet{}) t += "Changes only when rays are traced.";
    else if (info.reruns.has(Stage::obstacle_map)) t += "Rebuilds the obstacle map.";
    else if (info.reruns.has(Stage::trace)) t += "Retraces.";
    else if (info.reruns.has(Stage::blur)) t += "Re-blurs only.";
    else t += "Re-composites only.";
    if (info.type == ParamType::integer || info.type == ParamType::real) t += " Ctrl+click to type any value.";
    return t;
}

// One widget per row of the parameter table, grouped by the paper's section.
// A drag is one undo step; the document is validated by set_params.
void params_panel(App& app) {
    Editor& e = app.editor;
    ImGui::SetNextWindowPos(ImVec2(10, 230), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(320, 420), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Parameters")) return ImGui::End();
    ImGui::PushItemWidth(170);
    const char* group = "";
    for (const ParamInfo& info : param_table()) {
        if (std::string_view(group) != info.group) ImGui::TextDisabled("%s", group = info.group);
        const Scene before = e.scene;
        const double v = info.get(e.scene.params);
        const ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (info.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
        ImGui::PushID(info.name);
        double edited = v;
        bool changed = false;
        switch (info.type) {
            case ParamType::integer: {
                int x = int(v);
                changed = ImGui::SliderInt(info.label, &x, int(info.slider_min), int(info.slider_max), "%d", flags);
                edited = std::clamp(double(x), info.min, info.max);
                break;
            }
            case ParamType::real: {
                float x = float(v);
                changed = ImGui::SliderFloat(info.label, &x, float(info.slider_min), float(info.slider_max), "%.3f", flags);
                edited = std::clamp(double(x), info.min, info.max);
                if (info.min_open && edited <= info.min) edited = v;
                break;
            }
            case ParamType::choice: {
                int x = int(v);
                changed = ImGui::Combo(info.label, &x, info.choices.data(), choice_count(info));
                edited = x;
                break;
            }
            case ParamType::boolean: {
                bool x = v != 0;
                changed = ImGui::Checkbox(info.label, &x);
                edited = x ? 1 : 0;
                break;
            }
        }
        if (changed && edited != v) info.set(e.scene.params, edited);  // live while dragging
        if (info.type == ParamType::integer || info.type == ParamType::real) track_edit(app, before);
        else if (changed) commit_edit(e, before, app.now);
        ImGui::PopID();
        help(param_tooltip(info).c_str());
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

void overlays_panel(App& app) {
    Overlays& o = app.editor.overlays;
    ImGui::SetNextWindowPos(ImVec2(10, 660), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(320, 230), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Overlays")) return ImGui::End();
    auto row = [](const char* name, bool* on, float* opacity, const char* tip) {
        ImGui::Checkbox(name, on);
        help(tip);
        if (opacity) {
            ImGui::SameLine(190);
            ImGui::SetNextItemWidth(100);
            ImGui::SliderFloat((std::string("##") + name).c_str(), opacity, 0.0f, 1.0f, "%.2f");
        }
    };
    row("obstacle map", &o.obstacles, &o.obstacles_opacity, "The obstacle map in white, as the paper's Figure 6.");
    row("opacity maps", &o.opacity_maps, &o.opacity_maps_opacity,
        "Green: sprites standing above a light's centre, added to its light. Red: those below, subtracted.");
    row("delta y bands", &o.delta_y_bands, &o.delta_y_opacity,
        "Blue: the Δy rows Algorithm 1 reads on each sprite; cyan: the run it chose.");
    row("light areas", &o.light_areas, &o.light_areas_opacity, "Each light's (2a+1) x (2b+1) area.");
    row("raw light texture", &o.raw_light, nullptr, "Show the light texture instead of the final frame.");
    ImGui::TextDisabled("truth (the sprites' 3D shapes, lights at their height)");
    row("3D light texture", &o.truth_light, nullptr,
        "The light texture of the 3D reference: a pixel is lit when the segment from its surface point to the "
        "light clears every solid. Needs shapes in the tileset.");
    row("2.5D vs 3D", &o.truth_difference, &o.truth_difference_opacity,
        "Magenta: lit by the paper's model but dark in 3D. Cyan: dark in the model but lit in 3D. Recomputed when "
        "the scene changes (slow while dragging a light).");
    row("split view", &o.split_view, nullptr,
        "Left: the paper's lighting. Right: flat lighting (Figure 10), or the 3D reference.");
    if (o.split_view) {
        ImGui::SameLine();
        ImGui::Checkbox("3D on the right", &o.split_with_3d);
        ImGui::SetNextItemWidth(200);
        ImGui::SliderFloat("split", &o.split, 0.0f, 1.0f);
    }
    ImGui::End();
}

void lights_panel(App& app) {
    Editor& e = app.editor;
    ImGui::SetNextWindowPos(ImVec2(1270, 30), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(320, 380), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Lights")) return ImGui::End();
    ImGui::TextWrapped("Click the map to place a light, drag to move, right-click or Delete to remove.");
    for (int i = 0; i < int(e.scene.lights.size()); ++i) {
        const Light& l = e.scene.lights[i];
        char label[96];
        std::snprintf(label, sizeof label, "light %d  (%.0f, %.0f)", i + 1, l.x, l.y);
        if (ImGui::Selectable(label, e.selected == i)) e.selected = i;
    }
    if (e.selected >= 0 && e.selected < int(e.scene.lights.size())) {
        ImGui::Separator();
        Light& l = e.scene.lights[e.selected];
        Scene before = e.scene;
        float pos[2] = {float(l.x), float(l.y)};
        if (ImGui::DragFloat2("position", pos, 1.0f)) l.x = pos[0], l.y = pos[1];
        track_edit(app, before);
        before = e.scene;
        bool own_area = l.area_a.has_value();
        if (ImGui::Checkbox("own area", &own_area)) {
            if (own_area) l.area_a = e.scene.params.area_a, l.area_b = e.scene.params.area_b;
            else l.area_a.reset(), l.area_b.reset();
            commit_edit(e, before, app.now);
        }
        help("Off: the preset's a and b.");
        if (own_area) {
            before = e.scene;
            int ab[2] = {*l.area_a, *l.area_b};
            if (ImGui::SliderInt2("a, b", ab, 0, 512, "%d", ImGuiSliderFlags_AlwaysClamp))
                l.area_a = ab[0], l.area_b = ab[1];
            track_edit(app, before);
        }
        before = e.scene;
        float col[3] = {l.r / 255.0f, l.g / 255.0f, l.b / 255.0f};
        if (ImGui::ColorEdit3("colour", col)) {
            l.r = std::uint8_t(col[0] * 255 + 0.5f), l.g = std::uint8_t(col[1] * 255 + 0.5f),
            l.b = std::uint8_t(col[2] * 255 + 0.5f);
        }
        track_edit(app, before);
        before = e.scene;
        float intensity = float(l.intensity);
        if (ImGui::SliderFloat("intensity", &intensity, 0.0f, 4.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp))
            l.intensity = intensity;
        track_edit(app, before);
        before = e.scene;
        bool own_height = l.height.has_value();
        if (ImGui::Checkbox("own height", &own_height)) {
            if (own_height) l.height = e.scene.params.light_height;
            else l.height.reset();
            commit_edit(e, before, app.now);
        }
        help("Off: the preset's light height. The height above the ground in pixels: the paper's model ignores "
             "it; the 3D reference (Overlays, truth) uses it.");
        if (own_height) {
            before = e.scene;
            float h = float(*l.height);
            if (ImGui::SliderFloat("height", &h, 0.0f, 256.0f, "%.0f px", ImGuiSliderFlags_AlwaysClamp)) l.height = h;
            track_edit(app, before);
        }
        if (ImGui::Button("Remove")) remove_light(e, e.selected, app.now);
    }
    ImGui::Separator();
    Character& c = e.character;
    if (ImGui::Checkbox("character (WASD)", &c.enabled) && c.enabled) {
        c.x = app.view.x + app.view.w / 2.0;
        c.y = app.view.y + app.view.h / 2.0;
    }
    help("A character carrying a light walks with WASD or the arrow keys: the paper's l-frames shift at work.");
    if (c.enabled) {
        ImGui::SameLine();
        ImGui::Checkbox("follow", &c.follow);
    }
    ImGui::End();
}

void stats_panel(App& app) {
    if (!app.editor.settings.show_stats) return;
    ImGui::SetNextWindowPos(ImVec2(1270, 420), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(320, 430), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Stats", &app.editor.settings.show_stats)) return ImGui::End();
    const Stats& s = app.stats;
    ImGui::Text("%.1f FPS, %.2f ms a frame, %d lights traced", s.fps, s.frame_ms, s.lights_traced);
    std::string ran = "ran:";
    for (int k = 0; k < stage_count; ++k)
        if (s.last_ran[k]) ran += std::string(" ") + std::string(to_string(Stage(k)));
    static const char* gpu[4] = {"upload", "sprites(gpu)", "blur(gpu)", "composite(gpu)"};
    for (int k = 0; k < 4; ++k)
        if (s.gpu_ran[k]) ran += std::string(" ") + gpu[k];
    if (ran == "ran:") ran += " nothing (a still frame)";
    ImGui::TextWrapped("%s", ran.c_str());
    static const char* names[Stats::series] = {"sprites (cpu)", "obstacle map", "trace", "opacity correction",
                                               "blur (cpu)", "shift", "composite (cpu)", "upload",
                                               "sprites (gpu)", "blur (gpu)", "composite (gpu)"};
    for (int k = 0; k < Stats::series; ++k) {
        if (k == int(Stage::sprites) || k == int(Stage::blur) || k == int(Stage::composite)) continue;  // on the GPU here
        const auto& v = s.ms[k];
        float latest = v[(s.head + Stats::frames - 1) % Stats::frames];
        float peak = *std::max_element(v.begin(), v.end());
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "%.3f ms (max %.2f)", latest, peak);
        ImGui::PlotLines(names[k], v.data(), Stats::frames, s.head, overlay, 0.0f, std::max(0.1f, peak), ImVec2(170, 26));
    }
    ImGui::End();
}

void status_bar(App& app) {
    const Editor& e = app.editor;
    ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - 26));
    ImGui::SetNextWindowSize(ImVec2(vp->Size.x, 26));
    ImGui::Begin("##status", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus);
    int col = -1, row = -1;
    const bool on_tile = app.ui.cursor_in_view &&
                         tile_at(e.world.map, e.world.placed, app.ui.cursor_x, app.ui.cursor_y, col, row);
    ImGui::Text("world (%.0f, %.0f)  tile %s  |  %.0f FPS  %.2f ms  |  zoom %.2f  |  %s%s", app.ui.cursor_x,
                app.ui.cursor_y, on_tile ? (std::to_string(col) + ", " + std::to_string(row)).c_str() : "-",
                app.stats.fps, app.stats.frame_ms, e.view.zoom, e.dirty ? "unsaved  |  " : "", "");
    ImGui::SameLine();
    if (e.status_error) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", e.status.c_str());
    else ImGui::TextUnformatted(e.status.c_str());
    if (!app.renderer.shader_error.empty()) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "shader: %s", app.renderer.shader_error.c_str());
    }
    ImGui::End();
}

void light_area_overlay(App& app) {
    const Editor& e = app.editor;
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const Scene s = render_scene(e);
    auto to_screen = [&](double wx, double wy) {
        return ImVec2(float(app.view_x + (wx - app.view.x) * e.view.zoom), float(app.view_y + (wy - app.view.y) * e.view.zoom));
    };
    for (int i = 0; i < int(s.lights.size()); ++i) {
        const Light& l = s.lights[i];
        const bool sel = i == e.selected;
        const ImVec2 c = to_screen(l.x, l.y);
        if (e.overlays.light_areas) {
            const Rect a = light_area(l, s.params);
            const int alpha = int(255 * e.overlays.light_areas_opacity);
            dl->AddRect(to_screen(a.x, a.y), to_screen(a.x + a.w, a.y + a.h),
                        sel ? IM_COL32(255, 220, 90, alpha) : IM_COL32(200, 200, 255, alpha));
        }
        dl->AddCircle(c, sel ? 7.0f : 5.0f, sel ? IM_COL32(255, 220, 90, 255) : IM_COL32(255, 255, 255, 200), 16, 2.0f);
    }
    if (e.overlays.split_view) {
        const float x = float(app.view_x + app.view.w * e.overlays.split * e.view.zoom);
        dl->AddLine(ImVec2(x, 0), ImVec2(x, float(app.window_h)), IM_COL32(255, 255, 255, 160), 1.5f);
    }
}

}  // namespace

void draw_panels(App& app) {
    menu_bar(app);
    map_panel(app);
    params_panel(app);
    overlays_panel(app);
    lights_panel(app);
    stats_panel(app);
    accuracy_panel(app, app.accuracy);
    inspector_panel(app);
    status_bar(app);
    light_area_overlay(app);
    file_popup(app);
    recovery_popup(app);
}

void handle_viewport_input(App& app, double dt) {
    ImGuiIO& io = ImGui::GetIO();
    Editor& e = app.editor;
    Ui& ui = app.ui;
    const double mx = io.MousePos.x, my = io.MousePos.y;
    ui.cursor_x = app.view.x + (mx - app.view_x) / e.view.zoom;
    ui.cursor_y = app.view.y + (my - app.view_y) / e.view.zoom;
    ui.cursor_in_view = !io.WantCaptureMouse && mx >= 0 && my >= 0;

    if (!io.WantCaptureKeyboard) {
        const bool ctrl = io.KeyCtrl;
        if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Z, false)) {
            if (io.KeyShift) redo(e, app.now);
            else undo(e, app.now);
        }
        if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Y, false)) redo(e, app.now);
        if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_S, false)) {
            if (e.scene_path.empty()) open_file_popup(app, "save-scene", "scene.json");
            else save_scene_to(e, e.scene_path);
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_DELETE, false) && e.selected >= 0) remove_light(e, e.selected, app.now);
        if (ImGui::IsKeyPressed(GLFW_KEY_HOME, false)) reset_view(e);
        Character& c = e.character;
        if (c.enabled && !ctrl) {
            double dx = 0, dy = 0;
            if (ImGui::IsKeyDown(GLFW_KEY_A) || ImGui::IsKeyDown(GLFW_KEY_LEFT)) dx -= 1;
            if (ImGui::IsKeyDown(GLFW_KEY_D) || ImGui::IsKeyDown(GLFW_KEY_RIGHT)) dx += 1;
            if (ImGui::IsKeyDown(GLFW_KEY_W) || ImGui::IsKeyDown(GLFW_KEY_UP)) dy -= 1;
            if (ImGui::IsKeyDown(GLFW_KEY_S) || ImGui::IsKeyDown(GLFW_KEY_DOWN)) dy += 1;
            c.x += dx * c.speed * dt;
            c.y += dy * c.speed * dt * 0.5;  // isometric: half speed vertically
            if (c.follow) {
                e.view.x = c.x - app.window_w / 2.0 / e.view.zoom;
                e.view.y = c.y - app.window_h / 2.0 / e.view.zoom;
            }
        }
    }

    if (io.WantCaptureMouse) return;
    // Zoom at the cursor.
    if (io.MouseWheel != 0) {
        const double old = e.view.zoom;
        e.view.zoom = std::clamp(e.view.zoom * std::pow(1.15, io.MouseWheel), 0.25, 8.0);
        e.view.x = ui.cursor_x - (ui.cursor_x - e.view.x) * old / e.view.zoom;
        e.view.y = ui.cursor_y - (ui.cursor_y - e.view.y) * old / e.view.zoom;
    }
    // Pan: middle drag, or Space + left drag.
    const bool space = ImGui::IsKeyDown(GLFW_KEY_SPACE);
    if (ImGui::IsMouseDown(2) || (space && ImGui::IsMouseDown(0))) {
        e.view.x -= io.MouseDelta.x / e.view.zoom;
        e.view.y -= io.MouseDelta.y / e.view.zoom;
        return;
    }
    const double pick = 8.0 / e.view.zoom;
    if (ImGui::IsMouseClicked(0)) {
        const int hit = light_at(e, ui.cursor_x, ui.cursor_y, pick);
        if (hit >= 0) {
            e.selected = hit;
            ui.dragging_light = hit;
            ui.drag_before = e.scene;
        } else {
            place_light(e, ui.cursor_x, ui.cursor_y, app.now);
        }
    }
    if (ui.dragging_light >= 0) {
        if (ImGui::IsMouseDown(0)) {
            if (io.MouseDelta.x != 0 || io.MouseDelta.y != 0) move_light(e, ui.dragging_light, ui.cursor_x, ui.cursor_y);
        } else {
            commit_edit(e, ui.drag_before, app.now);  // one undo step per drag
            ui.dragging_light = -1;
        }
    }
    if (ImGui::IsMouseClicked(1)) {
        const int hit = light_at(e, ui.cursor_x, ui.cursor_y, pick);
        if (hit >= 0) remove_light(e, hit, app.now);
    }
}

bool export_image(App& app, const std::string& what, const std::string& path) {
    Editor& e = app.editor;
    try {
        if (what == "final") {
            save_image(path, renderer_read_final(app.renderer));
        } else if (what == "light") {
            const LightTexture blurred = box_blur(e.frame.traced, e.scene.params.blur_radius);
            save_image(path, light_texture_image(shift_light_texture(blurred, app.view)));
        } else {
            save_image(path, mask_image(e.frame.obstacles, app.view));
        }
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
    set_status(e, "exported " + path);
    return true;
}

}  // namespace isolux::app
