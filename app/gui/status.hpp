// What the app reports: the Stats panel (per-stage times) and the status bar.
#pragma once
#include <functional>
#include <string>

#include "gui/app.hpp"

namespace isolux::app {

void stats_panel(App& app);
void status_bar(App& app);

}  // namespace isolux::app
