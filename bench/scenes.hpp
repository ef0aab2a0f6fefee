// The benchmark's scenes: obstacle maps and worlds, built once.
#pragma once
#include <string>

#include "isolux/frame.hpp"

namespace isolux::bench {

// An obstacle map and a good light position in it, for the tracer alone.
struct TraceScene {
    std::string name;
    Mask obstacles;
    int cx = 0, cy = 0;
};

// "empty", "default" (the default seed's map), "forest" (every tile three
// trees), "corridors" (walls with doorways).
const TraceScene& trace_scene(const std::string& name);

// A world of `side` x `side` tiles on the default tileset ("forest" fills
// every tile with trees).
const World& world(const std::string& name, int side);

}  // namespace isolux::bench
