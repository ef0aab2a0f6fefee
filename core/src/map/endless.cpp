// Beyond the paper: endless seeded worlds (endless.hpp).
#include "isolux/endless.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/params.hpp"

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

// The seeded tiles of `chunks`, each chunk's from the cache or generated
// (a tile's content is its seed's and its own coordinates', so a chunk made
// alone has the tiles it has in any window).
Map seeded_from_chunks(const Scene& scene, const Tileset& ts, ChunkRange chunks, EndlessCache& cache) {
    Map m;
    m.width = chunks.cols;
    m.height = chunks.rows;
    m.layout = scene.layout;
    m.tile_width = ts.tile_width;
    m.tile_height = ts.tile_height;
    m.tiles.resize(std::size_t(chunks.cols) * chunks.rows);
    for (int j = 0; j < chunks.rows / chunk_tiles; ++j)
        for (int i = 0; i < chunks.cols / chunk_tiles; ++i) {
            const EndlessCache::Key key{floor_div(chunks.col0, chunk_tiles) + i, floor_div(chunks.row0, chunk_tiles) + j};
            auto it = cache.chunks.find(key);
            if (it == cache.chunks.end()) {
                Map c = generate_map(scene.seed, chunk_tiles, chunk_tiles, scene.layout, ts, key.first * chunk_tiles,
                                     key.second * chunk_tiles);
                it = cache.chunks.emplace(key, std::move(c.tiles)).first;
                cache.chunk_order.push_back(key);
                ++cache.chunks_made;
            } else {
                ++cache.chunks_reused;
            }
            for (int r = 0; r < chunk_tiles; ++r)
                std::copy_n(&it->second[std::size_t(r) * chunk_tiles], chunk_tiles,
                            &m.tiles[std::size_t(j * chunk_tiles + r) * chunks.cols + std::size_t(i) * chunk_tiles]);
        }
    while (cache.chunks.size() > max_kept_chunks) {
        cache.chunks.erase(cache.chunk_order.front());
        cache.chunk_order.pop_front();
    }
    return m;
}

// The cache holds what `scene` and `tileset` make, or is emptied. Returns
// whether the world itself changed (seed, layout, tileset or edits): a
// window made before no longer shows it.
bool sync_cache(EndlessCache& c, const Scene& scene, const Tileset& tileset) {
    const bool same_world =
        c.has && c.seed == scene.seed && c.layout == scene.layout && c.tileset == &tileset && c.edits == scene.edits;
    if (same_world && !stages_changed(c.params, scene.params).has(Stage::obstacle_map)) return false;
    c.chunks.clear();
    c.chunk_order.clear();
    c.blocks.clear();
    c.block_order.clear();
    c.has = true;
    c.seed = scene.seed;
    c.layout = scene.layout;
    c.tileset = &tileset;
    c.edits = scene.edits;
    c.params = scene.params;
    return !same_world;
}

// The obstacle map over `region` of the window, a block of the world's
// pixels at a time: copied where an earlier window built the block; built
// and kept where this window holds every tile that can reach it (the tiles
// within the tallest sprite, two tiles and the noise window of it); built
// for this region alone where it does not.
Mask obstacles_from_blocks(EndlessState& st, const Tileset& tileset, const Scene& scene, const World& world,
                           const Params& p, Rect region, const std::vector<Mask>& footprints) {
    EndlessCache& c = st.cache;
    const EndlessWindow& win = st.window;
    Mask out(region);
    if (region.empty()) return out;
    int margin = p.noise_window + 2 * tileset.tile_height;
    for (const Sprite& s : tileset.sprites) margin = std::max(margin, std::max(s.image.width, s.image.height) + p.noise_window);
    const std::int64_t B = obstacle_block;
    const std::int64_t wx0 = region.x + win.origin_x, wy0 = region.y + win.origin_y;
    // Copies `m`, whose pixel (0, 0) is the window's (x0, y0), into `out`.
    auto copy = [&](const Mask& m, int x0, int y0) {
        const Rect part = intersect(Rect{x0, y0, m.width, m.height}, region);
        for (int y = part.y; y < part.y + part.h; ++y)
            std::copy_n(&m.bits[std::size_t(y - y0) * m.width + std::size_t(part.x - x0)], part.w,
                        &out.bits[std::size_t(y - region.y) * region.w + std::size_t(part.x - region.x)]);
    };
    for (std::int64_t by = floor_div(wy0, B); by <= floor_div(wy0 + region.h - 1, B); ++by)
        for (std::int64_t bx = floor_div(wx0, B); bx <= floor_div(wx0 + region.w - 1, B); ++bx) {
            const EndlessCache::Key key{bx, by};
            const Rect in_window{int(bx * B - win.origin_x), int(by * B - win.origin_y), int(B), int(B)};
            if (auto it = c.blocks.find(key); it != c.blocks.end()) {
                copy(it->second, in_window.x, in_window.y);
                ++c.blocks_copied;
                continue;
            }
            bool complete = false;
            try {
                const ChunkRange need = endless_chunks(tileset, scene.layout, WorldRect{bx * B, by * B, int(B), int(B)}, margin, "");
                const ChunkRange& have = win.chunks;
                complete = need.col0 >= have.col0 && need.row0 >= have.row0 && need.col0 + need.cols <= have.col0 + have.cols &&
                           need.row0 + need.rows <= have.row0 + have.rows;
            } catch (const Error&) {
            }
            if (!complete) {
                const Mask part = build_obstacle_map(world.tileset, world.placed, p, intersect(in_window, region), &footprints);
                copy(part, part.x0, part.y0);
                continue;
            }
            Mask m = build_obstacle_map(world.tileset, world.placed, p, in_window, &footprints);
            copy(m, m.x0, m.y0);
            c.blocks.emplace(key, std::move(m));
            c.block_order.push_back(key);
            ++c.blocks_built;
        }
    while (c.blocks.size() > max_obstacle_blocks) {
        c.blocks.erase(c.block_order.front());
        c.block_order.pop_front();
    }
    return out;
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
    // The same cap as a bounded map's view: an endless view is no cheaper a pixel.
    if ((long long)view.w * view.h > max_render_pixels)
        throw Error(std::string(source) + ": a view of " + std::to_string(view.w) + "x" + std::to_string(view.h) +
                    " pixels is over the " + std::to_string(max_render_pixels >> 20) +
                    "-megapixel limit: show a smaller part of the endless world");
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
    if (cols > max_window_side || rows > max_window_side)
        throw Error(std::string(source) + ": a view of " + std::to_string(view.w) + "x" + std::to_string(view.h) +
                    " pixels with lights reaching " + std::to_string(reach) + " pixels past it needs " +
                    std::to_string(cols) + "x" + std::to_string(rows) + " tiles at once, over " +
                    std::to_string(max_window_side) + " a side: use a smaller view or smaller light areas");
    out.cols = int(cols);
    out.rows = int(rows);
    return out;
}

EndlessWindow make_endless_window(Tileset tileset, const Scene& scene, ChunkRange chunks, std::string_view source,
                                  EndlessCache* cache) {
    EndlessWindow out;
    out.chunks = chunks;
    World& w = out.world;
    w.tileset = std::move(tileset);
    const bool whole_chunks = chunks.col0 % chunk_tiles == 0 && chunks.row0 % chunk_tiles == 0 &&
                              chunks.cols % chunk_tiles == 0 && chunks.rows % chunk_tiles == 0;
    w.seeded = cache && whole_chunks
                   ? seeded_from_chunks(scene, w.tileset, chunks, *cache)
                   : generate_map(scene.seed, chunks.cols, chunks.rows, scene.layout, w.tileset, chunks.col0, chunks.row0);
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
    const bool world_changed = sync_cache(st.cache, scene, tileset);
    const bool holds = st.has_window && !world_changed && need.col0 >= have.col0 && need.row0 >= have.row0 &&
                       need.col0 + need.cols <= have.col0 + have.cols && need.row0 + need.rows <= have.row0 + have.rows;
    if (!holds) {
        ChunkRange grown = need;
        if (need.cols + 2 * chunk_tiles <= max_window_side && need.rows + 2 * chunk_tiles <= max_window_side)
            grown = ChunkRange{need.col0 - chunk_tiles, need.row0 - chunk_tiles, need.cols + 2 * chunk_tiles,
                               need.rows + 2 * chunk_tiles};
        // The old window and its frame state go before the new one is made,
        // so a jump never holds two windows at once (its chunks stay cached).
        st.frame = FrameState{st.frame.options};
        st.window = EndlessWindow{};
        st.has_window = false;
        st.window = make_endless_window(tileset, scene, grown, source, &st.cache);
        st.has_window = true;
        ++st.windows_built;
    }
    const Rect v = rect_in_window(st.window, view);
    // The obstacle map from the blocks earlier windows built, for this frame only.
    st.frame.options.obstacle_map = [&st, &tileset, &scene](const World& world, const Params& p, Rect region,
                                                            const std::vector<Mask>& footprints) {
        return obstacles_from_blocks(st, tileset, scene, world, p, region, footprints);
    };
    struct Reset {
        FrameOptions& o;
        ~Reset() { o.obstacle_map = {}; }
    } reset{st.frame.options};
    return render_frame(st.frame, st.window.world, scene_in_window(scene, st.window, view), Camera{double(v.x), double(v.y), v.w, v.h},
                        frame);
}

}  // namespace isolux
