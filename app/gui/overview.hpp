// The overview of an endless world: a minimap of the chunks around the view
// (editor.hpp, endless_overview), shown while the document is endless.
#pragma once

namespace isolux::app {

struct App;
void overview_panel(App& app);

}  // namespace isolux::app
