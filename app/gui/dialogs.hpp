// Dialogs and prompts: the file browser and its actions (open, save, export),
// "Save changes?", recovering an autosave, "keep or clear the edits?", and
// the prompts for work beyond the budget and for long work under way.
#pragma once
#include <functional>
#include <string>

#include "editor/editor.hpp"
#include "isolux/tiled.hpp"

namespace isolux::app {

struct App;

// The dialogs' state.
struct DialogState {
    std::string file_action;    // the file browser's action (file_actions in dialogs.cpp), "" when closed
    std::string path;           // its path field (typing a path works as in any dialog)
    std::string browse_folder;  // the folder it lists
    int filter = -1;            // its kind filter; -1: the action's own
    std::string overwrite;      // a path waiting for "replace?" confirmation
    std::string confirm_what;   // the unsaved-changes prompt: what waits ("" when none)
    std::function<void()> confirmed;   // runs after Save or Don't save
    std::function<void()> after_save;  // runs once a Save-as dialog has saved
    bool edits_prompt = false;         // "keep or clear the edits?" before a regenerate
    MapFields edits_target;
    bool recovery_offered = false;     // the autosave was offered once
    bool quit_confirmed = false;       // the window may close
};

// Opens the file browser for `action` (an id of file_actions in dialogs.cpp,
// e.g. "open-scene", "save-scene-as") with `suggestion` in its path field.
void open_file_popup(App& app, const std::string& action, const std::string& suggestion);
// Runs a file action on `path` (the dialog's OK, after any confirmation).
void run_file_action(App& app, const std::string& action, const std::string& path);
void save_or_save_as(App& app);
void new_scene_action(App& app);
void quit_action(App& app);

// Runs `then` now, or after asking to save unsaved changes (Save, Don't
// save, Cancel); `what` names what waits ("opening another scene").
void guard_unsaved(App& app, const std::string& what, std::function<void()> then);

// The dialogs, each drawn when open.
void file_popup(App& app);
void unsaved_popup(App& app);
void recovery_popup(App& app);
void edits_popup(App& app);
// Work beyond the budget (app_frame.cpp: work_allowed): trace it anyway, or undo.
void huge_work_prompt(App& app);
// Approved long work's progress, time and Cancel (LongTrace), drawn
// alone while its worker runs.
void long_work_prompt(App& app);

// Exports (PNG or EXR by extension): the final frame as shown (the window's
// size at zoom 1, exactly), the light texture and the obstacle map of the view.
bool export_image(App& app, const std::string& what, const std::string& path);

// How the editor exports a Tiled map (File › Export and the script's
// export-tiled): the level it holds, whatever export_memory estimates. The
// editor's level is already bounded by what it can show and edit (an endless
// world's loaded window), and the user asked for this file by name; the CLI's
// refusal is for a scene nobody has looked at.
inline const TiledExport editor_export = [] {
    TiledExport o;
    o.allow_huge = true;
    return o;
}();

}  // namespace isolux::app
