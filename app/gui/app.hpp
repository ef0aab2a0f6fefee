// The running app: the editor (document and actions), the renderer (all GL),
// and the UI's own transient state. Panels are functions over this.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "gui/accuracy_panel.hpp"
#include "gui/app_frame.hpp"
#include "gui/dialogs.hpp"
#include "editor/editor.hpp"
#include "gpu/gpu_tracer.hpp"
#include "gui/inspector.hpp"
#include "editor/layout.hpp"
#include "gpu/renderer.hpp"
#include "gui/script.hpp"
#include "gui/viewport.hpp"

namespace isolux::app {

// Per-stage times over the last frames, for the Stats panel.
struct Stats {
    static constexpr int frames = 240;
    // core stages (see Stage), then GPU: upload, sprites, blur, composite.
    static constexpr int series = stage_count + 4;
    std::array<std::array<float, frames>, series> ms{};
    std::array<bool, stage_count> last_ran{};
    std::array<bool, 4> gpu_ran{};  // upload, sprites, blur, composite
    int head = 0;
    long recorded = 0;  // frames pushed so far (the last `frames` of them are kept)
    // The lighting pipeline's time a frame, and the whole loop's (an
    // average over the same frames): the rate shown is 1000 / loop_ms, so the
    // two never disagree.
    float frame_ms = 0, loop_ms = 0;
    float fps() const { return loop_ms > 0 ? 1000.0f / loop_ms : 0.0f; }
    int lights_traced = 0;
    std::string tracer;  // which tracer traced the last traced frame: "cpu" or "gpu"
    Rect last_rebuilt;  // the last frame report's rebuilt rectangle that was not empty (an edit's, or a full rebuild's)
};

// The UI's transient state, each part owned by the file that reads and
// edits it; the document itself is the editor's.
// Where a panel and each of its controls were drawn in the last frame
// (screen pixels), for the app's script (save-controls) and its tests.
struct PanelRects {
    std::string name;
    float x = 0, y = 0, w = 0, h = 0;  // the window
    float scroll_y = 0, scroll_max_y = 0;
};
struct ControlRect {
    std::string panel, name;
    float x = 0, y = 0, w = 0, h = 0;
};

struct Ui {
    std::vector<PanelRects> panels;      // this frame's, so far (cleared as the panels start)
    std::vector<ControlRect> controls;
    bool editing = false;  // a slider or field is being dragged: one undo step at its end (widgets.cpp)
    Scene edit_before;
    DialogState dialogs;      // dialogs.cpp
    ViewportState viewport;   // viewport.cpp
    InspectorState inspector; // inspector.cpp
    PanelLayout layout;                // where the panels go (editor/layout.hpp)
    int layout_w = 0, layout_h = 0;    // the window size it was made for
    bool reset_layout = true;          // apply it this frame
    bool help_open = false;            // the Help window (menu_bar.cpp)
    std::vector<std::string> dropped;  // files dropped on the window, opened next frame
    std::string title;                 // the window title last set
    MapFields map_edit;       // the Map panel's fields while one is being edited
    bool map_editing = false;
};

struct App {
    Renderer renderer;
    GpuTracer gpu_tracer;      // Algorithm 2 as a compute shader (gpu_tracer.hpp)
    std::string gpu_tracer_error;  // why it is not available ("" when it is)
    std::string tracer_override;   // --tracer: wins over the saved setting, not saved
    std::string scene_arg;         // --scene, for messages about it
    HugeWork huge;         // app_frame.hpp: the budget; dialogs.cpp draws its prompt
    LongTrace long_trace;  // app_frame.hpp: the worker; dialogs.cpp draws its progress
    Editor editor;
    Ui ui;
    Stats stats;
    FrameState flat_frame;  // flat lighting for the split view
    TruthCache truth;  // app_frame.cpp
    int split_texture_holds = 0;  // what the renderer's second light texture holds: 0 nothing, 1 flat, 2 truth
    AccuracyPanel accuracy;
    std::optional<Script> script;
    double now = 0;        // seconds since start
    Rect view;             // world pixels shown this frame
    double view_x = 0, view_y = 0;  // window position of the view's top-left
    int window_w = 0, window_h = 0;
    double endless_zoom = 0;  // the last zoom whose view an endless world's window held
    bool overlay_dirty = true;
    Overlays overlay_key;
    Params overlay_params;
    std::vector<Light> overlay_lights;
    Rect overlay_region;
    long screenshot_frames = 0;
    bool quit = false;
    int exit_code = 0;
    unsigned character_tex = 0;  // the character's sprite (GL texture)
    int character_w = 0, character_h = 0, character_ax = 0, character_ay = 0;
    std::string font_warning;    // the label font was not found
};

// Every window of a frame: the panels, dialogs, prompts and viewport marks
// (gui/panels.cpp). Panels read the app's state and call the editor's actions.
void draw_panels(App& app);

}  // namespace isolux::app
