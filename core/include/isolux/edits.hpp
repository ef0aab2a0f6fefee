// Beyond the paper: the level as the seed's map plus hand edits. A scene's
// "edits" (scene.hpp, TileEdit) override tiles of the map its seed grows;
// names are resolved against the tileset here, once, so the rest of the
// pipeline sees plain sprite indices.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "isolux/map.hpp"
#include "isolux/scene.hpp"

namespace isolux {

// An edit with its names resolved to sprite indices.
struct ResolvedEdit {
    std::int64_t col = 0, row = 0;
    std::optional<int> floor;
    std::optional<std::vector<int>> overlays;
};

// Resolves every edit's names. Throws Error naming `source`, the entry
// (edits[i]) and the name when a name is not a sprite of the right kind, or
// an entry holds more than 3 overlays. The first sprite of a name counts.
std::vector<ResolvedEdit> resolve_edits(const std::vector<TileEdit>& edits, const Tileset& tileset,
                                        std::string_view source);

// One warning per edit whose tile lies outside a `width` x `height` map
// (kept in the scene, not applied).
void warn_edits_outside(const std::vector<TileEdit>& edits, int width, int height, std::string_view source,
                        std::vector<std::string>& warnings);

// Tile (col, row) of `seeded` after `edits` (later entries override earlier
// ones field by field). Overlays keep the seed's placement while they match
// the seed's list from its start; others take make_overlay's slot rule with
// jitter from the tile's own position, so the same edits place the same
// pixels on every machine.
Tile edited_tile(const Map& seeded, int col, int row, const std::vector<const ResolvedEdit*>& edits);

// The seeded map with every edit applied.
Map apply_edits(const Map& seeded, const std::vector<ResolvedEdit>& edits);

// What an editor's brush writes: tile (col, row) is to hold `floor` and
// `overlays` (sprite indices). Every entry for that tile is replaced by one
// holding exactly what differs from the seeded tile, or none when nothing
// does, so the file lists only real changes.
void set_tile_edit(std::vector<TileEdit>& edits, const Map& seeded, const Tileset& tileset, int col, int row,
                   int floor, const std::vector<int>& overlays);

// The sprites a tile holds: its floor and its overlays' sprites.
std::vector<int> overlay_sprites(const Tile& tile);

}  // namespace isolux
