// Where the front ends find the default tileset.
#pragma once
#include <filesystem>

namespace isolux::app {

// The default tileset's manifest: $ISOLUX_ASSETS/default/tileset.json, else
// <exe>/../share/isolux/assets/default/tileset.json (installed), else the
// source tree's assets/. Empty when none exists.
std::filesystem::path default_tileset_manifest();

}  // namespace isolux::app
