// check-tileset --sheet: every overlay sprite with what isolux estimated of it.
#pragma once
#include <vector>

#include "isolux/image.hpp"
#include "isolux/solid_estimate.hpp"
#include "isolux/tileset.hpp"

namespace isolux::app {

struct SheetSprite {
    const Sprite* sprite;
    Mask footprint;                        // the obstacle map's stamp (red)
    std::vector<EstimatedObject> objects;  // solids (yellow outline), footprints (orange)
};

// A contact sheet: each sprite over dark grey with its obstacle in red, its
// estimated solids' outline in yellow, each object's footprint outlined in
// orange and its anchor as a cyan cross. Throws Error when it would be over
// 64 megapixels.
Image contact_sheet(const std::vector<SheetSprite>& drawn);

}  // namespace isolux::app
