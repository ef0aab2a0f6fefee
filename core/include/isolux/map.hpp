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
};

struct Tile {
    int floor = -1;
    int overlay_count = 0;
    std::array<Overlay, 3> overlays{};
};

struct Map {
    int width = 0, height = 0;  // tiles
    Layout layout = Layout::diamond;
    int tile_width = 128, tile_height = 64;
    std::vector<Tile> tiles;  // row-major, width * height
    const Tile& at(int col, int row) const { return tiles[std::size_t(row) * width + col]; }
};

inline constexpr int max_map_side = 1024;  // tiles; 256 x 256 is the documented minimum we support

// Generates the map for `seed` deterministically: biome noise (elevation and
// moisture) picks water, sand, meadow, forest, dirt and stone regions; each
// biome picks its floor and 0 to 3 overlays. Throws Error on a size outside
// 1..max_map_side or a tileset without floors.
Map generate_map(std::string_view seed, int width, int height, Layout layout, const Tileset& tileset);

// One sprite placed in the world. World pixels: the map's bounding box starts
// at (0, 0).
struct SpriteInstance {
    int sprite = -1;
    int x = 0, y = 0;            // the sprite image's top-left
    int ground_x = 0, ground_y = 0;  // where it stands: its anchor in world pixels
    int tile = -1;               // index into Map::tiles
    int w = 0, h = 0;            // the sprite image's size
};

// Every sprite of the map in draw order (back to front): all floor blocks by
// their tile's depth, then all overlays by their ground point, so an overlay is
// never covered by a flat floor in front of it.
struct PlacedMap {
    Rect bounds;  // world pixels covered by any sprite; x = y = 0
    std::vector<SpriteInstance> instances;
    std::size_t first_overlay = 0;  // instances[first_overlay..] are overlays
    int shift_x = 0, shift_y = 0;   // world = layout pixels + shift (tile_center's frame to the world's)

    // A grid of `cell`-pixel squares over `bounds`: each lists the instances
    // whose rectangle meets it, so a frame touches only the sprites near its
    // view and lights, whatever the map's size.
    int cell = 256, grid_w = 0, grid_h = 0;
    std::vector<std::vector<std::uint32_t>> grid;
};

// The instances whose rectangle (grown by `margin` pixels) meets `r`, in draw
// order; overlays only when `overlays_only`. Without a grid (a hand-built
// PlacedMap), every instance is tested.
void instances_in(const PlacedMap& placed, Rect r, bool overlays_only, std::vector<std::uint32_t>& out,
                  int margin = 0);

PlacedMap place_sprites(const Map& map, const Tileset& tileset);

// The centre of tile (col, row) in layout pixels, before PlacedMap's shift.
void tile_center(Layout layout, int tile_w, int tile_h, int col, int row, int& x, int& y);

// The tile whose floor diamond holds world pixel (wx, wy); false when none does.
bool tile_at(const Map& map, const PlacedMap& placed, double wx, double wy, int& col, int& row);

// Draws the instances overlapping `view` (world pixels) back to front, alpha
// over a transparent background.
Image render_sprites(const Tileset& tileset, const PlacedMap& placed, Rect view);

}  // namespace isolux
