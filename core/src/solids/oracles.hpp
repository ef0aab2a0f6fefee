// The solids passes' oracles, never installed: what the tests hold the tree
// passes (solids_pass_tree.cpp) and the GPU's to.
#pragma once
#include "isolux/occluder_map.hpp"

namespace isolux {

// The same two passes ray by ray, every ray walked whole: the reference
// whose bytes trace_light_solids and light_sprite_points give (they walk the rays' shared prefixes
// once, and only the parts that can light a pixel of the clip), and what
// shaders/trace_solids.comp, sprite_points.comp and start_layers.comp do on
// the GPU.
LightMask trace_light_solids_by_rays(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b,
                                     double height, const Params& p, Rect clip);
void light_sprite_points_by_rays(LightMask& mask, const OccluderMap& occ, double height, const Params& p);

}  // namespace isolux
