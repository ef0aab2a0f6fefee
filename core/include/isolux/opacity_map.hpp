// Opacity maps (paper 3.2): one boolean matrix per sprite, "if a certain pixel
// of the sprite is transparent or not, given a certain threshold".
#pragma once
#include "isolux/image.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

// True where alpha / 255 > threshold (alpha16 / 65535 for 16-bit sources;
// strictly: alpha exactly at the threshold is transparent). threshold in [0, 1]. The mask is in sprite pixels at (0, 0).
Mask opacity_map(const Image& sprite, double threshold);

// The threshold a sprite uses: its own override, else the preset's.
double sprite_threshold(const Sprite& s, double preset_threshold);

}  // namespace isolux
