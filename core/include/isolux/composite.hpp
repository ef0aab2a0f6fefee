// Paper Algorithm 3: the fragment shader mixing sprite colour with the light
// texture under the ambient clarity. The CPU reference of shaders/composite.frag.
#pragma once
#include "isolux/image.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/params.hpp"

namespace isolux {

// With colour c and light L in [0, 1] (L per channel):
//   luminance = 0.349 r + 0.114 g + 0.537 b          (the paper's constants)
//   light     = luminance * L / (ambient_clarity^2 + 0.1)
//   texture   = c * sqrt(ambient_clarity)            (times L when dark_unlit)
//   result    = clamp(texture + light)               (texture - light in shadow mode,
//                                                     where L holds the shadow)
// rounded to 8 bits; alpha is the colour's. `colour` covers `view`; the light
// texture is read at the same world pixels (0 outside it); a grey one's texel
// is L in all three channels.
Image composite(const Image& colour, Rect view, const LightTexture& light, const Params& p);

// The same pixels written into `out` (resized to the view when it differs;
// kept otherwise) for `region` (world pixels) only: a band of rows for one
// thread, or where the light changed. Computed in float with the frame's
// constants; a pixel whose exact value lies near a rounding boundary is
// redone in double, so the bytes are always those of the rule in double.
void composite_into(const Image& colour, Rect view, const LightTexture& light, const Params& p, Rect region, Image& out);

}  // namespace isolux
