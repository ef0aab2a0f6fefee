// isolux-cli render: a seeded map, a scene, a Tiled map or an endless
// world's view, drawn as one of its layers (the lit frame, the light texture,
// the map, the obstacles, the opacity maps, the reference or the difference).
#pragma once
#include <string>
#include <vector>

#include "cli/args.hpp"

namespace isolux::cli {

struct RenderArgs {
    std::string seed, size, layout, tileset, scene, map, view, out;
    ParamArgs params;
    std::string layer = "final";
    std::string reference = "3d";
    std::vector<std::string> lights;
    int frames = 1;
    std::string camera_step;
    bool no_opacity_correction = false;
    bool allow_huge = false;
    bool stats = false;
    int threads = 1;
};

// The --layer names, in the order --help lists them.
std::vector<std::string> render_layer_names();

// Draws the layer and writes it; throws Error naming the file and field at fault.
int run_render(const RenderArgs& a);

}  // namespace isolux::cli
