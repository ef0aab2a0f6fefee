// Dialogs and prompts: dialogs.hpp.
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

namespace {

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

}  // namespace

void open_file_popup(App& app, const std::string& action, const std::string& suggestion) {
    Ui& ui = app.ui;
    ui.dialogs.file_action = action;
    ui.dialogs.path = suggestion;
    ui.dialogs.filter = -1;
    ui.dialogs.overwrite.clear();
    std::error_code ec;
    fs::path folder = suggestion.empty() ? fs::current_path(ec) : fs::absolute(suggestion, ec).parent_path();
    if (!fs::is_directory(folder, ec)) folder = fs::current_path(ec);
    ui.dialogs.browse_folder = folder.string();
}

// Runs a file action on `path` (the dialog's OK, after any confirmation).
void run_file_action(App& app, const std::string& action, const std::string& path) {
    Editor& e = app.editor;
    if (action == "open-scene") {
        guard_unsaved(app, "opening another scene", [&app, path] { load_scene_from(app.editor, path, app.now); });
    } else if (action == "save-scene") {
        if (save_scene_to(e, path) && app.ui.dialogs.after_save) {
            auto then = std::move(app.ui.dialogs.after_save);
            app.ui.dialogs.after_save = nullptr;
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
            export_tiled(e.world, e.scene, path, editor_export);
            const WorldOffset o = world_offset(e);
            set_status(e, "exported the level as a Tiled map: " + path +
                              (e.scene.endless ? " (the chunks around the view: tiles from (" + std::to_string(o.col) + ", " +
                                                     std::to_string(o.row) + ") of the endless world)"
                                               : std::string()));
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
        app.ui.dialogs.quit_confirmed = true;
        app.quit = true;
    });
}

// The file browser: a folder's entries of the action's kind, a path field
// (typing a path works), recent folders, and "replace?" before writing over
// a file.
void file_popup(App& app) {
    Ui& ui = app.ui;
    if (ui.dialogs.file_action.empty()) return;
    const FileAction* action = find_action(ui.dialogs.file_action);
    if (!action) {
        ui.dialogs.file_action.clear();
        return;
    }
    ImGui::OpenPopup("File");
    const Rect fl = ui.layout.floating;
    ImGui::SetNextWindowPos(ImVec2(float(fl.x), float(fl.y)), ImGuiCond_Appearing);
    ImGui::SetNextWindowSize(ImVec2(float(std::min(640, fl.w)), float(std::min(480, fl.h))), ImGuiCond_Appearing);
    if (!ImGui::BeginPopupModal("File", nullptr, ImGuiWindowFlags_NoSavedSettings)) return;
    ImGui::TextUnformatted(action->title);
    ImGui::Separator();
    const int filter = ui.dialogs.filter < 0 ? action->filter : ui.dialogs.filter;
    // The folder, its parent and recent folders.
    if (ImGui::Button("Up")) ui.dialogs.browse_folder = fs::path(ui.dialogs.browse_folder).parent_path().string();
    ImGui::SameLine();
    ImGui::TextWrapped("%s", ui.dialogs.browse_folder.c_str());
    const std::vector<std::string> recents = [&] {
        std::vector<std::string> files;
        for (const RecentFile& r : app.editor.settings.recent) files.push_back(r.path);
        return recent_folders(files);
    }();
    ImGui::SetNextItemWidth(260);
    if (ImGui::BeginCombo("##recent", "Recent folders")) {
        for (const std::string& f : recents)
            if (ImGui::Selectable(f.c_str())) ui.dialogs.browse_folder = f;
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(200);
    if (ImGui::BeginCombo("##filter", file_filters[filter].label)) {
        for (int i = 0; i < filter_count; ++i)
            if (ImGui::Selectable(file_filters[i].label, i == filter)) ui.dialogs.filter = i;
        ImGui::EndCombo();
    }
    // The listing.
    bool confirm = false;
    const float list_h = std::max(80.0f, ImGui::GetContentRegionAvail().y - 2 * ImGui::GetFrameHeightWithSpacing() - 8);
    ImGui::BeginChild("##entries", ImVec2(0, list_h), true);
    try {
        for (const FolderEntry& entry : list_folder(ui.dialogs.browse_folder, file_filters[filter])) {
            const std::string label = (entry.folder ? "[dir] " : "      ") + entry.name;
            const std::string full = (fs::path(ui.dialogs.browse_folder) / entry.name).string();
            if (ImGui::Selectable(label.c_str(), !entry.folder && ui.dialogs.path == full,
                                  ImGuiSelectableFlags_AllowDoubleClick)) {
                if (entry.folder) {
                    if (ImGui::IsMouseDoubleClicked(0)) ui.dialogs.browse_folder = full;
                } else {
                    ui.dialogs.path = full;
                    confirm = ImGui::IsMouseDoubleClicked(0);
                }
            }
        }
    } catch (const Error& err) {
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", err.what());
    }
    ImGui::EndChild();
    ImGui::SetNextItemWidth(-1);
    const bool enter = ImGui::InputText("##path", &ui.dialogs.path, ImGuiInputTextFlags_EnterReturnsTrue);
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere(-1);
    confirm = confirm || enter;
    if (ImGui::Button(action->writes ? "Save" : "Open") || confirm) {
        std::error_code ec;
        if (fs::is_directory(ui.dialogs.path, ec)) {
            ui.dialogs.browse_folder = ui.dialogs.path;  // a folder typed or picked: go there
        } else if (action->writes && fs::exists(ui.dialogs.path, ec) &&
                   !(ui.dialogs.file_action == "save-scene" && fs::path(ui.dialogs.path) == app.editor.scene_path)) {
            ui.dialogs.overwrite = ui.dialogs.path;
        } else {
            const std::string id = ui.dialogs.file_action, path = ui.dialogs.path;
            ui.dialogs.file_action.clear();
            ImGui::CloseCurrentPopup();
            run_file_action(app, id, path);
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) {
        ui.dialogs.file_action.clear();
        ui.dialogs.after_save = nullptr;
        ImGui::CloseCurrentPopup();
    }
    // Replace an existing file?
    if (!ui.dialogs.overwrite.empty()) ImGui::OpenPopup("Replace file?");
    if (ImGui::BeginPopupModal("Replace file?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("%s already exists. Replace it?", ui.dialogs.overwrite.c_str());
        if (ImGui::Button("Replace")) {
            const std::string id = ui.dialogs.file_action, path = ui.dialogs.overwrite;
            ui.dialogs.overwrite.clear();
            ui.dialogs.file_action.clear();
            ImGui::CloseCurrentPopup();
            run_file_action(app, id, path);
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel##replace")) {
            ui.dialogs.overwrite.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
    if (ui.dialogs.file_action.empty()) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

// "Save changes?" before New, Open, Recover and Quit.
void unsaved_popup(App& app) {
    Ui& ui = app.ui;
    if (ui.dialogs.confirm_what.empty()) return;
    ImGui::OpenPopup("Unsaved changes");
    if (!ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    const Editor& e = app.editor;
    ImGui::Text("%s has unsaved changes.", e.scene_path.empty() ? "The scene" : e.scene_path.filename().string().c_str());
    ImGui::Text("Save them before %s?", ui.dialogs.confirm_what.c_str());
    auto close = [&] {
        ui.dialogs.confirm_what.clear();
        ImGui::CloseCurrentPopup();
    };
    if (ImGui::Button("Save")) {
        auto then = std::move(ui.dialogs.confirmed);
        ui.dialogs.confirmed = nullptr;
        close();
        if (app.editor.scene_path.empty()) {
            ui.dialogs.after_save = then;  // once the Save dialog has saved
            open_file_popup(app, "save-scene", "scene.json");
        } else if (save_scene_to(app.editor, app.editor.scene_path) && then) {
            then();
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("Don't save")) {
        auto then = std::move(ui.dialogs.confirmed);
        ui.dialogs.confirmed = nullptr;
        close();
        if (then) then();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) {
        ui.dialogs.confirmed = nullptr;
        close();
    }
    ImGui::EndPopup();
}

void recovery_popup(App& app) {
    Editor& e = app.editor;
    if (!app.ui.dialogs.recovery_offered) return;
    ImGui::OpenPopup("Recover unsaved work?");
    if (ImGui::BeginPopupModal("Recover unsaved work?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("isolux did not close cleanly last time.");
        ImGui::Text("An autosaved scene is waiting in %s", recovery_path(e).string().c_str());
        if (ImGui::Button("Recover")) {
            app.ui.dialogs.recovery_offered = false;
            ImGui::CloseCurrentPopup();
            guard_unsaved(app, "recovering the autosaved scene", [&app] { recover_autosave(app.editor, app.now); });
        }
        ImGui::SameLine();
        if (ImGui::Button("Discard")) {
            discard_recovery(e);
            app.ui.dialogs.recovery_offered = false;
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
}

// "Keep or clear the edits?" when seed, size or layout change under a
// scene with edits.
void edits_popup(App& app) {
    Ui& ui = app.ui;
    if (!ui.dialogs.edits_prompt) return;
    ImGui::OpenPopup("Hand edits");
    if (!ImGui::BeginPopupModal("Hand edits", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    Editor& e = app.editor;
    ImGui::Text("This scene has %zu hand edits over its seeded map.", e.scene.edits.size());
    ImGui::TextUnformatted("Keep them on the new map (edits outside it stay in the file), or clear them?");
    const MapFields& m = ui.dialogs.edits_target;
    bool done = false;
    if (ImGui::Button("Keep edits")) {
        regenerate(e, m, app.now, true);
        done = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Clear edits")) {
        regenerate(e, m, app.now, false);
        done = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) done = true;
    if (done) {
        ui.dialogs.edits_prompt = false;
        ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
}

// Work beyond the budget (app_frame.cpp: work_allowed): trace it anyway, or undo
// the change that asked for it. Until then the last frame stays on screen.
void huge_work_prompt(App& app) {
    HugeWork& h = app.huge;
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

void long_work_prompt(App& app) {
    LongTrace& job = app.long_trace;
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

void guard_unsaved(App& app, const std::string& what, std::function<void()> then) {
    if (!app.editor.dirty) {
        then();
        return;
    }
    app.ui.dialogs.confirm_what = what;
    app.ui.dialogs.confirmed = std::move(then);
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
