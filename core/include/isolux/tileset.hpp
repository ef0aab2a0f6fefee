// A tileset: floor blocks and overlay sprites (paper section 3, Figure 2).
#pragma once
#include <optional>
#include <string_view>
#include <utility>
#include <string>
#include <vector>

#include <cstdint>

#include "isolux/image.hpp"
#include "isolux/solid.hpp"

namespace isolux {

enum class SpriteKind { floor, overlay };

enum class FootprintMode {
    automatic,  // "auto": Algorithm 1 after removing a baked ground diamond and baked shadows
    paper,      // Algorithm 1 exactly as the paper writes it
    none,       // no obstacle
    run,        // a given run (Algorithm 1's s), with the paper's arms
    polygon,    // a given polygon
};
std::string_view to_string(FootprintMode m);

// Beyond the paper: the kind of solid an object estimated from a sprite's
// alpha is (solid_estimate.hpp, docs/beyond.md).
enum class ObjectModel {
    revolution,  // a stack of cross-sections about a vertical axis: trees, towers, bushes
    prism,       // a footprint rectangle extruded upward: walls, fences, houses, town blocks
    mound,       // a half ellipsoid resting on its base: rocks, hills, mountains
};
std::string_view to_string(ObjectModel m);
// The model a name spells ("revolution", "prism", "mound"), none for another name.
std::optional<ObjectModel> object_model_named(std::string_view name);

// A sprite's footprint settings (the manifest's "footprint" and thresholds).
struct FootprintSpec {
    std::optional<FootprintMode> mode;              // unset: the preset's `footprint`
    int run_x = 0, run_y = 0, run_length = 0;      // run: its left pixel and length, sprite pixels
    std::vector<std::pair<int, int>> polygon;       // polygon: its corners, sprite pixels
    double shadow_alpha = 0.9;       // auto: a pixel under this alpha...
    double shadow_luminance = 0.08;  // ...and darker than this (0..1) is a baked shadow
    double ground_tolerance = 0.16;  // auto: colour distance (0..1) within which a diamond pixel is ground
    // A user's correction of the solid estimated from the alpha (beyond the
    // paper): where its axis meets the ground, sprite pixels, and the top of
    // its solid above the ground (0: the estimate's own).
    std::optional<std::pair<int, int>> object_foot;
    int object_height = 0;
    std::optional<ObjectModel> object_model;  // unset: the model that fits the silhouette best
    friend bool operator==(const FootprintSpec&, const FootprintSpec&) = default;
};

// How far a sprite's anchor and its footprint's points may lie from the
// sprite's top-left, pixels, in manifests and TMX alike: as far as the
// largest image isolux reads is wide.
inline constexpr int max_sprite_offset = 65536;
// The solids all of a tileset's shapes may hold together: tracing against
// shapes and the 3D reference test each one at every placed sprite.
inline constexpr std::size_t max_tileset_solids = 1000;

struct Sprite {
    std::string name;
    SpriteKind kind = SpriteKind::overlay;
    std::vector<std::string> tags;  // floors: grass dirt sand stone water; overlays: tree bush rock wall
    Image image;                    // the sprite's pixels, cut from its sheet
    int anchor_x = 0, anchor_y = 0; // sprite pixel placed on the tile's centre
    std::optional<double> opacity_threshold;  // overrides the preset's when set
    // The true 3D volume (optional): solids relative to the anchor, pixels (solid.hpp).
    std::vector<Solid> shape;
    // The true visible surface height above the ground per pixel, pixels
    // (optional: empty, or width x height values from the manifest's height_map).
    std::vector<std::uint16_t> height;
    // Where it meets the ground (footprint.hpp): the manifest's "footprint".
    FootprintSpec footprint;

    bool has_tag(std::string_view t) const;
};

struct Tileset {
    int tile_width = 128, tile_height = 64;  // the floor diamond, pixels
    std::vector<Sprite> sprites;
    std::string source;  // the manifest's path, for messages

    // Indices of sprites of `kind` carrying `tag`; all of that kind's untagged
    // sprites when none carries it (the manifest contract: untagged sprites are
    // used at random).
    std::vector<int> find(SpriteKind kind, std::string_view tag) const;
};

// Checks the rules a tileset must meet to build maps (at least one floor
// sprite, non-empty sprites, sane tile size, an object's height within its
// image, at most max_tileset_solids solids in all); throws Error naming the
// entry.
void validate(const Tileset& t);

}  // namespace isolux
