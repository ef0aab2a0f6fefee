// Small widgets every panel and dialog shares.
#pragma once
#include <functional>
#include <string>

#include "gui/app.hpp"

namespace isolux::app {

// The "(?)" marker beside an item: hovering shows `text` (the paper's symbol,
// meaning, range).
void help(const char* text);

// Wraps a widget that edits the document live: the first change snapshots
// the document, the end of the drag commits one undo step.
void track_edit(App& app, const Scene& before_widget);

// Places the docked panel `name` (layout.hpp): always on the frames the
// layout is (re)applied, otherwise where the user left it.
void dock(App& app, const char* name);

// Keeps the last item's rectangle as control `name` of `panel` (Ui::controls).
void record_control(App& app, const char* panel, const char* name);
// Keeps the current window's rectangle and scroll as panel `name` (Ui::panels).
void record_panel(App& app, const char* name);

}  // namespace isolux::app
