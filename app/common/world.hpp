// Builds a scene's world for the front ends: the scene's tileset (the default
// one when empty), then isolux::make_world.
#pragma once
#include "isolux/scene.hpp"
#include "isolux/world.hpp"

namespace isolux::app {

// Throws Error naming the tileset file on bad input.
World build_world(const Scene& scene);

}  // namespace isolux::app
