// Beyond the paper: the seed's map plus hand edits (edits.hpp).
#include "isolux/edits.hpp"
#include "base/warnings.hpp"

#include <algorithm>
#include <map>
#include <string_view>

#include "isolux/error.hpp"
#include "isolux/hash.hpp"

namespace isolux {

namespace {

std::string entry_name(std::string_view source, std::size_t i) {
    return std::string(source) + ": edits[" + std::to_string(i) + "]";
}

// The tileset's sprites by name (the first of a name, as a linear search
// would find): a lookup per edit costs log(sprites), so a million edits over
// a large Tiled tileset stay linear in the edits.
using SpritesByName = std::map<std::string_view, int>;

SpritesByName sprites_by_name(const Tileset& ts) {
    SpritesByName out;
    for (std::size_t i = 0; i < ts.sprites.size(); ++i) out.emplace(ts.sprites[i].name, int(i));
    return out;
}

int sprite_named(const Tileset& ts, const SpritesByName& names, const std::string& name, SpriteKind kind,
                 const std::string& where, const char* field) {
    const auto it = names.find(name);
    if (it == names.end())
        throw Error(where + ": " + field + " \"" + name + "\" is not a sprite of " +
                    (ts.source.empty() ? std::string("the tileset") : ts.source));
    if (ts.sprites[std::size_t(it->second)].kind != kind)
        throw Error(where + ": " + field + " \"" + name + "\" is " +
                    (kind == SpriteKind::floor ? "an overlay, not a floor" : "a floor, not an overlay") +
                    " sprite of " + (ts.source.empty() ? std::string("the tileset") : ts.source));
    return it->second;
}

bool inside(std::int64_t col, std::int64_t row, int width, int height) {
    return col >= 0 && row >= 0 && col < width && row < height;
}

}  // namespace

std::vector<ResolvedEdit> resolve_edits(const std::vector<TileEdit>& edits, const Tileset& ts, std::string_view source) {
    std::vector<ResolvedEdit> out;
    out.reserve(edits.size());
    const SpritesByName names = sprites_by_name(ts);
    for (std::size_t i = 0; i < edits.size(); ++i) {
        const TileEdit& e = edits[i];
        const std::string where = entry_name(source, i);
        ResolvedEdit r;
        r.col = e.col;
        r.row = e.row;
        if (e.floor) r.floor = sprite_named(ts, names, *e.floor, SpriteKind::floor, where, "floor");
        if (e.overlays) {
            if (e.overlays->size() > 3)
                throw Error(where + ": overlays holds " + std::to_string(e.overlays->size()) +
                            " sprites; a tile holds at most 3");
            r.overlays.emplace();
            for (const std::string& name : *e.overlays)
                r.overlays->push_back(sprite_named(ts, names, name, SpriteKind::overlay, where, "overlays"));
        }
        out.push_back(std::move(r));
    }
    return out;
}

void warn_edits_outside(const std::vector<TileEdit>& edits, int width, int height, std::string_view source,
                        std::vector<std::string>& warnings) {
    WarningRun run(&warnings, "edits outside the " + std::to_string(width) + "x" + std::to_string(height) +
                                  " map (kept in the scene, not applied)");
    for (std::size_t i = 0; i < edits.size(); ++i) {
        if (inside(edits[i].col, edits[i].row, width, height)) continue;
        if (!run.wanted()) {
            run.add({});
            continue;
        }
        run.add(entry_name(source, i) + ": tile [" + std::to_string(edits[i].col) + ", " + std::to_string(edits[i].row) +
                "] is outside the " + std::to_string(width) + "x" + std::to_string(height) +
                " map: kept in the scene, not applied");
    }
}

std::vector<int> overlay_sprites(const Tile& t) {
    std::vector<int> out;
    for (int i = 0; i < t.overlay_count; ++i) out.push_back(t.overlays[std::size_t(i)].sprite);
    return out;
}

Tile edited_tile(const Map& seeded, int col, int row, const std::vector<const ResolvedEdit*>& edits) {
    const Tile& seed = seeded.at(col, row);
    Tile t = seed;
    const std::vector<int>* overlays = nullptr;
    for (const ResolvedEdit* e : edits) {
        if (e->floor) t.floor = *e->floor;
        if (e->overlays) overlays = &*e->overlays;
    }
    if (!overlays) return t;
    // The seed's placement while the lists agree from the start; the slot
    // rule from then on, seeded by the tile alone.
    Pcg32 rng(hash_point(0x65646974ull /* "edit" */, col, row));
    t.overlay_count = int(overlays->size());
    bool same_so_far = true;
    for (int i = 0; i < t.overlay_count; ++i) {
        const int sprite = (*overlays)[std::size_t(i)];
        same_so_far = same_so_far && i < seed.overlay_count && seed.overlays[std::size_t(i)].sprite == sprite;
        t.overlays[std::size_t(i)] =
            same_so_far ? seed.overlays[std::size_t(i)] : make_overlay(sprite, i, seeded.tile_width, seeded.tile_height, rng);
    }
    for (int i = t.overlay_count; i < 3; ++i) t.overlays[std::size_t(i)] = Overlay{};
    return t;
}

Map apply_edits(const Map& seeded, const std::vector<ResolvedEdit>& edits) {
    Map m = seeded;
    // Each edited tile's entries in file order; tiles in row-major order.
    std::vector<std::pair<int, const ResolvedEdit*>> by_tile;
    for (const ResolvedEdit& e : edits)
        if (inside(e.col, e.row, m.width, m.height)) by_tile.push_back({int(e.row) * m.width + int(e.col), &e});
    std::stable_sort(by_tile.begin(), by_tile.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < by_tile.size();) {
        std::vector<const ResolvedEdit*> list;
        std::size_t j = i;
        for (; j < by_tile.size() && by_tile[j].first == by_tile[i].first; ++j) list.push_back(by_tile[j].second);
        const ResolvedEdit& e = *by_tile[i].second;
        m.tiles[std::size_t(by_tile[i].first)] = edited_tile(seeded, int(e.col), int(e.row), list);
        i = j;
    }
    return m;
}

void set_tile_edit(std::vector<TileEdit>& edits, const Map& seeded, const Tileset& ts, int col, int row, int floor,
                   const std::vector<int>& overlays) {
    edits.erase(std::remove_if(edits.begin(), edits.end(),
                               [&](const TileEdit& e) { return e.col == col && e.row == row; }),
                edits.end());
    const Tile& seed = seeded.at(col, row);
    TileEdit e;
    e.col = col;
    e.row = row;
    if (floor != seed.floor) e.floor = ts.sprites.at(std::size_t(floor)).name;
    if (overlays != overlay_sprites(seed)) {
        e.overlays.emplace();
        for (int s : overlays) e.overlays->push_back(ts.sprites.at(std::size_t(s)).name);
    }
    if (e.floor || e.overlays) edits.push_back(std::move(e));
}

}  // namespace isolux
