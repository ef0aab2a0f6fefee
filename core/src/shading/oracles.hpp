// The sprite shading's oracle, never installed: the rule stated plainly,
// what the tests hold shade_sprites (its baseline and AVX2 builds) to.
#pragma once
#include "isolux/sprite_shading.hpp"

namespace isolux {

// shade_sprites pixel by pixel, each lit sprite pixel's value worked out
// alone in single precision.
void shade_sprites_reference(LightMask& mask, const ShadingMap& map, double light_height, const Params& p);

}  // namespace isolux
