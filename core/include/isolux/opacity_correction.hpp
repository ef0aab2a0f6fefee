// Paper 3.2, Figures 6 and 7: opacity maps added to or subtracted from a
// light's traced pixels.
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/light_trace.hpp"
#include "isolux/map.hpp"

namespace isolux {

// For every overlay sprite that meets the light's mask, in draw order (back to
// front, so the sprite in front decides a shared pixel): a sprite that stands
// above the light's centre on screen (its ground point's y < the centre's y,
// i.e. behind the light) has its opacity map added: its opaque pixels get the
// light's intensity at their distance; any other sprite's opaque pixels
// become unlit. `opacity` holds one
// opacity map per tileset sprite. Returns how many sprites it touched.
//
// The add/subtract rule, on its own (the app's overlay shows it): whether a
// sprite's opacity map is added to a light centred at row `light_cy`.
// "Stands" means where the sprite meets the ground (its anchor), not its top
// or centre: a tall tree behind a light stands above it even when its canopy
// reaches below the light's centre on screen.
inline bool opacity_map_added(const SpriteInstance& sprite, std::int64_t light_cy) {
    return sprite.ground_y < light_cy;
}

int correct_with_opacity_maps(LightMask& mask, const PlacedMap& placed, const std::vector<Mask>& opacity);

// The same correction from a structure built once per world: for each pixel,
// where the sprite that decides it (the last drawn overlay opaque there)
// meets the ground, stored as ground_y - y in 16 bits (`none`: no opaque
// sprite). The rule above then reads, per pixel, "none: keep; stands above
// the light's centre: its intensity; otherwise: unlit", one branch-free pass
// over the light's area whatever the number of sprites. Applying it twice
// gives the same bytes (a pixel is kept, or set from the lines alone).
//
// The pass reads a byte per pixel: below8 = below + 128 (1..255 for below in
// [-127, 127], 0 for none), so that "stands above" is one unsigned compare
// against a per-row threshold. A row holding a value outside that range (a
// sprite pixel 128+ rows from its ground) is read from `below` instead.
struct GroundLines {
    static constexpr std::int16_t none = INT16_MIN;
    Rect rect;                            // world pixels it covers (elsewhere: none)
    std::vector<std::int16_t> below;      // ground_y - y per pixel, or none
    std::vector<std::uint8_t> below8;     // the same in a byte where it fits
    std::vector<std::uint32_t> wide;      // per row of rect: pixels whose below does not fit a byte
    bool exact = true;                    // false when a sprite's ground is 32766+ rows from its pixels
};

// Paints the overlays' opacity maps over `region` in draw order.
GroundLines ground_lines(const PlacedMap& placed, const std::vector<Mask>& opacity, Rect region);
// Paints `part` again (after an edit), within the lines' rectangle.
void repaint_ground_lines(GroundLines& lines, const PlacedMap& placed, const std::vector<Mask>& opacity, Rect part);
// Moves the lines to `region` (a pan, or a region grown or cut): the pixels
// both rectangles hold keep their values, the rest is painted.
void pan_ground_lines(GroundLines& lines, const PlacedMap& placed, const std::vector<Mask>& opacity, Rect region);

// correct_with_opacity_maps's bytes from the ground lines (which must be
// exact). It reads no sprite, so it does not count them.
void correct_with_ground_lines(LightMask& mask, const GroundLines& lines);

}  // namespace isolux
