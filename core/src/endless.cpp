// Beyond the paper: endless seeded worlds (endless.hpp).
#include "isolux/endless.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/light_texture.hpp"

namespace isolux {

namespace {

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

// The tile nearest an endless-frame pixel, as a real (col, row): tile_center
// inverted (exact for the diamond, and per row for the other two).
void tile_of(Layout layout, int tw, int th, double x, double y, double& col, double& row) {
    const double hw = tw / 2, hh = th / 2;
    switch (layout) {
        case Layout::diamond:
            col = (x / hw + y / hh) / 2;
            row = (y / hh - x / hw) / 2;
            return;
        case Layout::staggered:
            row = y / hh;
            col = x / tw;
            return;
        case Layout::paper:
            row = y / hh;
            col = (x - row * hw) / tw;
            return;
    }
}

}  // namespace

void endless_tile_center(Layout layout, int tw, int th, std::int64_t col, std::int64_t row, std::int64_t& x,
                         std::int64_t& y) {
    tile_center(layout, tw, th, col, row, x, y);
}

void endless_tile_at(Layout layout, int tw, int th, double x, double y, std::int64_t& col, std::int64_t& row) {
    double c = 0, r = 0;
    tile_of(layout, tw, th, x, y, c, r);
    col = std::llround(c);
    row = std::llround(r);
}

int endless_reach(const Scene& scene, const Tileset& tileset) {
    int area = std::max(scene.params.area_a, scene.params.area_b);
    for (const Light& l : scene.lights) area = std::max({area, l.area_a.value_or(0), l.area_b.value_or(0)});
    int sprite = 0;
    for (const Sprite& s : tileset.sprites) sprite = std::max({sprite, s.image.width, s.image.height});
    return 2 * area + sprite + 2 * tileset.tile_height;
}

ChunkRange endless_chunks(const Tileset& tileset, Layout layout, WorldRect view, int reach, std::string_view source) {
    const int tw = tileset.tile_width, th = tileset.tile_height;
    double c0 = 1e300, c1 = -1e300, r0 = 1e300, r1 = -1e300;
    const double x0 = double(view.x) - reach, x1 = double(view.x) + view.w + reach;
    const double y0 = double(view.y) - reach, y1 = double(view.y) + view.h + reach;
    for (double x : {x0, x1})
        for (double y : {y0, y1}) {
            double c = 0, r = 0;
            tile_of(layout, tw, th, x, y, c, r);
            c0 = std::min(c0, c), c1 = std::max(c1, c), r0 = std::min(r0, r), r1 = std::max(r1, r);
        }
    // A tile's rows and columns past the corners' (the staggered and paper
    // rows shift by half a tile), then whole chunks.
    const double limit = double(max_endless_tile);
    if (!(c0 >= -limit && c1 <= limit && r0 >= -limit && r1 <= limit))
        throw Error(std::string(source) + ": the view at (" + std::to_string(view.x) + ", " + std::to_string(view.y) +
                    ") needs tiles beyond +-" + std::to_string(max_endless_tile) +
                    ", the farthest an endless world reaches");
    const std::int64_t tc0 = std::int64_t(std::floor(c0)) - 2, tc1 = std::int64_t(std::ceil(c1)) + 2;
    const std::int64_t tr0 = std::int64_t(std::floor(r0)) - 2, tr1 = std::int64_t(std::ceil(r1)) + 2;
    ChunkRange out;
    out.col0 = floor_div(tc0, chunk_tiles) * chunk_tiles;
    out.row0 = floor_div(tr0, chunk_tiles) * chunk_tiles;
    const std::int64_t cols = (floor_div(tc1, chunk_tiles) + 1) * chunk_tiles - out.col0;
    const std::int64_t rows = (floor_div(tr1, chunk_tiles) + 1) * chunk_tiles - out.row0;
    if (cols > max_map_side || rows > max_map_side)
        throw Error(std::string(source) + ": a view of " + std::to_string(view.w) + "x" + std::to_string(view.h) +
                    " pixels with lights reaching " + std::to_string(reach) + " pixels past it needs " +
                    std::to_string(cols) + "x" + std::to_string(rows) + " tiles at once, over " +
                    std::to_string(max_map_side) + " a side: use a smaller view or smaller light areas");
    out.cols = int(cols);
    out.rows = int(rows);
    return out;
}

EndlessWindow make_endless_window(Tileset tileset, const Scene& scene, ChunkRange chunks, std::string_view source) {
    EndlessWindow out;
    out.chunks = chunks;
    World& w = out.world;
    w.tileset = std::move(tileset);
    w.seeded = generate_map(scene.seed, chunks.cols, chunks.rows, scene.layout, w.tileset, chunks.col0, chunks.row0);
    // Every edit is checked (a bad sprite name is an error wherever it
    // stands); those inside the window apply, in its own tiles.
    resolve_edits(scene.edits, w.tileset, source);
    std::vector<TileEdit> inside;
    for (const TileEdit& e : scene.edits) {
        const std::int64_t c = std::int64_t(e.col) - chunks.col0, r = std::int64_t(e.row) - chunks.row0;
        if (c < 0 || r < 0 || c >= chunks.cols || r >= chunks.rows) continue;
        TileEdit local = e;
        local.col = c;
        local.row = r;
        inside.push_back(local);
    }
    const std::vector<ResolvedEdit> resolved = resolve_edits(inside, w.tileset, source);
    w.placed = place_sprites(w.seeded, w.tileset);
    w.frame = w.placed.bounds;
    if (resolved.empty()) {
        w.map = w.seeded;
    } else {
        const PlacedMap origin = w.placed;
        w.map = apply_edits(w.seeded, resolved);
        w.placed = place_sprites(w.map, w.tileset, &origin);
    }
    w.edits = inside;
    touch(w);
    // Window pixels are layout pixels of its own tiles plus the shift; its
    // tiles' layout pixels are the endless frame's less its first tile's.
    std::int64_t fx = 0, fy = 0;
    endless_tile_center(scene.layout, w.seeded.tile_width, w.seeded.tile_height, chunks.col0, chunks.row0, fx, fy);
    out.origin_x = fx - w.placed.shift_x;
    out.origin_y = fy - w.placed.shift_y;
    return out;
}

Rect rect_in_window(const EndlessWindow& window, WorldRect view) {
    return Rect{int(view.x - window.origin_x), int(view.y - window.origin_y), view.w, view.h};
}

Scene scene_in_window(const Scene& scene, const EndlessWindow& window, WorldRect view) {
    Scene s = scene;
    s.endless = false;
    s.width = window.chunks.cols;
    s.height = window.chunks.rows;
    s.edits = window.world.edits;
    s.lights.clear();
    const Rect v = rect_in_window(window, view);
    for (const Light& l : scene.lights) {
        // Only lights whose area meets the frame's light texture (the view and
        // FrameOptions' default margin) are traced; far ones are left out
        // before their coordinates shrink to int.
        constexpr int margin = 64;
        const double x = l.x - double(window.origin_x), y = l.y - double(window.origin_y);
        const int a = l.area_a.value_or(scene.params.area_a), b = l.area_b.value_or(scene.params.area_b);
        if (x + a + 1 < v.x - margin || x - a - 1 > v.x + v.w + margin || y + b + 1 < v.y - margin || y - b - 1 > v.y + v.h + margin)
            continue;
        Light in = l;
        in.x = x;
        in.y = y;
        s.lights.push_back(in);
    }
    s.camera = Camera{double(v.x), double(v.y), v.w, v.h};
    return s;
}

FrameReport render_endless_frame(EndlessState& st, const Tileset& tileset, const Scene& scene, WorldRect view,
                                 long frame, std::string_view source) {
    const ChunkRange need = endless_chunks(tileset, scene.layout, view, endless_reach(scene, tileset), source);
    const ChunkRange& have = st.window.chunks;
    const bool holds = st.has_window && need.col0 >= have.col0 && need.row0 >= have.row0 &&
                       need.col0 + need.cols <= have.col0 + have.cols && need.row0 + need.rows <= have.row0 + have.rows;
    if (!holds) {
        ChunkRange grown = need;
        if (need.cols + 2 * chunk_tiles <= max_map_side && need.rows + 2 * chunk_tiles <= max_map_side)
            grown = ChunkRange{need.col0 - chunk_tiles, need.row0 - chunk_tiles, need.cols + 2 * chunk_tiles,
                               need.rows + 2 * chunk_tiles};
        st.window = make_endless_window(tileset, scene, grown, source);
        st.has_window = true;
        st.frame = FrameState{st.frame.options};
        ++st.windows_built;
    }
    const Rect v = rect_in_window(st.window, view);
    return render_frame(st.frame, st.window.world, scene_in_window(scene, st.window, view), Camera{double(v.x), double(v.y), v.w, v.h},
                        frame);
}

}  // namespace isolux
