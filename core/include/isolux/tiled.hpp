// Tiled maps (TMX, https://doc.mapeditor.org/en/stable/reference/tmx-map-format/):
// a level out of isolux into any engine's Tiled importer, and Tiled's
// isometric and staggered maps into isolux to be lit. File I/O like file_io.hpp:
// every reader throws Error naming the file and the element; every writer is
// atomic. The rules (which layer is the floor, how sprites are anchored, the
// paper layout's nearest form) are in docs/guide.md, "Tiled maps".
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "isolux/frame.hpp"
#include "isolux/scene.hpp"
#include "isolux/world.hpp"

namespace isolux {

struct TiledExport {
    bool images = false;  // the light texture and the final frame as image layers (PNG beside the map)
    // An infinite map (infinite="1"): tile layers as <chunk>s of chunk x
    // chunk tiles from tile (0, 0), the last ones cut to the map's edge, so
    // the chunks cover the map's cells exactly and Tiled draws it as the
    // finite map. 0: a finite map.
    int chunk = 0;
    // Run even when export_memory is beyond huge_render_bytes (isolux-cli's
    // --allow-huge); otherwise such an export is refused before any file.
    bool allow_huge = false;
    // Each sprite's normal map and height map (sprite_shading.hpp) beside its
    // image (NAME.normal.png, NAME.height.png, opengl's convention), named in
    // its tile's properties `normal_map` and `isolux_height_map`; from the
    // scene's sprite_shading, or the estimated solids when that is none.
    bool normal_maps = false;
};

// The memory an export holds at its peak, estimated from the map's pixels:
// the obstacle map built over the whole map, and its polygons as XML objects
// (export_pixel_bytes a pixel: isolux-cli's peak over a 128x128 seeded map's
// 137 megapixels is 1.47 GB), and with `images` a lit frame of it
// (render_memory).
inline constexpr double export_pixel_bytes = 11;
double export_memory(const World& world, const TiledExport& options);

// Writes `tmx` (DIR/NAME.tmx) for the scene's level: floors as a tile layer
// (diamond: an isometric map; staggered: a staggered one; paper: floors as
// tile objects, the sheared grid having no Tiled form), overlays as tile
// objects in draw order, an object layer `lights` (one point each, with
// color, a, b, intensity and height properties), an object layer
// `obstacles` (the obstacle map as polygons), the preset's parameters as map
// properties, and the tilesets as external TSX files (NAME_floors.tsx,
// NAME_overlays.tsx) with their images in NAME_images/. Where no map isolux
// exported stands at `tmx`, a file or folder already under one of those
// names is refused by name (Error), never replaced. Returns the world
// pixel that Tiled's map pixel (0, 0) is (also written as the map
// properties isolux_origin_x and isolux_origin_y).
std::pair<int, int> export_tiled(const World& world, const Scene& scene, const std::filesystem::path& tmx,
                                 const TiledExport& options = {});

// A Tiled map loaded as isolux's world: its own tileset (each tile used, as
// drawn: anchored and flipped as Tiled draws it), the sprites placed exactly
// where Tiled draws them and in its order, the `lights` layer as lights and
// the map properties as the preset.
struct TiledMap {
    Scene scene;
    World world;
    std::vector<std::string> warnings;
    int origin_x = 0, origin_y = 0;  // the world pixel of Tiled's screen pixel (0, 0)
};
TiledMap load_tiled(const std::filesystem::path& tmx);

// Limits a TMX file may not exceed: tiles per map side and in all (as
// isolux's own maps: map_size_ok), and layers (each is width x height tiles
// once decoded: a compression bomb is refused at that size, not inflated).
inline constexpr int max_tiled_side = max_map_side;
inline constexpr int max_tiled_layers = 256;
// Sprites a map may draw in all layers (4M: four full layers of a 1024x1024
// map), and sprite pixels it may load in all its tilesets
// (max_input_sprite_pixels): a small file cannot ask for gigabytes.
inline constexpr int max_tiled_sprites = 1 << 22;

}  // namespace isolux
