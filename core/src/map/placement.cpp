// Paper section 3: a generated map's sprites placed in world pixels and drawn
// back to front; the grid that finds them, and the placement's edits (one
// tile replaced) and queries (the sprites in a rectangle, the tile under a point).
#include <algorithm>
#include <cassert>
#include <climits>
#include <cmath>

#include "isolux/error.hpp"
#include "isolux/map.hpp"

namespace isolux {

namespace {

SpriteInstance make_instance(const Tileset& ts, int sprite, int gx, int gy, int tile, int layer) {
    const Sprite& s = ts.sprites.at(std::size_t(sprite));
    SpriteInstance in;
    in.sprite = sprite;
    in.ground_x = gx;
    in.ground_y = gy;
    in.x = gx - s.anchor_x;
    in.y = gy - s.anchor_y;
    in.tile = tile;
    in.w = s.image.width;
    in.h = s.image.height;
    in.layer = layer;
    return in;
}

Rect rect_of(const SpriteInstance& in) { return {in.x, in.y, in.w, in.h}; }


void grid_add(PlacedMap& p, std::uint32_t i) {
    const CellRange c = cells_of(p, rect_of(p.instances[i]));
    for (int cy = c.y0; cy <= c.y1; ++cy)
        for (int cx = c.x0; cx <= c.x1; ++cx) p.grid[std::size_t(cy) * p.grid_w + cx].push_back(i);
}

void grid_remove(PlacedMap& p, std::uint32_t i) {
    const CellRange c = cells_of(p, rect_of(p.instances[i]));
    for (int cy = c.y0; cy <= c.y1; ++cy)
        for (int cx = c.x0; cx <= c.x1; ++cx) {
            auto& cell = p.grid[std::size_t(cy) * p.grid_w + cx];
            cell.erase(std::remove(cell.begin(), cell.end(), i), cell.end());
        }
}

// Where any tileset sprite could stand on any tile (overlay offsets stay
// inside the diamond), in world pixels: the grid's extent, so an edit never
// has to grow it.
Rect reachable_rect(const Map& map, const Tileset& ts, int shift_x, int shift_y) {
    int left = 0, right = 0, up = 0, down = 0;
    for (const Sprite& s : ts.sprites) {
        left = std::max(left, s.anchor_x);
        right = std::max(right, s.image.width - s.anchor_x);
        up = std::max(up, s.anchor_y);
        down = std::max(down, s.image.height - s.anchor_y);
    }
    int x0 = INT_MAX, y0 = INT_MAX, x1 = INT_MIN, y1 = INT_MIN;
    auto corner = [&](int col, int row) {
        int cx = 0, cy = 0;
        tile_center(map.layout, map.tile_width, map.tile_height, col, row, cx, cy);
        x0 = std::min(x0, cx), y0 = std::min(y0, cy), x1 = std::max(x1, cx), y1 = std::max(y1, cy);
    };
    // Every layout's tile centres are extreme at the map's corners (or one
    // row in, for the staggered shift).
    for (int row : {0, std::min(1, map.height - 1), std::max(0, map.height - 2), map.height - 1})
        for (int col : {0, map.width - 1}) corner(col, row);
    const int mx = map.tile_width / 2 + 1, my = map.tile_height / 2 + 1;
    return {x0 + shift_x - left - mx, y0 + shift_y - up - my, x1 - x0 + left + right + 2 * mx,
            y1 - y0 + up + down + 2 * my};
}

Rect live_bounds(const PlacedMap& p) {
    Rect b;
    for (const SpriteInstance& in : p.instances)
        if (in.sprite >= 0) b = bounding(b, rect_of(in));
    return b;
}

}  // namespace

bool draws_before(const PlacedMap& p, std::uint32_t a, std::uint32_t b) {
    const bool oa = a >= p.first_overlay, ob = b >= p.first_overlay;
    if (oa != ob) return ob;
    const SpriteInstance &x = p.instances[a], &y = p.instances[b];
    if (x.ground_y != y.ground_y) return x.ground_y < y.ground_y;
    if (x.ground_x != y.ground_x) return x.ground_x < y.ground_x;
    if (x.tile != y.tile) return x.tile < y.tile;
    return x.layer < y.layer;
}

std::vector<std::uint32_t> draw_order(const PlacedMap& p, bool overlays_only) {
    std::vector<std::uint32_t> out;
    out.reserve(p.instances.size());
    for (std::size_t i = overlays_only ? p.first_overlay : 0; i < p.instances.size(); ++i)
        if (p.instances[i].sprite >= 0) out.push_back(std::uint32_t(i));
    if (!p.in_index_order) std::sort(out.begin(), out.end(), [&](std::uint32_t a, std::uint32_t b) { return draws_before(p, a, b); });
    return out;
}

// The grid's cell: 256 world pixels, or larger when the map's pixels are so
// many (huge tiles) that 256-pixel cells would outnumber its sprites many
// times over: the grid then never holds more than about 4 cells a sprite
// (plus 4096), whatever the tile size.
int grid_cell_for(Rect area, std::size_t sprites) {
    const double cells_max = 4.0 * double(sprites) + 4096.0;
    const double pixels = double(std::max(0, area.w)) * double(std::max(0, area.h));
    const double side = std::ceil(std::sqrt(pixels / cells_max));
    return int(std::clamp(side, 256.0, 1073741824.0));
}

PlacedMap place_sprites(const Map& map, const Tileset& ts, const PlacedMap* origin_of) {
    struct Key {
        int y, x, tile, layer;
        bool operator<(const Key& o) const {
            if (y != o.y) return y < o.y;
            if (x != o.x) return x < o.x;
            if (tile != o.tile) return tile < o.tile;
            return layer < o.layer;
        }
    };
    std::vector<std::pair<Key, SpriteInstance>> floors, overlays;
    for (int row = 0; row < map.height; ++row) {
        for (int col = 0; col < map.width; ++col) {
            int idx = row * map.width + col;
            const Tile& t = map.tiles[idx];
            int cx = 0, cy = 0;
            tile_center(map.layout, map.tile_width, map.tile_height, col, row, cx, cy);
            floors.push_back({{cy, cx, idx, 0}, make_instance(ts, t.floor, cx, cy, idx, 0)});
            for (int i = 0; i < t.overlay_count; ++i) {
                const Overlay& o = t.overlays[i];
                overlays.push_back(
                    {{cy + o.dy, cx + o.dx, idx, i + 1}, make_instance(ts, o.sprite, cx + o.dx, cy + o.dy, idx, i + 1)});
            }
        }
    }
    auto by_key = [](const auto& a, const auto& b) { return a.first < b.first; };
    std::sort(floors.begin(), floors.end(), by_key);  // keys are unique: the order is total
    std::sort(overlays.begin(), overlays.end(), by_key);

    PlacedMap out;
    out.instances.reserve(floors.size() + overlays.size());
    for (auto& f : floors) out.instances.push_back(f.second);
    out.first_overlay = out.instances.size();
    for (auto& o : overlays) out.instances.push_back(o.second);

    int x0 = INT_MAX, y0 = INT_MAX;
    if (origin_of) {
        x0 = -origin_of->shift_x;
        y0 = -origin_of->shift_y;
    } else {
        for (const SpriteInstance& in : out.instances) x0 = std::min(x0, in.x), y0 = std::min(y0, in.y);
    }
    out.tile_instances.assign(map.tiles.size(), {no_instance, no_instance, no_instance, no_instance});
    for (std::size_t i = 0; i < out.instances.size(); ++i) {
        SpriteInstance& in = out.instances[i];
        in.x -= x0;
        in.y -= y0;
        in.ground_x -= x0;
        in.ground_y -= y0;
        out.tile_instances[std::size_t(in.tile)][std::size_t(in.layer)] = std::uint32_t(i);
    }
    out.bounds = live_bounds(out);
    out.shift_x = -x0;
    out.shift_y = -y0;
    const Rect g = bounding(reachable_rect(map, ts, out.shift_x, out.shift_y), out.bounds);
    out.cell = grid_cell_for(g, out.instances.size());
    out.grid_x = g.x;
    out.grid_y = g.y;
    out.grid_w = (g.w + out.cell - 1) / out.cell;
    out.grid_h = (g.h + out.cell - 1) / out.cell;
    out.grid.assign(std::size_t(out.grid_w) * out.grid_h, {});
    for (std::size_t i = 0; i < out.instances.size(); ++i) grid_add(out, std::uint32_t(i));
    return out;
}

void finish_placed(PlacedMap& p) {
    p.bounds = live_bounds(p);
    p.cell = grid_cell_for(p.bounds, p.instances.size());
    p.grid_x = p.bounds.x;
    p.grid_y = p.bounds.y;
    p.grid_w = (p.bounds.w + p.cell - 1) / p.cell;
    p.grid_h = (p.bounds.h + p.cell - 1) / p.cell;
    p.grid.assign(std::size_t(p.grid_w) * p.grid_h, {});
    for (std::size_t i = 0; i < p.instances.size(); ++i) grid_add(p, std::uint32_t(i));
    p.tile_instances.clear();
    p.in_index_order = true;
}

Rect replace_tile(PlacedMap& p, const Map& map, const Tileset& ts, int col, int row, const Tile& tile) {
    assert(col >= 0 && row >= 0 && col < map.width && row < map.height && tile.floor >= 0);
    const int idx = row * map.width + col;
    auto& slots = p.tile_instances[std::size_t(idx)];
    int cx = 0, cy = 0;
    tile_center(map.layout, map.tile_width, map.tile_height, col, row, cx, cy);
    cx += p.shift_x;
    cy += p.shift_y;

    // What the tile would hold, as instances.
    std::array<SpriteInstance, 4> want;
    want[0] = make_instance(ts, tile.floor, cx, cy, idx, 0);
    for (int i = 0; i < tile.overlay_count; ++i) {
        const Overlay& o = tile.overlays[std::size_t(i)];
        want[std::size_t(i) + 1] = make_instance(ts, o.sprite, cx + o.dx, cy + o.dy, idx, i + 1);
    }
    auto same = [](const SpriteInstance& a, const SpriteInstance& b) {
        return a.sprite == b.sprite && a.x == b.x && a.y == b.y && a.ground_x == b.ground_x && a.ground_y == b.ground_y;
    };
    bool unchanged = same(p.instances[slots[0]], want[0]);
    for (int l = 1; l <= 3; ++l) {
        const bool had = slots[std::size_t(l)] != no_instance, has = l <= tile.overlay_count;
        unchanged = unchanged && had == has && (!has || same(p.instances[slots[std::size_t(l)]], want[std::size_t(l)]));
    }
    if (unchanged) return {};

    Rect changed;
    bool touched_edge = false;
    const Rect b = p.bounds;
    auto remove = [&](std::uint32_t i) {
        const Rect r = rect_of(p.instances[i]);
        changed = bounding(changed, r);
        touched_edge = touched_edge || r.x == b.x || r.y == b.y || r.x + r.w == b.x + b.w || r.y + r.h == b.y + b.h;
        grid_remove(p, i);
    };
    auto add = [&](std::uint32_t i) {
        changed = bounding(changed, rect_of(p.instances[i]));
        p.bounds = bounding(p.bounds, rect_of(p.instances[i]));
        grid_add(p, i);
    };
    // The floor keeps its slot (its draw position depends only on the tile).
    remove(slots[0]);
    p.instances[slots[0]] = want[0];
    add(slots[0]);
    for (int l = 1; l <= 3; ++l) {
        std::uint32_t& s = slots[std::size_t(l)];
        if (s != no_instance) {
            remove(s);
            p.instances[s].sprite = -1;
            p.free_slots.push_back(s);
            s = no_instance;
        }
        if (l > tile.overlay_count) continue;
        p.in_index_order = false;
        if (!p.free_slots.empty()) {
            s = p.free_slots.back();
            p.free_slots.pop_back();
            p.instances[s] = want[std::size_t(l)];
        } else {
            s = std::uint32_t(p.instances.size());
            p.instances.push_back(want[std::size_t(l)]);
        }
        add(s);
    }
    // Removing a sprite on the edge may shrink what the map covers.
    if (touched_edge) p.bounds = live_bounds(p);
    return changed;
}

void instances_in(const PlacedMap& placed, Rect r, bool overlays_only, std::vector<std::uint32_t>& out, int margin) {
    out.clear();
    const std::size_t first = overlays_only ? placed.first_overlay : 0;
    const Rect q{r.x - margin, r.y - margin, r.w + 2 * margin, r.h + 2 * margin};
    auto meets = [&](const SpriteInstance& in) { return in.sprite >= 0 && !intersect(rect_of(in), q).empty(); };
    if (placed.grid.empty()) {
        for (std::size_t i = first; i < placed.instances.size(); ++i)
            if (meets(placed.instances[i])) out.push_back(std::uint32_t(i));
        return;
    }
    const CellRange c = cells_of(placed, q);
    for (int cy = c.y0; cy <= c.y1; ++cy)
        for (int cx = c.x0; cx <= c.x1; ++cx)
            for (std::uint32_t i : placed.grid[std::size_t(cy) * placed.grid_w + cx])
                if (i >= first && meets(placed.instances[i])) out.push_back(i);
    std::sort(out.begin(), out.end());  // a sprite over several cells counts once
    out.erase(std::unique(out.begin(), out.end()), out.end());
    if (!placed.in_index_order)
        std::sort(out.begin(), out.end(), [&](std::uint32_t a, std::uint32_t b) { return draws_before(placed, a, b); });
}

bool tile_at(const Map& map, const PlacedMap& placed, double wx, double wy, int& col, int& row) {
    const double x = wx - placed.shift_x, y = wy - placed.shift_y;
    const double hw = map.tile_width / 2.0, hh = map.tile_height / 2.0;
    // A first guess by inverting the layout, then the best of its neighbours
    // by the diamond's own distance |dx|/hw + |dy|/hh.
    double gc = 0, gr = 0;
    switch (map.layout) {
        case Layout::diamond: gc = (x / hw + y / hh) / 2; gr = (y / hh - x / hw) / 2; break;
        case Layout::paper: gr = y / hh; gc = (x - gr * hw) / map.tile_width; break;
        case Layout::staggered: gr = y / hh; gc = x / map.tile_width; break;
    }
    const int c0 = int(std::floor(gc + 0.5)), r0 = int(std::floor(gr + 0.5));
    double best = 1e300;
    for (int r = r0 - 2; r <= r0 + 2; ++r)
        for (int c = c0 - 2; c <= c0 + 2; ++c) {
            if (c < 0 || r < 0 || c >= map.width || r >= map.height) continue;
            int cx = 0, cy = 0;
            tile_center(map.layout, map.tile_width, map.tile_height, c, r, cx, cy);
            const double d = std::abs(x - cx) / hw + std::abs(y - cy) / hh;
            if (d < best) {
                best = d;
                col = c;
                row = r;
            }
        }
    return best <= 1.0;
}

Image render_sprites(const Tileset& ts, const PlacedMap& placed, Rect view) {
    Image out(view.w, view.h);
    std::vector<std::uint32_t> near;
    instances_in(placed, view, false, near);
    for (std::uint32_t k : near) {
        const SpriteInstance& in = placed.instances[k];
        const Image& s = ts.sprites[in.sprite].image;
        Rect r = intersect({in.x, in.y, s.width, s.height}, view);
        if (r.empty()) continue;
        for (int y = r.y; y < r.y + r.h; ++y) {
            for (int x = r.x; x < r.x + r.w; ++x) {
                const std::uint8_t* sp = s.at(x - in.x, y - in.y);
                unsigned sa = sp[3];
                if (sa == 0) continue;
                std::uint8_t* dp = out.at(x - view.x, y - view.y);
                unsigned da = dp[3];
                if (sa == 255 || da == 0) {
                    dp[0] = sp[0], dp[1] = sp[1], dp[2] = sp[2], dp[3] = std::uint8_t(sa);
                    continue;
                }
                // Straight-alpha "over" in integers, exact on every machine.
                unsigned ws = sa * 255, wd = da * (255 - sa), wo = ws + wd;
                for (int c = 0; c < 3; ++c) dp[c] = std::uint8_t((sp[c] * ws + dp[c] * wd + wo / 2) / wo);
                dp[3] = std::uint8_t((wo + 127) / 255);
            }
        }
    }
    return out;
}

}  // namespace isolux
