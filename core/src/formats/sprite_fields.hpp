// Inside core: the fields a sprite carries beyond its pixels (anchor, tags,
// opacity threshold, footprint), read by one parser for every format that
// carries them: a tileset manifest's sprite entry, and a TMX tile's isolux_*
// properties (tiled_import.cpp turns them into the same JSON fields).
#pragma once
#include <string>

#include "isolux/tileset.hpp"
#include "formats/json_fields.hpp"

namespace isolux {

// Reads "anchor": [x, y], "tags": [names], "opacity_threshold": t in [0, 1]
// and "footprint" (footprint_from) into `s`; a field that is absent leaves
// the sprite's value. Errors name f.where and the field.
void read_sprite_fields(const Fields& f, Sprite& s);

// "auto" | "paper" | "none" | {"mode": ..., "run": [x, y, length],
// "polygon": [[x, y], ...], "shadow_alpha": a, "shadow_luminance": l,
// "ground_tolerance": t}; a run or polygon without a mode sets it.
FootprintSpec footprint_from(const json& j, const std::string& where);
// The footprint as footprint_from reads it; an empty object for the default.
json footprint_json(const FootprintSpec& f);

}  // namespace isolux
