// The whole CPU frame against the hardware's floor (memcpy, memset of the
// same bytes, measured in the same run), stage by stage, and what one moved
// light costs against all of them moving.
#pragma once
#include <vector>

#include "isolux/frame.hpp"

namespace isolux::bench {

void register_whole_frames();
// Prints frame_times_floor, blur_times_floor, composite_times_floor,
// correction_times_floor, threads2_frame_speedup and one_light_moved_cost.
void print_floor_ratios();
// Its solids figures alone (print_floor_ratios prints them too):
// solids_frame_cost, and the frame with the occluders at half resolution
// over footprints' (solids_frame_cost_scale2) and over full resolution's
// (occluder_scale2_over_full).
void print_solids_frame_ratios(int pairs);

// The screen scene's whole frame against solids, every light moved, as the
// app runs it: traced by `tracer` (its GPU), the sprites, blur and
// composite left to the GPU, one thread. The calling thread's CPU time
// (its thread clock, not the wall) of each of `frames` frames, in ms; and
// in `same`, whether each frame's light texture is the CPU-traced frame's.
std::vector<double> solids_frame_thread_ms(const LightTracer& tracer, int frames, bool& same);

}  // namespace isolux::bench
