// A scene: what a user saves and reloads (seed, map, tileset, preset, lights,
// camera).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "isolux/map.hpp"
#include "isolux/params.hpp"

namespace isolux {

struct Light {
    double x = 0, y = 0;                 // centre, world pixels
    std::optional<int> area_a, area_b;   // half-extents; the preset's when unset
    std::uint8_t r = 255, g = 255, b = 255;
    double intensity = 1.0;              // scales the paper's 255 / (1 + d)
    std::optional<double> height;        // above the ground, pixels; the preset's light_height when unset
    std::string name;                    // the editor's label; empty: "light N"
    bool hidden = false;                 // kept in the scene, not rendered
    bool locked = false;                 // the editor does not move or delete it

    friend bool operator==(const Light&, const Light&) = default;
};

// The view onto the world. width/height 0 mean "the whole map".
struct Camera {
    double x = 0, y = 0;  // top-left, world pixels
    int width = 0, height = 0;
    friend bool operator==(const Camera&, const Camera&) = default;
};

// One hand edit over the seeded map (docs/guide.md, "Edits"): the tile's
// column and row as the layout numbers them, and what replaces the seed's
// content there. Names are the tileset's sprite names. A later edit of the
// same tile overrides an earlier one field by field.
struct TileEdit {
    std::int64_t col = 0, row = 0;  // 64-bit: an endless world's tiles reach +-max_edit_tile
    std::optional<std::string> floor;                  // unset: the seed's (or an earlier edit's) floor
    std::optional<std::vector<std::string>> overlays;  // unset: unchanged; empty: no overlays

    friend bool operator==(const TileEdit&, const TileEdit&) = default;
};

inline constexpr std::int64_t max_edit_tile = 1'000'000'000'000;  // |col|, |row| of an edit (endless.hpp's bound)
inline constexpr const char* default_seed = "isolux";
inline constexpr int default_map_side = 16;

struct Scene {
    std::string seed = default_seed;
    int width = default_map_side, height = default_map_side;
    bool endless = false;  // no edge: width and height unused, lit around a view (endless.hpp)
    Layout layout = Layout::diamond;
    std::string tileset;  // manifest path; empty: the default tileset
    std::string map;      // a Tiled map (.tmx) this scene lights instead of a seeded one; empty: seeded
    Params params;
    std::vector<Light> lights;
    Camera camera;
    std::vector<TileEdit> edits;  // the level: the seed's map plus these, in order

    friend bool operator==(const Scene&, const Scene&) = default;
};

}  // namespace isolux
