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

// The same values written into `out` (resized to `tex`'s rectangle when it
// differs; kept otherwise, so a frame reuses its buffer) for the texels of
// `region` (world pixels) only: a band of rows for one thread, or where the
// light changed. Row-major exact integer running sums, a few rows of scratch.
void box_blur_into(const LightTexture& tex, int radius, Rect region, LightTexture& out);

// The rule stated as plainly as possible: per texel, per channel, the sum of
// its clamped window and one rounded division. The oracle box_blur is tested
// against.
LightTexture box_blur_reference(const LightTexture& tex, int radius);

}  // namespace isolux
