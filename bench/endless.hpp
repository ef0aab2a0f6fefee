// Endless worlds (endless.hpp): memory and cost follow the view, never the
// world.
#pragma once

namespace isolux::bench {

// Prints endless_walk_memory (peak resident memory while the camera walks
// 100,000 tiles over that while it walks the first 1,000), endless_frame_cost
// (a moving frame on an endless world over the same frame on a 64x64 map,
// interleaved), chunk_build_us and chunk_build_over_floor (one chunk's
// sprites and obstacle map, and that over memset of its pixels' bytes).
void print_endless_ratios();

}  // namespace isolux::bench
