// Beyond the paper: endless seeded worlds. The paper's case is terrain made
// at run time, and a tile's content depends only on the seed and the tile's
// own coordinates (generate_map), so a world needs no edge: what a view
// shows is lit from a window of whole chunks of tiles around it, made on
// demand, and its cost and memory follow the view and the lights' reach,
// never the world (docs/beyond.md, "Endless worlds").
//
// Coordinates: an endless world's tiles and pixels are 64-bit. Its pixel
// frame puts tile (0, 0)'s centre at the layout's origin (tile_center), so a
// tile's pixels never depend on which window holds it. A window is a finite
// World whose pixel (0, 0) lies at `origin` in that frame.
#pragma once
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "isolux/frame.hpp"
#include "isolux/scene.hpp"
#include "isolux/world.hpp"

namespace isolux {

inline constexpr int chunk_tiles = 32;                            // a chunk's side, tiles
inline constexpr int max_window_side = 1024;                      // a window's side at most, tiles
inline constexpr std::int64_t max_endless_tile = 1'000'000'000'000;  // |col|, |row| of any tile shown

// A rectangle of an endless world's pixels.
struct WorldRect {
    std::int64_t x = 0, y = 0;
    int w = 0, h = 0;
    friend bool operator==(const WorldRect&, const WorldRect&) = default;
};

// Tile (col, row)'s centre in the endless frame (tile_center's, 64-bit).
void endless_tile_center(Layout layout, int tile_w, int tile_h, std::int64_t col, std::int64_t row, std::int64_t& x,
                         std::int64_t& y);

// The tile whose centre is nearest endless pixel (x, y) (tile_center
// inverted and rounded; for the staggered and paper layouts, per row).
void endless_tile_at(Layout layout, int tile_w, int tile_h, double x, double y, std::int64_t& col, std::int64_t& row);

// Whole chunks of tiles: [col0, col0 + cols) x [row0, row0 + rows).
struct ChunkRange {
    std::int64_t col0 = 0, row0 = 0;
    int cols = 0, rows = 0;
    friend bool operator==(const ChunkRange&, const ChunkRange&) = default;
};

// The chunks whose tiles light `view`: every tile whose sprites or floor may
// show in it, or stand where a light that reaches it traces (the lights'
// areas, `reach` pixels: endless_reach), grown by a chunk. Throws Error
// naming `source` when a tile beyond +-max_endless_tile would be needed.
ChunkRange endless_chunks(const Tileset& tileset, Layout layout, WorldRect view, int reach, std::string_view source);

// How far past a view an endless world must be built for `scene`: a light
// whose area meets the view stands up to its half-extent outside it, and its
// rays reach as far again; plus the tallest sprite and Algorithm 1's lines.
int endless_reach(const Scene& scene, const Tileset& tileset);

// Chunks and blocks kept across windows, so a walk makes each once: each
// chunk's seeded tiles, and the obstacle map in blocks of the world's pixels
// (a block is built from a window that holds every tile that can reach it,
// then copied into the frames of later windows). Bounded: beyond
// max_kept_chunks chunks or max_obstacle_blocks blocks the oldest are
// dropped. Dropped whole when what they were made from changes (the seed,
// layout, tileset, edits, or a parameter the obstacle map reads).
inline constexpr int obstacle_block = 256;                 // a block's side, pixels
inline constexpr std::size_t max_obstacle_blocks = 256;    // 16 MiB of bits
inline constexpr std::size_t max_kept_chunks = 256;        // 256 chunks of 32x32 tiles
struct EndlessCache {
    using Key = std::pair<std::int64_t, std::int64_t>;
    std::map<Key, std::vector<Tile>> chunks;  // seeded tiles, by chunk (col0 / 32, row0 / 32)
    std::deque<Key> chunk_order;              // oldest first
    std::map<Key, Mask> blocks;               // obstacle bits, by block (x / 256, y / 256)
    std::deque<Key> block_order;
    // What they were made from.
    bool has = false;
    std::string seed;
    Layout layout = Layout::diamond;
    const Tileset* tileset = nullptr;  // the caller's: a tileset changed in place needs a new EndlessState
    std::vector<TileEdit> edits;
    Params params;
    // What was made and what was reused, for tests and benchmarks.
    std::uint64_t chunks_made = 0, chunks_reused = 0, blocks_built = 0, blocks_copied = 0;
};

// A finite window onto an endless world: the scene's seed, layout and edits
// (in the world's own tile coordinates) over `chunks`, placed so that its
// world pixel (x, y) is the endless frame's (origin_x + x, origin_y + y).
struct EndlessWindow {
    ChunkRange chunks;
    std::int64_t origin_x = 0, origin_y = 0;
    World world;
};
EndlessWindow make_endless_window(Tileset tileset, const Scene& scene, ChunkRange chunks,
                                  std::string_view source = "scene", EndlessCache* cache = nullptr);

// The scene's lights and camera moved into the window's pixels (lights whose
// area cannot meet `view` are left out: the window may not hold what they
// stand on), and `view` with them.
Scene scene_in_window(const Scene& scene, const EndlessWindow& window, WorldRect view);
Rect rect_in_window(const EndlessWindow& window, WorldRect view);

// A walk through an endless world: the window and the frame state lit from
// it. Default-constructed: nothing built yet.
struct EndlessState {
    EndlessWindow window;
    bool has_window = false;
    FrameState frame;       // its options are the caller's (obstacle_map is set by render_endless_frame)
    std::uint64_t windows_built = 0;
    EndlessCache cache;
};

// One frame of `view` (endless pixels): the window is kept while it holds
// every chunk the view needs, else made anew around them with a chunk to
// spare on every side (so a walking camera remakes it once a chunk, not
// once a frame), and the frame state starts afresh on it: its seeded chunks
// and obstacle blocks come from st.cache where an earlier window made them.
// The frame's pixels do not depend on which window holds the view.
// `tileset` is copied into each window.
FrameReport render_endless_frame(EndlessState& st, const Tileset& tileset, const Scene& scene, WorldRect view,
                                 long frame, std::string_view source = "scene");

}  // namespace isolux
