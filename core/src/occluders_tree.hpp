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

// Whether the trees reach a light of half-extents a, b (border rays, an
// extent the trees are kept for); and whether the tree passes serve a
// light's area: within that extent, lying inside the occluder map.
bool occluder_tree_extent(int a, int b, const Params& p);
bool occluder_tree_serves(const OccluderMap& occ, Rect area, const Params& p);

// The ground pass (trace_light_solids) over the tree, into `m` as started
// with its clip the whole area; only the pixels in `wanted` (within the
// area) are sure to be lit: the walk skips the rays once they leave it.
void trace_ground_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                       const Params& p, Rect wanted);

// The sprite pass's rays (light_sprite_points, after its sprite pixels are
// unlit) over the tree of its rays' area (the light's grown by occ.tallest
// rows up and down, which the caller checks the tree serves), the mask's
// clip the light's whole area; only the sprite pixels in `wanted` (within
// the area) are sure to be lit: the walk skips what lights no other.
void light_sprite_points_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                              const Params& p, int own_steps, Rect wanted);

}  // namespace isolux
