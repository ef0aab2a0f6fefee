// The border rays of one light's area, merged into a prefix tree (shared by
// the paper's tracer, light_trace.cpp, and the solids tracer, solids_pass.cpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace isolux {

// The border rays of one area shape, merged into a prefix tree: rays that
// share their first pixels share nodes, so tracing visits each shared prefix
// once and an obstacle prunes every ray through it at one stroke. Stored in
// depth-first order: node i's subtree is [i, end[i]). Node 0 is the centre.
// Same pixels as tracing ray by ray: a pixel is lit exactly when all nodes on
// some root path to it are clear.
struct RayTree {
    std::vector<std::int16_t> dx, dy;  // offset from the centre
    std::vector<std::int32_t> end;
    std::vector<std::int32_t> offset;  // dy * (2a+1) + dx: the node's index offset in an area-sized buffer
    std::vector<std::uint16_t> depth;  // max(|dx|, |dy|): the falloff's d
    // Each area pixel's nodes (a pixel many rays reach has several): pixel
    // p's are pixel_nodes[pixel_start[p] .. pixel_start[p + 1]), and their
    // count in a byte (prunable: no pixel has more than 255).
    std::vector<std::int32_t> pixel_start, pixel_nodes;
    std::vector<std::uint8_t> nodes_at;
    bool prunable = true;
};

// The tree of the border rays to every k-th border pixel of the
// (2a+1) x (2b+1) area, kept per (a, b, k) while the trees kept hold at most
// ray_tree_cache_budget bytes, the least recently used dropped first
// (bounded_cache.hpp): a scene's lights mostly share a few shapes. Thread-safe.
constexpr std::size_t ray_tree_cache_budget = std::size_t(256) << 20;
std::shared_ptr<const RayTree> ray_tree(int a, int b, int k);

}  // namespace isolux
