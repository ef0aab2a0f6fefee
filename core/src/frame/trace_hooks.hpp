// Test and bench hooks of the tracer (light_trace.cpp), never installed: its
// step counter, how its ray trees were walked, and the paper's Algorithm 2
// as written, the reference the fast tracer is measured against.
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/image.hpp"

namespace isolux {

// Bresenham steps the last trace_light calls on this thread took (for the
// benchmark's steps-per-pixel figure).
std::uint64_t& bresenham_steps();

// How the ray tree was traced by this thread's trace_light calls (for tests
// and the benchmark): walked node by node, or pruned (the clear mask, minus
// what the obstacles' subtrees cut off: cheaper when obstacles are few).
struct TreeTraces {
    std::uint64_t walked = 0, pruned = 0;
};
TreeTraces& tree_traces();

// The plain transcription of Algorithm 2 for one ray, kept as the reference
// implementation the fast tracer is measured against (bench/): "enlighten
// pixel" writes the paper's intensity 255 / (1 + max(|Δx|, |Δy|)), computed
// per pixel, into texture[] (clip-relative) until the first blocked pixel.
void trace_light_ray_paper(const Mask& obstacles, std::int64_t orgX, std::int64_t orgY, std::int64_t dstX,
                           std::int64_t dstY, Rect clip, std::vector<std::uint8_t>& texture);

}  // namespace isolux
