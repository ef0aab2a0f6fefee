// The viewport: its input (pan, zoom, tools, lights, the character) and the
// marks drawn over it (light areas, the tile under the cursor).
#pragma once
#include <functional>
#include <string>

#include "gui/app.hpp"

namespace isolux::app {

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
