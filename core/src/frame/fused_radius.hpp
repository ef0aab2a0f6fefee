// The largest radius the blurs' fused passes take (blur.cpp, blur_within.cpp):
// a window's sum, (2r+1)^2 * 255, plus its half fits 16 bits.
#pragma once

namespace isolux {

constexpr int max_fused_radius = 7;

}  // namespace isolux
