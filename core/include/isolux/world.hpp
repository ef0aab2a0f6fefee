// A scene's world: its tileset, the map generated from its seed with the
// scene's edits applied, and the placed sprites. Built once per seed, size,
// layout or tileset change; edits change it in place (set_edits).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "isolux/map.hpp"
#include "isolux/scene.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

struct World {
    Tileset tileset;
    Map seeded;                   // the seed's map, before edits
    Map map;                      // the level: the seeded map with `edits` applied
    PlacedMap placed;
    std::vector<TileEdit> edits;  // the edits `map` holds
    // The picture of the whole map (a camera with no size): the seeded map's
    // bounds, its tiles and the seed's own sprites, so an edit that removes
    // or adds a sprite on the edge never moves where a world pixel lands in
    // the image. Empty (a Tiled map's world): the placed sprites' bounds.
    Rect frame;
    std::uint64_t revision = 0;   // changes whenever the world changes, so caches know

    // What edits changed in place since the world was built (or touched):
    // (revision after the change, world rectangle). A cache built at an
    // earlier revision of this list redoes only those rectangles.
    std::uint64_t built_revision = 0;
    std::vector<std::pair<std::uint64_t, Rect>> changes;
};

// Generates the map for the scene's seed, size and layout on `tileset`,
// applies the scene's edits and places its sprites. Throws Error on a bad size
// or tileset, or an edit naming no sprite of the tileset (naming `source`, the
// scene's file, and the entry). Edits outside the map are kept in the scene
// and reported in `warnings`.
World make_world(Tileset tileset, const Scene& scene, std::string_view source = "scene",
                 std::vector<std::string>* warnings = nullptr);

// Brings the world's map to its seeded map plus `edits`, changing only the
// tiles whose content differs, in place. Throws Error (the world unchanged)
// as make_world does. Returns the world rectangle that changed.
Rect set_edits(World& w, const std::vector<TileEdit>& edits, std::string_view source = "scene");

// One tile of a seeded map to hold `floor` and `overlays` (sprite indices of
// the tileset, of the right kinds): the world's edits get the one entry for
// it that set_tile_edit writes, and only that tile is replaced, so an edit
// costs its tile whatever the edits before it (a brush, the C API). Throws
// Error, the world unchanged, for a tile outside the seeded map. Returns the
// world rectangle that changed.
Rect set_tile(World& w, int col, int row, int floor, const std::vector<int>& overlays);

// The world rectangle changed in place since `revision`; false when the
// world was rebuilt since (or the record is gone): everything changed.
bool changed_since(const World& w, std::uint64_t revision, Rect& region);

// Marks the world changed in place (a sprite's footprint edited, say), so
// every cache built from it is rebuilt.
void touch(World& w);

}  // namespace isolux
