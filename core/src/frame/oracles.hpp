// The frame's fast kernels' oracles, never installed: each rule stated as
// plainly as possible, what the tests hold the fast paths (and their AVX2
// builds) to.
#pragma once
#include "isolux/blur.hpp"
#include "isolux/composite.hpp"

namespace isolux {

// The rule stated as plainly as possible: per texel, per channel, the sum of
// its clamped window and one rounded division. The oracle box_blur is tested
// against.
LightTexture box_blur_reference(const LightTexture& tex, int radius);

// The same rule per texel, as plainly as possible: the oracle of box_blur_within_into.
LightTexture box_blur_within_reference(const LightTexture& tex, int radius, const SurfaceIds& ids);

// The rule stated plainly: composite_pixel in double for every pixel. The
// oracle composite is tested against.
Image composite_reference(const Image& colour, Rect view, const LightTexture& light, const Params& p);

// The composite's formula for one pixel, in [0, 1]: the oracles' own rule.
void composite_pixel(const double colour[3], const double light[3], const Params& p, double out[3]);

}  // namespace isolux
