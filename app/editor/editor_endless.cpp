// Endless worlds in the editor (editor.hpp, EndlessPlace): the document in
// the frame of a window of chunks around the view, moved into a new window's
// frame when the view leaves it.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/world.hpp"
#include "editor/editor.hpp"
#include "isolux/error.hpp"

namespace isolux::app {

namespace {

// A frame the document can be in: the world's own (all zero) or a window's.
struct Frame {
    std::int64_t col0 = 0, row0 = 0, origin_x = 0, origin_y = 0;
};

Frame frame_of(const EndlessPlace& p) { return {p.chunks.col0, p.chunks.row0, p.origin_x, p.origin_y}; }
Frame frame_of(const EndlessWindow& w) { return {w.chunks.col0, w.chunks.row0, w.origin_x, w.origin_y}; }

// An endless scene moved from one frame to another: lights by whole pixels,
// edits by whole tiles. Finite scenes (history from before the map became
// endless) keep their own frame.
void move_scene(Scene& s, const Frame& from, const Frame& to) {
    if (!s.endless) return;
    const double dx = double(from.origin_x - to.origin_x), dy = double(from.origin_y - to.origin_y);
    for (Light& l : s.lights) l.x += dx, l.y += dy;
    const std::int64_t dc = from.col0 - to.col0, dr = from.row0 - to.row0;
    for (TileEdit& t : s.edits) t.col += dc, t.row += dr;
}

// The tileset a window is made with: the world's own while its manifest is
// the same (it holds the inspector's unsaved footprints), else loaded.
Tileset tileset_for(const Editor& e, const Scene& s) {
    if (!e.world.tileset.sprites.empty() && e.world_source.tileset == s.tileset) return e.world.tileset;
    return load_scene_tileset(s);
}

// A window around `view` (world pixels) for `world_scene` (the world's
// frame), a chunk to spare on every side. Throws Error naming `source`.
EndlessWindow make_window_for(const Editor& e, const Scene& world_scene, WorldRect view, std::string_view source) {
    Tileset ts = tileset_for(e, world_scene);
    const ChunkRange need = endless_chunks(ts, world_scene.layout, view, endless_reach(world_scene, ts), source);
    const ChunkRange grown{need.col0 - chunk_tiles, need.row0 - chunk_tiles, need.cols + 2 * chunk_tiles,
                           need.rows + 2 * chunk_tiles};
    if (long(grown.cols) * grown.rows > max_endless_window_tiles)
        throw Error(std::string(source) + ": a view of " + std::to_string(view.w) + "x" + std::to_string(view.h) +
                    " pixels needs " + std::to_string(grown.cols) + "x" + std::to_string(grown.rows) +
                    " tiles around it, over the editor's " + std::to_string(max_endless_window_tiles) +
                    " for an endless world: zoom in");
    return make_endless_window(std::move(ts), world_scene, grown, source);
}

// The window becomes the world, and every endless scene the editor holds
// moves into its frame, with the view and the character. `document`, when
// given, replaces the document (it is in the world's frame).
void adopt_window(Editor& e, EndlessWindow w, WorldRect view, const Scene* document) {
    const Frame from = frame_of(e.endless), to = frame_of(w);
    if (document) e.scene = *document;
    move_scene(e.scene, document ? Frame{} : from, to);
    for (std::vector<HistoryStep>* stack : {&e.undo_stack, &e.redo_stack})
        for (HistoryStep& step : *stack) move_scene(step.scene, from, to);
    if (e.stroke.active) move_scene(e.stroke.before, from, to);
    const double dx = double(from.origin_x - to.origin_x), dy = double(from.origin_y - to.origin_y);
    if (!document) {
        e.view.x += dx, e.view.y += dy;
        e.character.x += dx, e.character.y += dy;
    } else {
        e.view.x = double(view.x - to.origin_x);
        e.view.y = double(view.y - to.origin_y);
        e.character.x = e.view.x + view.w / 2.0;
        e.character.y = e.view.y + view.h / 2.0;
    }
    e.scene.width = w.chunks.cols;
    e.scene.height = w.chunks.rows;
    e.scene.endless = true;
    e.world = std::move(w.world);
    e.world.edits = e.scene.edits;  // the window applied those inside it; set_edits skips the rest
    e.world_source = e.scene;
    e.world_source.camera = Camera{};
    fresh_frame(e);
    e.endless.on = true;
    e.endless.chunks = w.chunks;
    e.endless.origin_x = w.origin_x;
    e.endless.origin_y = w.origin_y;
    e.endless.last_view = view;
    ++e.endless.windows_built;
}

// Where a finite map's pixel (0, 0) lies in the endless frame: its first
// tile's centre less its shift, as a window's origin is (make_endless_window).
std::pair<double, double> finite_origin(Layout layout, const World& w) {
    std::int64_t fx = 0, fy = 0;
    endless_tile_center(layout, w.map.tile_width, w.map.tile_height, 0, 0, fx, fy);
    return {double(fx - w.placed.shift_x), double(fy - w.placed.shift_y)};
}

}  // namespace

Scene endless_world_scene(const Editor& e, const Scene& s) {
    Scene out = s;
    move_scene(out, frame_of(e.endless), Frame{});
    return out;
}

WorldOffset world_offset(const Editor& e) {
    if (!e.scene.endless) return {};
    return {double(e.endless.origin_x), double(e.endless.origin_y), e.endless.chunks.col0, e.endless.chunks.row0};
}

WorldRect endless_world_rect(const Editor& e, Rect r) {
    return WorldRect{r.x + e.endless.origin_x, r.y + e.endless.origin_y, r.w, r.h};
}

void open_endless(Editor& e, const Scene& world_scene, WorldRect view, std::string_view source) {
    Scene doc = world_scene;
    doc.endless = true;
    doc.camera = Camera{};
    EndlessWindow w = make_window_for(e, doc, view, source);
    adopt_window(e, std::move(w), view, &doc);
}

Follow follow_view(Editor& e, Rect view) {
    if (!e.scene.endless || view.empty()) return Follow::kept;
    const WorldRect wr = endless_world_rect(e, view);
    try {
        const ChunkRange need = endless_chunks(e.world.tileset, e.scene.layout, wr,
                                               endless_reach(render_scene(e), e.world.tileset), "view");
        const ChunkRange& have = e.endless.chunks;
        e.endless.last_view = wr;
        if (need.col0 >= have.col0 && need.row0 >= have.row0 && need.col0 + need.cols <= have.col0 + have.cols &&
            need.row0 + need.rows <= have.row0 + have.rows)
            return Follow::kept;
        adopt_window(e, make_window_for(e, endless_world_scene(e, e.scene), wr, "view"), wr, nullptr);
        return Follow::moved;
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return Follow::refused;
    }
}

bool sync_endless_world(Editor& e) {
    try {
        const bool was_finite = !e.world_source.endless;
        adopt_window(e, make_window_for(e, endless_world_scene(e, e.scene), e.endless.last_view, "map"),
                     e.endless.last_view, nullptr);
        if (was_finite) {  // the view was the finite map's: back to the last endless one
            e.view.x = double(e.endless.last_view.x - e.endless.origin_x);
            e.view.y = double(e.endless.last_view.y - e.endless.origin_y);
        }
        return true;
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
}

WorldRect default_endless_view(const Scene& world_scene) {
    const Camera& c = world_scene.camera;
    return WorldRect{std::int64_t(std::floor(c.x)), std::int64_t(std::floor(c.y)), c.width > 0 ? c.width : 1600,
                     c.height > 0 ? c.height : 900};
}

Overview endless_overview(const Editor& e, int radius) {
    Overview o;
    const Map& m = e.world.map;
    const WorldRect& v = e.endless.last_view;
    endless_tile_at(e.scene.layout, m.tile_width, m.tile_height, double(v.x) + v.w / 2.0, double(v.y) + v.h / 2.0, o.col,
                    o.row);
    auto chunk_of = [](std::int64_t t) { return t >= 0 ? t / chunk_tiles : -((-t + chunk_tiles - 1) / chunk_tiles); };
    o.cx = chunk_of(o.col);
    o.cy = chunk_of(o.row);
    const int side = 2 * radius + 1;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            OverviewChunk c;
            c.cx = o.cx - radius + i;
            c.cy = o.cy - radius + j;
            const ChunkRange& w = e.endless.chunks;
            c.in_window = c.cx * chunk_tiles >= w.col0 && (c.cx + 1) * chunk_tiles <= w.col0 + w.cols &&
                          c.cy * chunk_tiles >= w.row0 && (c.cy + 1) * chunk_tiles <= w.row0 + w.rows;
            o.chunks.push_back(c);
        }
    auto add = [&](std::int64_t col, std::int64_t row, int OverviewChunk::*field) {
        const std::int64_t i = chunk_of(col) - (o.cx - radius), j = chunk_of(row) - (o.cy - radius);
        if (i >= 0 && j >= 0 && i < side && j < side) ++(o.chunks[std::size_t(j * side + i)].*field);
    };
    for (const TileEdit& t : e.scene.edits) add(t.col + e.endless.chunks.col0, t.row + e.endless.chunks.row0, &OverviewChunk::edits);
    for (const Light& l : e.scene.lights) {
        std::int64_t col = 0, row = 0;
        endless_tile_at(e.scene.layout, m.tile_width, m.tile_height, l.x + double(e.endless.origin_x),
                        l.y + double(e.endless.origin_y), col, row);
        add(col, row, &OverviewChunk::lights);
    }
    return o;
}

void regenerate(Editor& e, const MapFields& m, double now, bool keep_edits) {
    if (!m.endless && !e.scene.endless) return regenerate(e, m.seed, m.width, m.height, m.layout, now, keep_edits);
    const Scene before = e.scene;
    // The document in the world's frame.
    Scene world = e.scene;
    WorldRect view = e.endless.last_view;
    if (!e.scene.endless) {
        const auto [ox, oy] = finite_origin(e.scene.layout, e.world);
        for (Light& l : world.lights) l.x += ox, l.y += oy;
        view = WorldRect{std::int64_t(std::floor(e.view.x + ox)), std::int64_t(std::floor(e.view.y + oy)),
                         view.w > 0 ? view.w : 1600, view.h > 0 ? view.h : 900};
    } else {
        world = endless_world_scene(e, e.scene);
    }
    world.seed = m.seed;
    world.layout = m.layout;
    if (!keep_edits) world.edits.clear();
    try {
        if (m.endless) {
            open_endless(e, world, view, "map");
        } else {
            // Into a finite map: its pixels are the world's less its origin.
            world.endless = false;
            world.width = m.width;
            world.height = m.height;
            World w = build_world(world, "edits");
            const auto [ox, oy] = finite_origin(world.layout, w);
            for (Light& l : world.lights) l.x -= ox, l.y -= oy;
            e.scene = world;
            e.world = std::move(w);
            e.world_source = world;
            fresh_frame(e);
            e.view.x = double(view.x) - ox;
            e.view.y = double(view.y) - oy;
            e.endless.on = false;
            e.fit_pending = true;
        }
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return;
    }
    commit_edit(e, before, now);
    set_status(e, "generated \"" + m.seed + "\" (" +
                      (m.endless ? std::string("endless") : std::to_string(m.width) + "x" + std::to_string(m.height)) +
                      ")");
}

}  // namespace isolux::app
