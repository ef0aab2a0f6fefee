// Paper Algorithm 3: the fragment shader mixing sprite colour with the light
// texture under the ambient clarity. The CPU reference of shaders/composite.frag.
#pragma once
#include "isolux/image.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/params.hpp"

namespace isolux {

// With colour c and light L in [0, 1] (L per channel):
//   luminance = 0.349 r + 0.114 g + 0.537 b          (the paper's constants)
//   light     = luminance * L / (ambient_clarity^2 + 0.1) * exposure
//   texture   = c * sqrt(ambient_clarity)            (times L when dark_unlit)
//   result    = clamp(texture + light)               (texture - light in shadow mode,
//                                                     where L holds the shadow)
// rounded to 8 bits; alpha is the colour's. `colour` covers `view`; the light
// texture is read at the same world pixels (0 outside it); a grey one's texel
// is L in all three channels. light_mix surface takes c for the luminance,
// and in shadow mode gives c * sqrt(ambient_clarity) * (1 - 0.75 * exposure * L).
//
// tone_map reinhard_knee (tone_knee below) replaces the clamp of texture +
// light where light adds (light and flat modes): in shadow mode nothing adds
// and the result never exceeds the texture, so it is clamped as with none.
Image composite(const Image& colour, Rect view, const LightTexture& light, const Params& p);

// tone_map reinhard_knee on one pixel: `base` (the texture term, each channel
// in [0, 1]) plus `add` (the light term, >= 0). With top the base's highest
// channel and H = 1 - top the headroom it leaves, the sum's highest channel
// rises above top as the light does up to the knee, tone_knee_at * H, and
// above it rolls off as Reinhard's x / (1 + x) toward 1 (the slope
// continuous at the knee); the light is scaled down until the sum's highest
// channel is there. So no channel clips: the pixel keeps the hue of its
// texture plus its light however bright the light (a blue lamp stays blue),
// brightening ever more slowly. An unlit pixel (add 0) and a dim one (below
// the knee) are their composite with none.
inline constexpr double tone_knee_at = 0.5;
void tone_knee(const double base[3], const double add[3], double out[3]);

// The same pixels written into `out` (resized to the view when it differs;
// kept otherwise) for `region` (world pixels) only: a band of rows for one
// thread, or where the light changed. Computed in float with the frame's
// constants; a pixel whose exact value lies near a rounding boundary is
// redone in double, so the bytes are always those of the rule in double.
void composite_into(const Image& colour, Rect view, const LightTexture& light, const Params& p, Rect region, Image& out);

}  // namespace isolux
