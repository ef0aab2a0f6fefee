// Where the panels go: docked to the window's edges and sized from the
// window, so that every panel is on screen from 1280x720 up. The app applies
// it on the first frame, whenever the window is resized, and on Window ›
// Reset layout; between those the user may move panels freely.
#pragma once
#include <string>
#include <vector>

#include "isolux/image.hpp"

namespace isolux::app {

struct PanelRect {
    std::string name;  // the ImGui window's name
    Rect rect;         // window pixels
};

struct PanelLayout {
    std::vector<PanelRect> panels;  // docked: the left column, then the right
    Rect free;                      // the map's area between the columns
    Rect floating;                  // where floating windows (Accuracy, inspector, Help) open
};

// `top`: the menu bar's height; `bottom`: the status bar's.
PanelLayout panel_layout(int window_w, int window_h, int top, int bottom);

// The rectangle of panel `name`, or an empty one.
Rect panel_rect(const PanelLayout& layout, const std::string& name);

}  // namespace isolux::app
