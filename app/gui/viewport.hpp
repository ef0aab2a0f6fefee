// The viewport: its input (pan, zoom, tools, lights, the character) and the
// marks drawn over it (light areas, the tile under the cursor).
#pragma once
#include <functional>
#include <string>

#include "editor/editor.hpp"

namespace isolux::app {

struct App;

// The viewport's input in progress.
struct ViewportState {
    int dragging_light = -1;  // the light the drag started on (the whole selection moves)
    Scene drag_before;
    bool box_selecting = false;        // a box select in progress, from (box_x0, box_y0) world
    double box_x0 = 0, box_y0 = 0;
    bool pressed_empty = false;        // the left button went down on empty ground (lights tool)
    double press_x = 0, press_y = 0;   // where, window pixels
    int stroke_col = -1, stroke_row = -1;
    double cursor_x = 0, cursor_y = 0;  // world pixel under the mouse
    bool cursor_in_view = false;
};

// Viewport input: pan, zoom, place, drag and delete lights, shortcuts, the
// character. Skipped while ImGui wants the mouse or keyboard.
void handle_viewport_input(App& app, double dt);

// Zoom to `zoom` keeping the world point under window pixel (sx, sy) there.
void zoom_at(App& app, double zoom, double sx, double sy);
// The selected lights and their areas, fitted into the free area.
void frame_selection(App& app);
// Applies the pending fit (Editor::fit_pending) to the free area.
void fit_map(App& app);

// The selected lights' areas, and the tile under the cursor (and a rectangle
// stroke's tiles) outlined with the character at its feet.
void light_area_overlay(App& app);
void viewport_marks(App& app);

}  // namespace isolux::app
