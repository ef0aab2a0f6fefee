// The two passes of occluders.hpp over the border rays' prefix tree
// (ray_tree.hpp): every node once, not every ray's every step, and the parts
// of the tree no solid stands before walked with no bookkeeping at all. The
// same bytes as the ray-by-ray passes (tests/occluders_test.cpp holds them
// to it); those stay the reference and serve every case these do not.
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/light_trace.hpp"
#include "isolux/occluders.hpp"

namespace isolux {

// Whether the tree passes serve this light: border rays, an area within the
// tree's extent that is the mask's whole clip and lies inside the occluder map.
bool occluder_tree_serves(const OccluderMap& occ, const LightMask& m, const Params& p);

// The ground pass (trace_light_solids) over the tree, into `m` as started.
void trace_ground_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                       const Params& p);

// The sprite pass's rays (light_sprite_points, after its sprite pixels are
// unlit) over the tree.
void light_sprite_points_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                              const Params& p, int own_steps);

}  // namespace isolux
