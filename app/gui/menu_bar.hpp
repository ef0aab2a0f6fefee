// The menu bar and the Help window it opens.
#pragma once
#include <functional>
#include <string>

#include "gui/app.hpp"

namespace isolux::app {

void menu_bar(App& app);
// Every tool's and shortcut's keys (F1).
void help_window(App& app);

}  // namespace isolux::app
