// Paper 3.2: "a simple box-blur algorithm is applied" to the light texture,
// hiding the gaps skipped rays leave. The CPU reference of shaders/blur.frag.
#pragma once
#include "isolux/light_texture.hpp"

namespace isolux {

// Each texel becomes the mean of the (2r+1) x (2r+1) texels around it,
// rounded to nearest, with coordinates clamped to the texture's edge (the
// shader's GL_CLAMP_TO_EDGE). radius 0 returns the input; any radius works,
// larger than the texture included. O(1) per texel.
LightTexture box_blur(const LightTexture& tex, int radius);

}  // namespace isolux
