// The menu bar and the Help window: menu_bar.hpp.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "gui/app.hpp"
#include "gui/dialogs.hpp"
#include "editor/file_browser.hpp"
#include "gui/menu_bar.hpp"
#include "gui/status.hpp"
#include "gui/viewport.hpp"
#include "gui/widgets.hpp"
#include "isolux/blur.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

void menu_bar(App& app) {
    Editor& e = app.editor;
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("New scene", "Ctrl+N")) new_scene_action(app);
        if (ImGui::MenuItem("Open scene or Tiled map...", "Ctrl+O")) open_file_popup(app, "open-scene", e.scene_path.string());
        if (ImGui::MenuItem("Save scene", "Ctrl+S")) save_or_save_as(app);
        if (ImGui::MenuItem("Save scene as...", "Ctrl+Shift+S"))
            open_file_popup(app, "save-scene", e.scene_path.empty() ? "scene.json" : e.scene_path.string());
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
        if (ImGui::BeginMenu("Export")) {
            if (ImGui::MenuItem("Tiled map...")) open_file_popup(app, "export-tiled", "level.tmx");
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Recent", !e.settings.recent.empty())) {
            const std::vector<RecentFile> recent = e.settings.recent;  // opening one reorders the list
            for (const RecentFile& r : recent)
                if (ImGui::MenuItem(r.path.c_str(), std::string(to_string(r.kind)).c_str())) {
                    if (r.kind == FileKind::scene)
                        guard_unsaved(app, "opening another scene", [&app, r] { open_recent(app.editor, r, app.now); });
                    else
                        open_recent(e, r, app.now);
                }
            ImGui::EndMenu();
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) quit_action(app);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        if (ImGui::MenuItem("Undo", "Ctrl+Z", false, !e.undo_stack.empty())) undo(e, app.now);
        if (ImGui::MenuItem("Redo", "Ctrl+Y", false, !e.redo_stack.empty())) redo(e, app.now);
        ImGui::Separator();
        const bool any = !e.selection.empty();
        if (ImGui::MenuItem("Copy lights", "Ctrl+C", false, any)) copy_selection(e);
        if (ImGui::MenuItem("Paste lights", "Ctrl+V", false, !e.clipboard.empty()))
            paste_lights(e, app.view.x + app.view.w / 2.0, app.view.y + app.view.h / 2.0, app.now);
        if (ImGui::MenuItem("Duplicate lights", "Ctrl+D", false, any)) duplicate_selection(e, app.now);
        if (ImGui::MenuItem("Delete lights", "Delete", false, any)) delete_selection(e, app.now);
        if (ImGui::MenuItem("Select all lights", "Ctrl+A")) select_lights_in(e, {-2000000000, -2000000000, 2147483647, 2147483647}, false);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        if (ImGui::MenuItem("Fit map", "F")) e.fit_pending = true;
        if (ImGui::MenuItem("Frame selection", "Shift+F", false, !e.selection.empty())) frame_selection(app);
        if (ImGui::MenuItem("Actual size", "Ctrl+0")) zoom_at(app, 1.0, app.window_w / 2.0, app.window_h / 2.0);
        ImGui::Separator();
        ImGui::MenuItem("Stats", nullptr, &e.settings.show_stats);
        if (ImGui::BeginMenu("Tracer")) {
            // The same pixels either way (tests/app/gpu/gl_test.cpp); only the time differs.
            static const char* const choices[3][2] = {
                {"auto", "Automatic (GPU unless its driver is a software renderer)"}, {"cpu", "CPU"}, {"gpu", "GPU (compute shader)"}};
            for (const auto& c : choices)
                if (ImGui::MenuItem(c[1], nullptr, e.settings.tracer == c[0], c[0] != std::string("gpu") || app.gpu_tracer.program)) {
                    e.settings.tracer = c[0];
                    app.tracer_override.clear();
                }
            if (!app.gpu_tracer.program) ImGui::TextDisabled("GPU tracer unavailable: %s", app.gpu_tracer_error.c_str());
            ImGui::EndMenu();
        }
        ImGui::MenuItem("Accuracy", nullptr, &app.accuracy.open);
        ImGui::MenuItem("Tileset inspector", nullptr, &app.ui.inspector.open);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Window")) {
        if (ImGui::MenuItem("Reset layout")) app.ui.reset_layout = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        if (ImGui::MenuItem("Shortcuts", "F1")) app.ui.help_open = true;
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

namespace {

// One table: every shortcut, for the Help window (the tools' own keys come
// from tool_table()).
struct Shortcut {
    const char* keys;
    const char* what;
};
const Shortcut shortcuts[] = {
    {"F1", "this help"},
    {"Ctrl+N / Ctrl+O / Ctrl+S / Ctrl+Shift+S", "new, open, save, save as"},
    {"Ctrl+Q", "quit (asks to save unsaved changes)"},
    {"Ctrl+Z / Ctrl+Y (Ctrl+Shift+Z)", "undo / redo; a stroke or a drag is one step"},
    {"F or Home", "fit the map in the view"},
    {"Shift+F", "frame the selected lights"},
    {"Ctrl+0", "actual size (zoom 1)"},
    {"mouse wheel", "zoom at the cursor, 1/16 to 16"},
    {"middle drag, or Space + drag", "pan"},
    {"Shift+click, drag on empty ground", "add to the light selection, box select (Lights tool)"},
    {"Ctrl+A / Escape", "select all lights / none"},
    {"Ctrl+C / Ctrl+V / Ctrl+D", "copy, paste (at the cursor), duplicate lights"},
    {"Delete, right-click", "remove the selected lights, the light under the cursor"},
    {"1 2 3 4 5", "overlays: obstacle map, opacity maps, Δy bands, light areas, raw light texture"},
    {"W A S D or arrows", "walk the character (Lights panel, character)"},
    {"drop a file on the window", "open a scene, preset or tileset manifest"},
};

}  // namespace

void help_window(App& app) {
    if (!app.ui.help_open) return;
    const Rect fl = app.ui.layout.floating;
    ImGui::SetNextWindowPos(ImVec2(float(fl.x), float(fl.y)), ImGuiCond_Appearing);
    ImGui::SetNextWindowSize(ImVec2(float(fl.w), float(fl.h)), ImGuiCond_Appearing);
    if (!ImGui::Begin("Help", &app.ui.help_open)) return ImGui::End();
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        for (const ToolInfo& t : tool_table()) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%c", t.key);
            ImGui::TableNextColumn();
            ImGui::TextWrapped("%s tool: %s", t.label, t.help);
        }
        for (const Shortcut& k : shortcuts) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(k.keys);
            ImGui::TableNextColumn();
            ImGui::TextWrapped("%s", k.what);
        }
        ImGui::EndTable();
    }
    ImGui::End();
}

}  // namespace isolux::app
