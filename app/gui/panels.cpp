// The app's panels, viewport input and exports. Thin: each reads the state
// and calls the editor's actions (gui/editor.hpp).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "gui/app.hpp"
#include "gui/file_browser.hpp"
#include "isolux/blur.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;

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

// ---------------------------------------------------------------- layout

// Places a docked panel: always on the frames the layout is (re)applied,
// otherwise where the user left it.
void dock(App& app, const char* name) {
    const Rect r = panel_rect(app.ui.layout, name);
    if (r.empty()) return;
    const ImGuiCond cond = app.ui.reset_layout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(ImVec2(float(r.x), float(r.y)), cond);
    ImGui::SetNextWindowSize(ImVec2(float(r.w), float(r.h)), cond);
}

// Zoom to `zoom` keeping the world point under window pixel (sx, sy) there.
void zoom_at(App& app, double zoom, double sx, double sy) {
    View& v = app.editor.view;
    const double wx = v.x + sx / v.zoom, wy = v.y + sy / v.zoom;
    v.zoom = std::clamp(zoom, min_zoom, max_zoom);
    v.x = wx - sx / v.zoom;
    v.y = wy - sy / v.zoom;
}

// The selected lights and their areas, fitted into the free area.
void frame_selection(App& app) {
    Editor& e = app.editor;
    if (e.selection.empty()) return;
    Rect r;
    for (int i : e.selection) {
        const Rect a = light_area(e.scene.lights[std::size_t(i)], e.scene.params);
        if (r.empty()) {
            r = a;
            continue;
        }
        const int x0 = std::min(r.x, a.x), y0 = std::min(r.y, a.y);
        const int x1 = std::max(r.x + r.w, a.x + a.w), y1 = std::max(r.y + r.h, a.y + a.h);
        r = {x0, y0, x1 - x0, y1 - y0};
    }
    fit_view(e.view, r, app.ui.layout.free);
}

// ---------------------------------------------------------------- files

// One table: every file action's dialog title, whether it writes, and the
// kind of file it lists.
struct FileAction {
    const char* id;
    const char* title;
    bool writes;
    int filter;  // index into file_filters
};
const FileAction file_actions[] = {
    {"open-scene", "Open scene", false, 0},           {"save-scene", "Save scene as", true, 0},
    {"load-preset", "Load preset", false, 0},         {"save-preset", "Export preset", true, 0},
    {"load-tileset", "Load tileset manifest", false, 0}, {"export-final", "Export final frame", true, 1},
    {"export-light", "Export light texture", true, 1}, {"export-obstacles", "Export obstacle map", true, 1},
    {"export-tiled", "Export Tiled map (.tmx)", true, 3},
};
const FileFilter file_filters[] = {{"Scenes and Tiled maps (*.json, *.tmx)", {".json", ".tmx"}},
                                   {"Images (*.png, *.exr)", {".png", ".exr"}},
                                   {"All files", {}},
                                   {"Tiled maps (*.tmx)", {".tmx"}}};
constexpr int filter_count = int(sizeof file_filters / sizeof file_filters[0]);

const FileAction* find_action(const std::string& id) {
    for (const FileAction& a : file_actions)
        if (id == a.id) return &a;
    return nullptr;
}

void open_file_popup(App& app, const std::string& action, const std::string& suggestion) {
    Ui& ui = app.ui;
    ui.file_action = action;
    ui.path = suggestion;
    ui.filter = -1;
    ui.overwrite.clear();
    std::error_code ec;
    fs::path folder = suggestion.empty() ? fs::current_path(ec) : fs::absolute(suggestion, ec).parent_path();
    if (!fs::is_directory(folder, ec)) folder = fs::current_path(ec);
    ui.browse_folder = folder.string();
}

// Runs a file action on `path` (the dialog's OK, after any confirmation).
void run_file_action(App& app, const std::string& action, const std::string& path) {
    Editor& e = app.editor;
    if (action == "open-scene") {
        guard_unsaved(app, "opening another scene", [&app, path] { load_scene_from(app.editor, path, app.now); });
    } else if (action == "save-scene") {
        if (save_scene_to(e, path) && app.ui.after_save) {
            auto then = std::move(app.ui.after_save);
            app.ui.after_save = nullptr;
            then();
        }
    } else if (action == "load-preset") import_preset(e, path, app.now);
    else if (action == "save-preset") export_preset(e, path);
    else if (action == "load-tileset") load_tileset_from(e, path, app.now);
    else if (action == "export-final") export_image(app, "final", path);
    else if (action == "export-light") export_image(app, "light", path);
    else if (action == "export-obstacles") export_image(app, "obstacles", path);
    else if (action == "export-tiled") {
        try {
            export_tiled(e.world, e.scene, path);
            set_status(e, "exported the level as a Tiled map: " + path);
        } catch (const Error& err) {
            set_status(e, err.what(), true);
        }
    }
}

void save_or_save_as(App& app) {
    Editor& e = app.editor;
    if (e.scene_path.empty()) open_file_popup(app, "save-scene", "scene.json");
    else save_scene_to(e, e.scene_path);
}

void new_scene_action(App& app) {
    guard_unsaved(app, "starting a new scene", [&app] { new_scene(app.editor, app.now); });
}

void quit_action(App& app) {
    guard_unsaved(app, "quitting", [&app] {
        app.ui.quit_confirmed = true;
        app.quit = true;
    });
}

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
            // The same pixels either way (tests/gl_test.cpp); only the time differs.
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
        ImGui::MenuItem("Tileset inspector", nullptr, &app.ui.inspector_open);
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

// The file browser: a folder's entries of the action's kind, a path field
// (typing a path works), recent folders, and "replace?" before writing over
// a file.
void file_popup(App& app) {
    Ui& ui = app.ui;
    if (ui.file_action.empty()) return;
    const FileAction* action = find_action(ui.file_action);
    if (!action) {
        ui.file_action.clear();
        return;
    }
    ImGui::OpenPopup("File");
    const Rect fl = ui.layout.floating;
    ImGui::SetNextWindowPos(ImVec2(float(fl.x), float(fl.y)), ImGuiCond_Appearing);
    ImGui::SetNextWindowSize(ImVec2(float(std::min(640, fl.w)), float(std::min(480, fl.h))), ImGuiCond_Appearing);
    if (!ImGui::BeginPopupModal("File", nullptr, ImGuiWindowFlags_NoSavedSettings)) return;
    ImGui::TextUnformatted(action->title);
    ImGui::Separator();
    const int filter = ui.filter < 0 ? action->filter : ui.filter;
    // The folder, its parent and recent folders.
    if (ImGui::Button("Up")) ui.browse_folder = fs::path(ui.browse_folder).parent_path().string();
    ImGui::SameLine();
    ImGui::TextWrapped("%s", ui.browse_folder.c_str());
    const std::vector<std::string> recents = [&] {
        std::vector<std::string> files;
        for (const RecentFile& r : app.editor.settings.recent) files.push_back(r.path);
        return recent_folders(files);
    }();
    ImGui::SetNextItemWidth(260);
    if (ImGui::BeginCombo("##recent", "Recent folders")) {
        for (const std::string& f : recents)
            if (ImGui::Selectable(f.c_str())) ui.browse_folder = f;
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(200);
    if (ImGui::BeginCombo("##filter", file_filters[filter].label)) {
        for (int i = 0; i < filter_count; ++i)
            if (ImGui::Selectable(file_filters[i].label, i == filter)) ui.filter = i;
        ImGui::EndCombo();
    }
    // The listing.
    bool confirm = false;
    const float list_h = std::max(80.0f, ImGui::GetContentRegionAvail().y - 2 * ImGui::GetFrameHeightWithSpacing() - 8);
    ImGui::BeginChild("##entries", ImVec2(0, list_h), true);
    try {
        for (const FolderEntry& entry : list_folder(ui.browse_folder, file_filters[filter])) {
            const std::string label = (entry.folder ? "[dir] " : "      ") + entry.name;
            const std::string full = (fs::path(ui.browse_folder) / entry.name).string();
            if (ImGui::Selectable(label.c_str(), !entry.folder && ui.path == full,
                                  ImGuiSelectableFlags_AllowDoubleClick)) {
                if (entry.folder) {
                    if (ImGui::IsMouseDoubleClicked(0)) ui.browse_folder = full;
                } else {
                    ui.path = full;
                    confirm = ImGui::IsMouseDoubleClicked(0);
                }
            }
        }
    } catch (const Error& err) {
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", err.what());
    }
    ImGui::EndChild();
    ImGui::SetNextItemWidth(-1);
    const bool enter = ImGui::InputText("##path", &ui.path, ImGuiInputTextFlags_EnterReturnsTrue);
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere(-1);
    confirm = confirm || enter;
    if (ImGui::Button(action->writes ? "Save" : "Open") || confirm) {
        std::error_code ec;
        if (fs::is_directory(ui.path, ec)) {
            ui.browse_folder = ui.path;  // a folder typed or picked: go there
        } else if (action->writes && fs::exists(ui.path, ec) &&
                   !(ui.file_action == "save-scene" && fs::path(ui.path) == app.editor.scene_path)) {
            ui.overwrite = ui.path;
        } else {
            const std::string id = ui.file_action, path = ui.path;
            ui.file_action.clear();
            ImGui::CloseCurrentPopup();
            run_file_action(app, id, path);
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) {
        ui.file_action.clear();
        ui.after_save = nullptr;
        ImGui::CloseCurrentPopup();
    }
    // Replace an existing file?
    if (!ui.overwrite.empty()) ImGui::OpenPopup("Replace file?");
    if (ImGui::BeginPopupModal("Replace file?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("%s already exists. Replace it?", ui.overwrite.c_str());
        if (ImGui::Button("Replace")) {
            const std::string id = ui.file_action, path = ui.overwrite;
            ui.overwrite.clear();
            ui.file_action.clear();
            ImGui::CloseCurrentPopup();
            run_file_action(app, id, path);
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel##replace")) {
            ui.overwrite.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
    if (ui.file_action.empty()) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

// "Save changes?" before New, Open, Recover and Quit.
void unsaved_popup(App& app) {
    Ui& ui = app.ui;
    if (ui.confirm_what.empty()) return;
    ImGui::OpenPopup("Unsaved changes");
    if (!ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    const Editor& e = app.editor;
    ImGui::Text("%s has unsaved changes.", e.scene_path.empty() ? "The scene" : e.scene_path.filename().string().c_str());
    ImGui::Text("Save them before %s?", ui.confirm_what.c_str());
    auto close = [&] {
        ui.confirm_what.clear();
        ImGui::CloseCurrentPopup();
    };
    if (ImGui::Button("Save")) {
        auto then = std::move(ui.confirmed);
        ui.confirmed = nullptr;
        close();
        if (app.editor.scene_path.empty()) {
            ui.after_save = then;  // once the Save dialog has saved
            open_file_popup(app, "save-scene", "scene.json");
        } else if (save_scene_to(app.editor, app.editor.scene_path) && then) {
            then();
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Don't save")) {
        auto then = std::move(ui.confirmed);
        ui.confirmed = nullptr;
        close();
        if (then) then();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) {
        ui.confirmed = nullptr;
        close();
    }
    ImGui::EndPopup();
}

void recovery_popup(App& app) {
    Editor& e = app.editor;
    if (!app.ui.recovery_offered) return;
    ImGui::OpenPopup("Recover unsaved work?");
    if (ImGui::BeginPopupModal("Recover unsaved work?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("isolux did not close cleanly last time.");
        ImGui::Text("An autosaved scene is waiting in %s", autosave_path(e).string().c_str());
        if (ImGui::Button("Recover")) {
            app.ui.recovery_offered = false;
            ImGui::CloseCurrentPopup();
            guard_unsaved(app, "recovering the autosaved scene", [&app] { recover_autosave(app.editor, app.now); });
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

// "Keep or clear the edits?" when seed, size or layout change under a
// scene with edits.
void edits_popup(App& app) {
    Ui& ui = app.ui;
    if (!ui.edits_prompt) return;
    ImGui::OpenPopup("Hand edits");
    if (!ImGui::BeginPopupModal("Hand edits", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    Editor& e = app.editor;
    ImGui::Text("This scene has %zu hand edits over its seeded map.", e.scene.edits.size());
    ImGui::TextUnformatted("Keep them on the new map (edits outside it stay in the file), or clear them?");
    const MapFields& m = ui.edits_target;
    bool done = false;
    if (ImGui::Button("Keep edits")) {
        regenerate(e, m.seed, m.width, m.height, m.layout, app.now, true);
        done = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Clear edits")) {
        regenerate(e, m.seed, m.width, m.height, m.layout, app.now, false);
        done = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) done = true;
    if (done) {
        ui.edits_prompt = false;
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
}

// Shows the document's map fields; an edit applies (regenerates, one undo
// step) when the field is left or Enter is pressed. While a field is active
// ImGui edits `ui.map_edit`, which is refreshed from the document otherwise.
void map_panel(App& app) {
    Editor& e = app.editor;
    Ui& ui = app.ui;
    dock(app, "Map");
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
        else if (!(m == shown) && !e.scene.edits.empty()) {
            ui.edits_target = m;  // ask: keep or clear the hand edits?
            ui.edits_prompt = true;
        } else if (!(m == shown))
            regenerate(e, m.seed, m.width, m.height, m.layout, app.now);
        ui.map_editing = false;
    }
    if (!e.scene.edits.empty()) {
        const int outside = edits_outside(e.scene);
        ImGui::Text("%zu hand edits", e.scene.edits.size());
        if (outside > 0) {
            ImGui::SameLine();
            ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "(%d outside the map, kept)", outside);
        }
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
    dock(app, "Parameters");
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
    dock(app, "Overlays");
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
    dock(app, "Lights");
    if (!ImGui::Begin("Lights")) return ImGui::End();
    ImGui::TextWrapped("Lights tool (L): click to place, drag to move, Shift+click or drag a box to select "
                       "several, right-click or Delete to remove.");
    ImGui::BeginChild("##lights", ImVec2(0, std::min(160.0f, 22.0f * float(e.scene.lights.size()) + 8)), true);
    for (int i = 0; i < int(e.scene.lights.size()); ++i) {
        const Light& l = e.scene.lights[std::size_t(i)];
        char label[160];
        std::snprintf(label, sizeof label, "%s  (%.0f, %.0f)%s%s##%d", light_label(e.scene, i).c_str(), l.x, l.y,
                      l.hidden ? "  hidden" : "", l.locked ? "  locked" : "", i);
        if (ImGui::Selectable(label, is_selected(e, i)))
            select_light(e, i, ImGui::GetIO().KeyShift || ImGui::GetIO().KeyCtrl);
    }
    ImGui::EndChild();
    if (!e.selection.empty()) {
        if (ImGui::Button("Duplicate")) duplicate_selection(e, app.now);
        ImGui::SameLine();
        if (ImGui::Button("Copy")) copy_selection(e);
        ImGui::SameLine();
        if (ImGui::Button("Frame")) frame_selection(app);
        ImGui::SameLine();
        if (ImGui::Button("Delete")) delete_selection(e, app.now);
    }
    if (!e.clipboard.empty()) {
        if (e.selection.empty()) ImGui::NewLine();
        ImGui::SameLine();
        if (ImGui::Button("Paste")) paste_lights(e, app.view.x + app.view.w / 2.0, app.view.y + app.view.h / 2.0, app.now);
    }
    if (e.selected >= 0 && e.selected < int(e.scene.lights.size())) {
        ImGui::Separator();
        Light& l = e.scene.lights[std::size_t(e.selected)];
        Scene before = e.scene;
        ImGui::InputText("name", &l.name);
        track_edit(app, before);
        before = e.scene;
        bool flag = l.hidden;
        if (ImGui::Checkbox("hidden", &flag)) {
            l.hidden = flag;
            commit_edit(e, before, app.now);
        }
        help("Hidden lights stay in the scene (and the file) but light nothing, in the app and in isolux-cli.");
        ImGui::SameLine();
        before = e.scene;
        flag = l.locked;
        if (ImGui::Checkbox("locked", &flag)) {
            l.locked = flag;
            commit_edit(e, before, app.now);
        }
        help("Locked lights are not moved by drags nor removed by Delete or right-click.");
        before = e.scene;
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


// ---------------------------------------------------------------- terrain tools

// A sprite's thumbnail from the renderer's atlas, as a button; `selected`
// draws it framed.
bool sprite_button(App& app, int sprite, bool selected, float size) {
    const Renderer& r = app.renderer;
    if (sprite < 0 || std::size_t(sprite) >= r.atlas_pos.size() || r.atlas_w <= 0) return false;
    const Image& im = app.editor.world.tileset.sprites[std::size_t(sprite)].image;
    const auto& pos = r.atlas_pos[std::size_t(sprite)];
    const ImVec2 uv0(float(pos[0]) / float(r.atlas_w), float(pos[1]) / float(r.atlas_h));
    const ImVec2 uv1(float(pos[0] + im.width) / float(r.atlas_w), float(pos[1] + im.height) / float(r.atlas_h));
    const float k = size / float(std::max(im.width, im.height));
    ImGui::PushID(sprite);
    const ImVec4 bg = selected ? ImVec4(0.95f, 0.8f, 0.3f, 0.6f) : ImVec4(0, 0, 0, 0);
    const bool pressed = ImGui::ImageButton((ImTextureID)(intptr_t)r.atlas, ImVec2(im.width * k, im.height * k), uv0, uv1,
                                            2, bg);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", app.editor.world.tileset.sprites[std::size_t(sprite)].name.c_str());
    ImGui::PopID();
    return pressed;
}

// A row of thumbnails that wraps at the panel's edge.
template <class Body>
void wrapped_row(float item_w, int count, Body body) {
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    for (int i = 0; i < count; ++i) {
        body(i);
        const float next = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + item_w;
        if (i + 1 < count && next < right) ImGui::SameLine();
    }
}

void tools_panel(App& app) {
    Editor& e = app.editor;
    dock(app, "Tools");
    if (!ImGui::Begin("Tools")) return ImGui::End();
    Brush& b = e.brush;
    const auto& tools = tool_table();
    wrapped_row(96, int(tools.size()), [&](int i) {
        const ToolInfo& t = tools[std::size_t(i)];
        const bool on = b.tool == t.tool;
        if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.6f, 0.2f, 0.9f));
        char label[48];
        std::snprintf(label, sizeof label, "%s (%c)", t.label, t.key);
        if (ImGui::Button(label, ImVec2(96, 0))) b.tool = t.tool;
        if (on) ImGui::PopStyleColor();
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", t.help);
    });
    ImGui::Separator();
    const Tileset& ts = e.world.tileset;
    const bool floors = b.tool == Tool::floor || b.tool == Tool::floor_rect || b.tool == Tool::floor_fill;
    const bool overlays = b.tool == Tool::overlay_add;
    if (floors || b.tool == Tool::eyedropper) {
        ImGui::Text("Floor: %s", sprite_name(e, b.floor).c_str());
        std::vector<int> list;
        for (int i = 0; i < int(ts.sprites.size()); ++i)
            if (ts.sprites[std::size_t(i)].kind == SpriteKind::floor) list.push_back(i);
        wrapped_row(44, int(list.size()), [&](int k) {
            if (sprite_button(app, list[std::size_t(k)], b.floor == list[std::size_t(k)], 40)) b.floor = list[std::size_t(k)];
        });
    }
    if (overlays || b.tool == Tool::eyedropper) {
        ImGui::Text("Overlay: %s", b.overlay_tag.empty() ? sprite_name(e, b.overlay).c_str()
                                                         : ("any sprite with tag " + b.overlay_tag).c_str());
        // "Any sprite with tag": natural variation, one pick per tile.
        std::vector<std::string> tags;
        for (const Sprite& sp : ts.sprites)
            if (sp.kind == SpriteKind::overlay)
                for (const std::string& t : sp.tags)
                    if (std::find(tags.begin(), tags.end(), t) == tags.end()) tags.push_back(t);
        wrapped_row(80, int(tags.size()), [&](int k) {
            const std::string label = "any " + tags[std::size_t(k)];
            const bool on = b.overlay_tag == tags[std::size_t(k)];
            if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.6f, 0.2f, 0.9f));
            if (ImGui::Button(label.c_str())) b.overlay_tag = tags[std::size_t(k)];
            if (on) ImGui::PopStyleColor();
        });
        std::vector<int> list;
        for (int i = 0; i < int(ts.sprites.size()); ++i)
            if (ts.sprites[std::size_t(i)].kind == SpriteKind::overlay) list.push_back(i);
        wrapped_row(44, int(list.size()), [&](int k) {
            const int sp = list[std::size_t(k)];
            if (sprite_button(app, sp, b.overlay_tag.empty() && b.overlay == sp, 40)) {
                b.overlay = sp;
                b.overlay_tag.clear();
            }
        });
    }
    if (b.tool == Tool::lights) ImGui::TextWrapped("%s", tool_info(Tool::lights).help);
    else if (!floors && !overlays) ImGui::TextWrapped("%s", tool_info(b.tool).help);
    // What the brush will do under the cursor.
    int col = -1, row = -1;
    if (app.ui.cursor_in_view && tile_at(e.world.map, e.world.placed, app.ui.cursor_x, app.ui.cursor_y, col, row)) {
        ImGui::Separator();
        ImGui::TextWrapped("%s", brush_preview(e, col, row).c_str());
    }
    ImGui::End();
}

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

// The tile under the cursor (and a rectangle stroke's tiles) outlined, and
// the character drawn at its feet.
void viewport_marks(App& app) {
    const Editor& e = app.editor;
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    auto to_screen = [&](double wx, double wy) {
        return ImVec2(float(app.view_x + (wx - app.view.x) * e.view.zoom), float(app.view_y + (wy - app.view.y) * e.view.zoom));
    };
    const Map& m = e.world.map;
    auto outline = [&](int col, int row, ImU32 colour) {
        int cx = 0, cy = 0;
        tile_center(m.layout, m.tile_width, m.tile_height, col, row, cx, cy);
        const double x = cx + e.world.placed.shift_x, y = cy + e.world.placed.shift_y;
        const double hw = m.tile_width / 2.0, hh = m.tile_height / 2.0;
        dl->AddQuad(to_screen(x, y - hh), to_screen(x + hw, y), to_screen(x, y + hh), to_screen(x - hw, y), colour, 2.0f);
    };
    if (e.brush.tool != Tool::lights) {
        int col = -1, row = -1;
        const Stroke& st = e.stroke;
        if (st.active && e.brush.tool == Tool::floor_rect) {
            const int c0 = std::min(st.col0, st.col1), c1 = std::max(st.col0, st.col1);
            const int r0 = std::min(st.row0, st.row1), r1 = std::max(st.row0, st.row1);
            const bool all = long(c1 - c0 + 1) * (r1 - r0 + 1) <= 1024;  // else only its corners
            for (int r = r0; r <= r1; ++r)
                for (int c = c0; c <= c1; ++c)
                    if (all || ((r == r0 || r == r1) && (c == c0 || c == c1))) outline(c, r, IM_COL32(255, 200, 80, 220));
        } else if (app.ui.cursor_in_view &&
                   tile_at(m, e.world.placed, app.ui.cursor_x, app.ui.cursor_y, col, row)) {
            outline(col, row, IM_COL32(255, 230, 120, 230));
            ImGui::SetTooltip("%s", brush_preview(e, col, row).c_str());
        }
    }
    if (app.ui.box_selecting) {
        dl->AddRect(to_screen(app.ui.box_x0, app.ui.box_y0), to_screen(app.ui.cursor_x, app.ui.cursor_y),
                    IM_COL32(120, 200, 255, 230), 0, 0, 1.5f);
    }
    const Character& c = e.character;
    if (c.enabled && app.character_tex) {
        const double k = e.view.zoom;
        const ImVec2 p = to_screen(c.x, c.y);
        const ImVec2 p0(float(p.x - app.character_ax * k), float(p.y - app.character_ay * k));
        const ImVec2 p1(float(p0.x + app.character_w * k), float(p0.y + app.character_h * k));
        dl->AddImage((ImTextureID)(intptr_t)app.character_tex, p0, p1);
    }
}

void stats_panel(App& app) {
    if (!app.editor.settings.show_stats) return;
    dock(app, "Stats");
    if (!ImGui::Begin("Stats", &app.editor.settings.show_stats)) return ImGui::End();
    const Stats& s = app.stats;
    ImGui::Text("%.1f FPS, %.2f ms a frame, %d lights traced", s.fps, s.frame_ms, s.lights_traced);
    ImGui::Text("tracer: %s", s.tracer.empty() ? "none yet" : s.tracer == "gpu" ? "GPU (compute shader)" : "CPU");
    help("Which tracer traced the last traced frame: set under View › Tracer. Automatic takes the GPU's compute shader "
         "unless the GL driver is a software renderer (Mesa's llvmpipe), where the CPU is faster. Both give the same "
         "pixels.");
    const Rect& rb = s.last_rebuilt;
    ImGui::Text("last rebuilt: %d x %d px at (%d, %d)", rb.w, rb.h, rb.x, rb.y);
    help("The world rectangle whose obstacle map was last rebuilt: around the edited tiles after a terrain edit, the "
         "whole region the lights need after a change of Δy, n, the threshold or the map.");
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

// Work beyond the budget (main.cpp: work_allowed): trace it anyway, or undo
// the change that asked for it. Until then the last frame stays on screen.
void huge_work_prompt(App& app) {
    App::HugeWork& h = app.huge;
    if (!h.asking) return;
    if (!ImGui::IsPopupOpen("Long work")) ImGui::OpenPopup("Long work");
    if (!ImGui::BeginPopupModal("Long work", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::Text("This frame would trace about %.2g ray steps: minutes or more on one core,", h.steps);
    ImGui::Text("during which the editor does not respond.");
    if (ImGui::Button("Trace it")) {
        const Scene scene = render_scene(app.editor);
        h.approved = true;
        h.approved_params = scene.params;
        h.approved_lights = scene.lights.size();
        h.asking = false;
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Undo the change")) {
        undo(app.editor, app.now);
        h.asking = false;
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Not now")) {  // the last frame stays until the parameters change
        h.declined = true;
        h.declined_params = render_scene(app.editor).params;
        h.asking = false;
        set_status(app.editor, "not traced: beyond the work budget (change the area, rays or lights)", true);
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
}

}  // namespace

void long_work_prompt(App& app) {
    App::LongTrace& job = app.long_trace;
    if (!ImGui::IsPopupOpen("Tracing")) ImGui::OpenPopup("Tracing");
    if (!ImGui::BeginPopupModal("Tracing", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    const double f = std::min(1.0, double(job.done.load()) / std::max(1.0, job.total));
    const double seconds = app.now - job.started;
    ImGui::Text("Tracing about %.2g ray steps on the CPU, %.0f s so far", job.total, seconds);
    // Rays stop at obstacles, so the estimate is an upper bound: the time
    // left is a guess from the share of rays done.
    if (f > 0.01) ImGui::Text("about %.0f s left", seconds * (1 - f) / f);
    else ImGui::TextUnformatted("estimating the time left...");
    char label[32];
    std::snprintf(label, sizeof label, "%.0f%%", 100 * f);
    ImGui::ProgressBar(float(f), ImVec2(360, 0), label);
    const bool script_cancels = app.script && app.huge.script_answer == "cancel" && job.done.load() > 0;
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false) || script_cancels) job.cancel = true;
    if (job.cancel) {
        ImGui::SameLine();
        ImGui::TextUnformatted("stopping...");
    }
    ImGui::EndPopup();
}

namespace {

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
        const bool sel = i < int(e.scene.lights.size()) && is_selected(e, i);
        const ImVec2 c = to_screen(l.x, l.y);
        if (e.overlays.light_areas) {
            const Rect a = light_area(l, s.params);
            const int alpha = int(255 * e.overlays.light_areas_opacity);
            dl->AddRect(to_screen(a.x, a.y), to_screen(a.x + a.w, a.y + a.h),
                        sel ? IM_COL32(255, 220, 90, alpha) : IM_COL32(200, 200, 255, alpha));
        }
        const ImU32 colour = l.hidden ? IM_COL32(140, 140, 140, 160) : sel ? IM_COL32(255, 220, 90, 255) : IM_COL32(255, 255, 255, 200);
        dl->AddCircle(c, sel ? 7.0f : 5.0f, colour, 16, 2.0f);
        if (l.locked) dl->AddRect(ImVec2(c.x - 3, c.y - 3), ImVec2(c.x + 3, c.y + 3), colour);
        if (!l.name.empty()) dl->AddText(ImVec2(c.x + 9, c.y - 8), colour, l.name.c_str());
    }
    if (e.overlays.split_view) {
        const float x = float(app.view_x + app.view.w * e.overlays.split * e.view.zoom);
        dl->AddLine(ImVec2(x, 0), ImVec2(x, float(app.window_h)), IM_COL32(255, 255, 255, 160), 1.5f);
    }
}

}  // namespace

void guard_unsaved(App& app, const std::string& what, std::function<void()> then) {
    if (!app.editor.dirty) {
        then();
        return;
    }
    app.ui.confirm_what = what;
    app.ui.confirmed = std::move(then);
}

void fit_map(App& app) {
    Editor& e = app.editor;
    if (!e.fit_pending || app.ui.layout.free.empty()) return;
    fit_view(e.view, e.world.placed.bounds, app.ui.layout.free);
    e.fit_pending = false;
}

void draw_panels(App& app) {
    Ui& ui = app.ui;
    // The layout follows the window: applied on the first frame, on every
    // resize and on Window > Reset layout.
    if (ui.layout_w != app.window_w || ui.layout_h != app.window_h) {
        ui.layout_w = app.window_w;
        ui.layout_h = app.window_h;
        ui.reset_layout = true;
    }
    ui.layout = panel_layout(app.window_w, app.window_h, int(ImGui::GetFrameHeight()), 26);
    menu_bar(app);
    map_panel(app);
    params_panel(app);
    overlays_panel(app);
    tools_panel(app);
    lights_panel(app);
    stats_panel(app);
    accuracy_panel(app, app.accuracy);
    inspector_panel(app);
    help_window(app);
    huge_work_prompt(app);
    status_bar(app);
    light_area_overlay(app);
    viewport_marks(app);
    file_popup(app);
    unsaved_popup(app);
    edits_popup(app);
    recovery_popup(app);
    ui.reset_layout = false;
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
        const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
        auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
        if (ctrl && pressed(GLFW_KEY_Z)) {
            if (shift) redo(e, app.now);
            else undo(e, app.now);
        }
        if (ctrl && pressed(GLFW_KEY_Y)) redo(e, app.now);
        if (ctrl && pressed(GLFW_KEY_S)) {
            if (shift) open_file_popup(app, "save-scene", e.scene_path.empty() ? "scene.json" : e.scene_path.string());
            else save_or_save_as(app);
        }
        if (ctrl && pressed(GLFW_KEY_N)) new_scene_action(app);
        if (ctrl && pressed(GLFW_KEY_O)) open_file_popup(app, "open-scene", e.scene_path.string());
        if (ctrl && pressed(GLFW_KEY_Q)) quit_action(app);
        if (ctrl && pressed(GLFW_KEY_C)) copy_selection(e);
        if (ctrl && pressed(GLFW_KEY_V)) paste_lights(e, ui.cursor_x, ui.cursor_y, app.now);
        if (ctrl && pressed(GLFW_KEY_D)) duplicate_selection(e, app.now);
        if (ctrl && pressed(GLFW_KEY_A)) select_lights_in(e, {-2000000000, -2000000000, 2147483647, 2147483647}, false);
        if (ctrl && pressed(GLFW_KEY_0)) zoom_at(app, 1.0, app.window_w / 2.0, app.window_h / 2.0);
        if (pressed(GLFW_KEY_ESCAPE)) select_light(e, -1);
        if (pressed(GLFW_KEY_DELETE) && !e.selection.empty()) delete_selection(e, app.now);
        if (pressed(GLFW_KEY_F1)) ui.help_open = !ui.help_open;
        if (pressed(GLFW_KEY_HOME) || (!ctrl && !shift && pressed(GLFW_KEY_F))) e.fit_pending = true;
        if (!ctrl && shift && pressed(GLFW_KEY_F)) frame_selection(app);
        Character& c = e.character;
        if (!ctrl) {
            // Tool hotkeys (letters WASD stay the character's while it walks).
            for (const ToolInfo& t : tool_table())
                if (pressed(GLFW_KEY_A + (t.key - 'A'))) e.brush.tool = t.tool;
            bool* overlay_keys[5] = {&e.overlays.obstacles, &e.overlays.opacity_maps, &e.overlays.delta_y_bands,
                                     &e.overlays.light_areas, &e.overlays.raw_light};
            for (int k = 0; k < 5; ++k)
                if (pressed(GLFW_KEY_1 + k)) *overlay_keys[k] = !*overlay_keys[k];
        }
        if (c.enabled && !ctrl) {
            double dx = 0, dy = 0;
            if (ImGui::IsKeyDown(GLFW_KEY_A) || ImGui::IsKeyDown(GLFW_KEY_LEFT)) dx -= 1;
            if (ImGui::IsKeyDown(GLFW_KEY_D) || ImGui::IsKeyDown(GLFW_KEY_RIGHT)) dx += 1;
            if (ImGui::IsKeyDown(GLFW_KEY_W) || ImGui::IsKeyDown(GLFW_KEY_UP)) dy -= 1;
            if (ImGui::IsKeyDown(GLFW_KEY_S) || ImGui::IsKeyDown(GLFW_KEY_DOWN)) dy += 1;
            // Isometric: half speed vertically. The character keeps to the
            // map and walks around the obstacle map.
            if (dx != 0 || dy != 0) walk_character(e, dx * c.speed * dt, dy * c.speed * dt * 0.5);
            if (c.follow) {
                e.view.x = c.x - app.window_w / 2.0 / e.view.zoom;
                e.view.y = c.y - app.window_h / 2.0 / e.view.zoom;
            }
        }
    }

    if (io.WantCaptureMouse) {
        if (e.stroke.active && !ImGui::IsMouseDown(0)) end_stroke(e, app.now);
        return;
    }
    // Zoom at the cursor, 1/16 to 16.
    if (io.MouseWheel != 0) zoom_at(app, e.view.zoom * std::pow(1.15, io.MouseWheel), mx, my);
    // Pan: middle drag, or Space + left drag.
    const bool space = ImGui::IsKeyDown(GLFW_KEY_SPACE);
    if (ImGui::IsMouseDown(2) || (space && ImGui::IsMouseDown(0))) {
        e.view.x -= io.MouseDelta.x / e.view.zoom;
        e.view.y -= io.MouseDelta.y / e.view.zoom;
        return;
    }
    int col = -1, row = -1;
    const bool on_tile = tile_at(e.world.map, e.world.placed, ui.cursor_x, ui.cursor_y, col, row);

    // Terrain tools: a stroke from press to release, one undo step.
    if (e.brush.tool != Tool::lights) {
        if (ImGui::IsMouseClicked(0) && on_tile) begin_stroke(e, col, row);
        if (e.stroke.active && ImGui::IsMouseDown(0) && on_tile) continue_stroke(e, col, row);
        if (e.stroke.active && !ImGui::IsMouseDown(0)) end_stroke(e, app.now);
        return;
    }

    // Lights: click a light to select it (Shift adds), drag to move the
    // selection; on empty ground a click places a light and a drag selects
    // the lights in its box.
    const double pick = 8.0 / e.view.zoom;
    if (ImGui::IsMouseClicked(0)) {
        const int hit = light_at(e, ui.cursor_x, ui.cursor_y, pick);
        if (hit >= 0) {
            if (io.KeyShift) select_light(e, hit, true);
            else if (!is_selected(e, hit)) select_light(e, hit);
            if (is_selected(e, hit)) {
                ui.dragging_light = hit;
                ui.drag_before = e.scene;
            }
        } else {
            ui.pressed_empty = true;
            ui.press_x = mx;
            ui.press_y = my;
            ui.box_x0 = ui.cursor_x;
            ui.box_y0 = ui.cursor_y;
        }
    }
    if (ui.pressed_empty) {
        const bool moved = std::hypot(mx - ui.press_x, my - ui.press_y) > 4;
        if (ImGui::IsMouseDown(0)) {
            ui.box_selecting = ui.box_selecting || moved;
        } else {
            if (ui.box_selecting) {
                const double x0 = std::min(ui.box_x0, ui.cursor_x), y0 = std::min(ui.box_y0, ui.cursor_y);
                const double x1 = std::max(ui.box_x0, ui.cursor_x), y1 = std::max(ui.box_y0, ui.cursor_y);
                select_lights_in(e, {int(std::floor(x0)), int(std::floor(y0)), int(std::ceil(x1 - x0)) + 1,
                                     int(std::ceil(y1 - y0)) + 1},
                                 io.KeyShift);
            } else if (!io.KeyShift) {
                place_light(e, ui.box_x0, ui.box_y0, app.now);
            }
            ui.pressed_empty = ui.box_selecting = false;
        }
    }
    if (ui.dragging_light >= 0) {
        if (ImGui::IsMouseDown(0)) {
            // The selection moves with the light under the cursor, by whole pixels.
            const Light& anchor = e.scene.lights[std::size_t(ui.dragging_light)];
            const double dx = std::floor(ui.cursor_x) + 0.5 - anchor.x, dy = std::floor(ui.cursor_y) + 0.5 - anchor.y;
            if ((dx != 0 || dy != 0) && !anchor.locked) move_selection(e, dx, dy);
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
            // The view is drawn one pixel larger than the window (for a
            // fractional pan); the export is the window's size at zoom 1.
            const Image full = renderer_read_final(app.renderer);
            const int w = std::min(full.width, std::max(1, int(std::lround(app.window_w / e.view.zoom))));
            const int h = std::min(full.height, std::max(1, int(std::lround(app.window_h / e.view.zoom))));
            Image out(w, h);
            for (int y = 0; y < h; ++y) std::copy_n(full.at(0, y), std::size_t(w) * 4, out.at(0, y));
            save_image(path, out);
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
