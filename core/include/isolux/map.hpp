// Seeded isometric maps (paper section 3): W x H tiles, each a floor block plus
// up to 3 overlay sprites, placed by one of three layouts.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

enum class Layout {
    paper,      // section 3's assembly rule, as written (a parallelogram of blocks)
    diamond,    // Tiled's "isometric" orientation
    staggered,  // Tiled's "staggered" orientation (stagger axis y, odd rows shifted)
};

std::string_view to_string(Layout l);
Layout parse_layout(std::string_view s, std::string_view source);  // throws Error

// One overlay on a tile: a sprite and its offset from the tile's centre, pixels.
struct Overlay {
    int sprite = -1;
    int dx = 0, dy = 0;
    friend bool operator==(const Overlay&, const Overlay&) = default;
};

struct Tile {
    int floor = -1;
    int overlay_count = 0;
    std::array<Overlay, 3> overlays{};
    friend bool operator==(const Tile&, const Tile&) = default;
};

struct Map {
    int width = 0, height = 0;  // tiles
    Layout layout = Layout::diamond;
    int tile_width = 128, tile_height = 64;
    std::vector<Tile> tiles;  // row-major, width * height
    const Tile& at(int col, int row) const { return tiles[std::size_t(row) * width + col]; }
};

// A map's size: each side up to max_map_side tiles, and at most
// max_map_tiles tiles in all, what bounds its memory (a 1024 x 1024 map
// renders in about 400 MB): a long strip may reach 4096 tiles where a square
// stops at 1024. An endless world (endless.hpp) has no size.
inline constexpr int max_map_side = 4096;
inline constexpr long long max_map_tiles = 1LL << 20;
inline bool map_size_ok(long long width, long long height) {
    return width >= 1 && height >= 1 && width <= max_map_side && height <= max_map_side && width * height <= max_map_tiles;
}
// The rule map_size_ok holds, for messages.
inline const char* map_size_rule() { return "each side in [1, 4096] tiles and at most 1048576 tiles (1024x1024)"; }

// Generates the map for `seed` deterministically: biome noise (elevation and
// moisture) picks water, sand, meadow, forest, dirt and stone regions; each
// biome picks its floor and 0 to 3 overlays. Throws Error on a size that
// map_size_ok refuses or a tileset without floors. Tile (col, row) holds what
// the seed gives tile (col0 + col, row0 + row): a tile's content depends on
// the seed and its own coordinates only, so a larger map extends a smaller
// one and an endless world is any window of tiles (endless.hpp).
Map generate_map(std::string_view seed, int width, int height, Layout layout, const Tileset& tileset,
                 std::int64_t col0 = 0, std::int64_t row0 = 0);

struct Pcg32;
// The overlay generate_map puts on a tile as its `index`-th (0, 1, 2): one of
// four slots inside the diamond, jittered by `rng`. Hand edits place theirs
// by the same rule (edits.hpp).
Overlay make_overlay(int sprite, int index, int tile_width, int tile_height, Pcg32& rng);

// One sprite placed in the world. World pixels: the map's bounding box starts
// at (0, 0).
struct SpriteInstance {
    int sprite = -1;
    int x = 0, y = 0;            // the sprite image's top-left
    int ground_x = 0, ground_y = 0;  // where it stands: its anchor in world pixels
    int tile = -1;               // index into Map::tiles
    int w = 0, h = 0;            // the sprite image's size
    int layer = 0;               // 0: the tile's floor; 1..3: its overlays
};

inline constexpr std::uint32_t no_instance = 0xFFFFFFFFu;

// Every sprite of the map. Draw order (back to front): all floor blocks by
// their tile's depth, then all overlays by their ground point, so an overlay is
// never covered by a flat floor in front of it. As placed, `instances` is in
// draw order; after hand edits (replace_tile) removed overlays leave dead
// slots (sprite -1) and new ones may sit anywhere past first_overlay, so
// walk the map with draw_order() or instances_in(), never by index.
struct PlacedMap {
    // World pixels covered by any sprite. The world's origin is the seeded
    // map's top-left, so bounds start at (0, 0) unless edits reach further.
    Rect bounds;
    std::vector<SpriteInstance> instances;
    std::size_t first_overlay = 0;  // instances[..first_overlay] are the floors, in draw order
    int shift_x = 0, shift_y = 0;   // world = layout pixels + shift (tile_center's frame to the world's)

    // A grid of `cell`-pixel squares from (grid_x, grid_y) over every place a
    // tileset sprite can stand on the map: each lists the instances whose
    // rectangle meets it, so a frame or an edit touches only the sprites near
    // it, whatever the map's size.
    int cell = 256, grid_x = 0, grid_y = 0, grid_w = 0, grid_h = 0;
    std::vector<std::vector<std::uint32_t>> grid;

    // Per tile, its floor's and overlays' instances (no_instance when none).
    std::vector<std::array<std::uint32_t, 4>> tile_instances;
    std::vector<std::uint32_t> free_slots;  // dead overlay slots, reused by edits
    bool in_index_order = true;             // instances' indices are still their draw order (no overlay edited)
};

// Whether instance `a` is drawn before instance `b`.
bool draws_before(const PlacedMap& placed, std::uint32_t a, std::uint32_t b);

// Every live instance in draw order (overlays only when `overlays_only`).
std::vector<std::uint32_t> draw_order(const PlacedMap& placed, bool overlays_only = false);

// The instances whose rectangle (grown by `margin` pixels) meets `r`, in draw
// order; overlays only when `overlays_only`. Without a grid (a hand-built
// PlacedMap), every instance is tested.
void instances_in(const PlacedMap& placed, Rect r, bool overlays_only, std::vector<std::uint32_t>& out,
                  int margin = 0);

// The grid cells a world rectangle meets, clamped to the grid.
struct CellRange {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};
inline CellRange cells_of(const PlacedMap& p, Rect r) {
    CellRange c;
    const Rect q = intersect(r, Rect{p.grid_x, p.grid_y, p.grid_w * p.cell, p.grid_h * p.cell});
    if (q.empty()) return c;
    c.x0 = (q.x - p.grid_x) / p.cell;
    c.y0 = (q.y - p.grid_y) / p.cell;
    c.x1 = (q.x + q.w - 1 - p.grid_x) / p.cell;
    c.y1 = (q.y + q.h - 1 - p.grid_y) / p.cell;
    return c;
}

// How many instances meet `r` and satisfy `meets`, each counted once:
// instances_in's count without its sorts, for callers that need no order.
template <class Meets>
std::size_t count_instances_in(const PlacedMap& placed, Rect r, bool overlays_only, Meets&& meets) {
    const std::size_t first = overlays_only ? placed.first_overlay : 0;
    auto counts = [&](const SpriteInstance& in) {
        return in.sprite >= 0 && !intersect({in.x, in.y, in.w, in.h}, r).empty() && meets(in);
    };
    std::size_t n = 0;
    if (placed.grid.empty()) {
        for (std::size_t i = first; i < placed.instances.size(); ++i) n += counts(placed.instances[i]);
        return n;
    }
    // A sprite over several cells is listed in each: it counts in the cell
    // holding the top-left of its overlap with the query (the grid holds
    // every sprite, so that corner lies in the grid), tested without dividing.
    const CellRange c = cells_of(placed, r);
    for (int cy = c.y0; cy <= c.y1; ++cy)
        for (int cx = c.x0; cx <= c.x1; ++cx) {
            const int x0 = placed.grid_x + cx * placed.cell, y0 = placed.grid_y + cy * placed.cell;
            for (std::uint32_t i : placed.grid[std::size_t(cy) * placed.grid_w + cx]) {
                if (i < first) continue;
                const SpriteInstance& in = placed.instances[i];
                const int corner_x = in.x > r.x ? in.x : r.x, corner_y = in.y > r.y ? in.y : r.y;
                if (corner_x < x0 || corner_x >= x0 + placed.cell || corner_y < y0 || corner_y >= y0 + placed.cell) continue;
                n += counts(in);
            }
        }
    return n;
}

// Places every tile's sprites. The world's origin is the top-left of what
// they cover, unless `origin_of` is given: then it is that map's (a seeded
// map's, so that its edited copy keeps the same world pixels).
PlacedMap place_sprites(const Map& map, const Tileset& tileset, const PlacedMap* origin_of = nullptr);

// Completes a PlacedMap built by hand (instances in draw order, floors
// first): its bounds and grid. Such a map is lit and drawn, not edited.
void finish_placed(PlacedMap& placed);

// Gives tile (col, row) of `placed` the sprites of `tile`, in place, touching
// only the grid cells they cover: an edit costs what it touches, not the
// map's size. `map` holds the tile's placement (layout and tile size).
// Returns the world rectangle whose pixels may have changed (the old and the
// new sprites'); empty when the tile already held exactly these sprites.
Rect replace_tile(PlacedMap& placed, const Map& map, const Tileset& tileset, int col, int row, const Tile& tile);

// The centre of tile (col, row) in layout pixels, before PlacedMap's shift.
void tile_center(Layout layout, int tile_w, int tile_h, int col, int row, int& x, int& y);
// The same for any tile of an endless world (endless.hpp), 64-bit.
void tile_center(Layout layout, int tile_w, int tile_h, std::int64_t col, std::int64_t row, std::int64_t& x,
                 std::int64_t& y);

// The tile whose floor diamond holds world pixel (wx, wy); false when none does.
bool tile_at(const Map& map, const PlacedMap& placed, double wx, double wy, int& col, int& row);

// Draws the instances overlapping `view` (world pixels) back to front, alpha
// over a transparent background.
Image render_sprites(const Tileset& tileset, const PlacedMap& placed, Rect view);

}  // namespace isolux
