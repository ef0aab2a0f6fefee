// Builds a scene's world for the front ends: the scene's tileset (the default
// one when empty), then isolux::make_world.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "isolux/endless.hpp"
#include "isolux/scene.hpp"
#include "isolux/world.hpp"

namespace isolux::app {

// The scene's tileset (the default one when its field is empty); throws
// Error naming the manifest.
Tileset load_scene_tileset(const Scene& scene);

// Throws Error naming the tileset file on bad input, or `source` (the scene's
// file) and the entry for a bad edit. Warnings (edits outside the map) are
// printed to stderr when `warnings` is null.
World build_world(const Scene& scene, std::string_view source = "scene", std::vector<std::string>* warnings = nullptr);

// An endless scene's window around `view` (endless pixels): the chunks its
// lights need, generated (endless.hpp). Errors as build_world's, and one
// naming `source` for a view beyond the world's reach.
EndlessWindow build_endless_window(const Scene& scene, WorldRect view, std::string_view source = "scene");

// An endless world's --view X,Y,W,H: 64-bit X and Y, W and H in [1,
// max_image_side]; Error naming the flag otherwise.
WorldRect parse_endless_view(const std::string& text);

}  // namespace isolux::app
