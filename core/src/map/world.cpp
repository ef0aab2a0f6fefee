#include "isolux/world.hpp"

#include <algorithm>
#include <atomic>
#include <map>
#include <string>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"

namespace isolux {

namespace {

std::atomic<std::uint64_t> next_revision{1};

// Changes remembered for caches; older ones make a cache rebuild everything.
constexpr std::size_t max_changes = 4096;

// Records an in-place change of `changed` (nothing when it is empty).
void record_change(World& w, Rect changed) {
    if (changed.empty()) return;
    w.revision = next_revision++;
    if (w.changes.size() >= max_changes) {
        // Too long a record: caches older than its start rebuild everything.
        w.changes.erase(w.changes.begin(), w.changes.begin() + std::ptrdiff_t(max_changes / 2));
        w.built_revision = 0;
    }
    w.changes.push_back({w.revision, changed});
}

}  // namespace

void touch(World& w) {
    w.revision = next_revision++;
    w.built_revision = w.revision;
    w.changes.clear();
}

World make_world(Tileset tileset, const Scene& scene, std::string_view source, std::vector<std::string>* warnings) {
    if (scene.endless)
        throw Error(std::string(source) + ": an endless world is lit around a view (render --view, or the scene's camera "
                                          "with a size); this needs a map with an edge");
    World w;
    w.tileset = std::move(tileset);
    w.seeded = generate_map(scene.seed, scene.width, scene.height, scene.layout, w.tileset);
    const std::vector<ResolvedEdit> resolved = resolve_edits(scene.edits, w.tileset, source);
    if (warnings) warn_edits_outside(scene.edits, scene.width, scene.height, source, *warnings);
    if (resolved.empty()) {
        w.map = w.seeded;
        w.placed = place_sprites(w.map, w.tileset);
        w.frame = w.placed.bounds;
    } else {
        // The world's pixels are the seeded map's: an edit never moves lights.
        const PlacedMap origin = place_sprites(w.seeded, w.tileset);
        w.map = apply_edits(w.seeded, resolved);
        w.placed = place_sprites(w.map, w.tileset, &origin);
        w.frame = origin.bounds;
    }
    w.edits = scene.edits;
    touch(w);
    return w;
}

Rect set_edits(World& w, const std::vector<TileEdit>& edits, std::string_view source) {
    const std::vector<ResolvedEdit> resolved = resolve_edits(edits, w.tileset, source);  // may throw: nothing changed yet
    const std::vector<ResolvedEdit> before = resolve_edits(w.edits, w.tileset, source);
    // Every tile the old or the new edits name, with the new edits' entries
    // for it (an ordered map: the same order on every machine).
    std::map<int, std::vector<const ResolvedEdit*>> tiles;
    auto inside = [&](const ResolvedEdit& e) { return e.col >= 0 && e.row >= 0 && e.col < w.map.width && e.row < w.map.height; };
    for (const ResolvedEdit& e : before)
        if (inside(e)) tiles[int(e.row) * w.map.width + int(e.col)];
    for (const ResolvedEdit& e : resolved)
        if (inside(e)) tiles[int(e.row) * w.map.width + int(e.col)].push_back(&e);
    Rect changed;
    for (const auto& [idx, list] : tiles) {
        const int col = idx % w.map.width, row = idx / w.map.width;
        const Tile t = edited_tile(w.seeded, col, row, list);
        w.map.tiles[std::size_t(idx)] = t;
        changed = bounding(changed, replace_tile(w.placed, w.map, w.tileset, col, row, t));
    }
    w.edits = edits;
    record_change(w, changed);
    return changed;
}

Rect set_tile(World& w, int col, int row, int floor, const std::vector<int>& overlays) {
    if (w.seeded.tiles.empty() || col < 0 || row < 0 || col >= w.map.width || row >= w.map.height)
        throw Error("set_tile: tile " + std::to_string(col) + ", " + std::to_string(row) + " is not a tile of the " +
                    std::to_string(w.map.width) + "x" + std::to_string(w.map.height) + " seeded map");
    set_tile_edit(w.edits, w.seeded, w.tileset, col, row, floor, overlays);
    // The tile's one entry now holds what differs from the seed: the same
    // tile apply_edits makes of the whole list.
    const Tile& seed = w.seeded.at(col, row);
    ResolvedEdit e{col, row, {}, {}};
    if (floor != seed.floor) e.floor = floor;
    if (overlays != overlay_sprites(seed)) e.overlays = overlays;
    const Tile t = edited_tile(w.seeded, col, row, {&e});
    w.map.tiles[std::size_t(row) * std::size_t(w.map.width) + std::size_t(col)] = t;
    const Rect changed = replace_tile(w.placed, w.map, w.tileset, col, row, t);
    record_change(w, changed);
    return changed;
}

bool changed_since(const World& w, std::uint64_t revision, Rect& region) {
    region = {};
    if (revision == w.revision) return true;
    std::size_t first = 0;
    if (revision != w.built_revision || w.built_revision == 0) {
        auto it = std::find_if(w.changes.begin(), w.changes.end(), [&](const auto& c) { return c.first == revision; });
        if (it == w.changes.end()) return false;
        first = std::size_t(it - w.changes.begin()) + 1;
    }
    for (std::size_t i = first; i < w.changes.size(); ++i) region = bounding(region, w.changes[i].second);
    return true;
}

}  // namespace isolux
