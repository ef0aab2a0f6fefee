// The whole CPU frame against the hardware's floor (memcpy, memset of the
// same bytes, measured in the same run), stage by stage, and what one moved
// light costs against all of them moving.
#pragma once

namespace isolux::bench {

void register_whole_frames();
// Prints frame_times_floor, blur_times_floor, composite_times_floor,
// correction_times_floor, threads2_frame_speedup and one_light_moved_cost.
void print_floor_ratios();

}  // namespace isolux::bench
