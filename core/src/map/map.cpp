// Paper section 3: seeded maps of blocks, assembled by a layout (their placement and drawing: placement.cpp).
#include "isolux/map.hpp"

#include <algorithm>
#include <cassert>
#include <climits>
#include <cmath>
#include <string>

#include "isolux/error.hpp"
#include "isolux/hash.hpp"

namespace isolux {

std::string_view to_string(Layout l) {
    switch (l) {
        case Layout::paper: return "paper";
        case Layout::diamond: return "diamond";
        case Layout::staggered: return "staggered";
    }
    return "diamond";
}

Layout parse_layout(std::string_view s, std::string_view source) {
    if (s == "paper") return Layout::paper;
    if (s == "diamond") return Layout::diamond;
    if (s == "staggered") return Layout::staggered;
    throw Error(std::string(source) + ": layout \"" + std::string(s) +
                "\" is not one of paper, diamond, staggered");
}

void tile_center(Layout layout, int tw, int th, std::int64_t col, std::int64_t row, std::int64_t& x, std::int64_t& y) {
    const std::int64_t hw = tw / 2, hh = th / 2;
    switch (layout) {
        case Layout::paper:
            // Block n sits right of block n-1; after a line break it goes below
            // the previous line's first block p (its centre on p's bottom
            // corner) and halfway between p and p+1: each line shifts by half
            // a block, giving a parallelogram.
            x = col * tw + row * hw;
            y = row * hh;
            return;
        case Layout::diamond:
            x = (col - row) * hw;
            y = (col + row) * hh;
            return;
        case Layout::staggered:
            x = col * tw + (row & 1) * hw;
            y = row * hh;
            return;
    }
}

void tile_center(Layout layout, int tw, int th, int col, int row, int& x, int& y) {
    std::int64_t x64 = 0, y64 = 0;
    tile_center(layout, tw, th, std::int64_t(col), std::int64_t(row), x64, y64);
    x = int(x64);
    y = int(y64);
}

Overlay make_overlay(int sprite, int index, int tile_width, int tile_height, Pcg32& rng) {
    // Overlays share the tile: spread them over slots inside the diamond so
    // they overlap like the paper's Figure 2 without standing on one point.
    static constexpr int slots[4][2] = {{0, 0}, {-1, 0}, {1, 0}, {0, 1}};
    const int slot = index == 0 ? int(rng.below(2)) * 3 % 4 : index;
    const int jx = int(rng.below(9)) - 4, jy = int(rng.below(5)) - 2;
    Overlay o;
    o.sprite = sprite;
    o.dx = slots[slot][0] * tile_width / 5 + jx * tile_width / 128;
    o.dy = slots[slot][1] * tile_height / 5 + jy * tile_height / 64;
    return o;
}

namespace {

enum class Biome { water, sand, meadow, forest, dirt, stone };

Biome biome_at(std::uint64_t seed, std::int64_t col, std::int64_t row) {
    // Two independent noise fields, sampled per tile so a tile's content does
    // not depend on the map's size: a larger map extends a smaller one.
    double e = fractal_noise(mix64(seed ^ 0x656C6576ull), double(col) / 9.0, double(row) / 9.0, 4);
    double m = fractal_noise(mix64(seed ^ 0x6D6F6973ull), double(col) / 7.0, double(row) / 7.0, 3);
    if (e < 0.33) return Biome::water;
    if (e < 0.39) return Biome::sand;
    if (e > 0.70) return Biome::stone;
    if (m > 0.58) return Biome::forest;
    if (m > 0.40) return Biome::meadow;
    return Biome::dirt;
}

int pick(const Tileset& ts, SpriteKind kind, std::string_view tag, Pcg32& rng) {
    std::vector<int> c = ts.find(kind, tag);
    if (c.empty()) return -1;
    return c[rng.below(std::uint32_t(c.size()))];
}

void add_overlay(Tile& t, int sprite, const Map& m, Pcg32& rng) {
    if (sprite < 0 || t.overlay_count >= 3) return;
    t.overlays[t.overlay_count] = make_overlay(sprite, t.overlay_count, m.tile_width, m.tile_height, rng);
    ++t.overlay_count;
}

}  // namespace

Map generate_map(std::string_view seed, int width, int height, Layout layout, const Tileset& ts, std::int64_t col0,
                 std::int64_t row0) {
    if (!map_size_ok(width, height))
        throw Error("map size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range: " +
                    map_size_rule());
    validate(ts);
    Map m;
    m.width = width;
    m.height = height;
    m.layout = layout;
    m.tile_width = ts.tile_width;
    m.tile_height = ts.tile_height;
    m.tiles.resize(std::size_t(width) * height);
    const std::uint64_t s = hash_seed(seed);
    for (int row = 0; row < height; ++row) {
        for (int col = 0; col < width; ++col) {
            Tile& t = m.tiles[std::size_t(row) * width + col];
            const std::int64_t gc = col0 + col, gr = row0 + row;  // the tile's own coordinates: its content
            Pcg32 rng(hash_point(s, gc, gr, 0x74696C65ull));
            auto chance = [&](int percent) { return int(rng.below(100)) < percent; };
            const SpriteKind F = SpriteKind::floor, O = SpriteKind::overlay;
            switch (biome_at(s, gc, gr)) {
                case Biome::water:
                    t.floor = pick(ts, F, "water", rng);
                    break;
                case Biome::sand:
                    t.floor = pick(ts, F, "sand", rng);
                    if (chance(6)) add_overlay(t, pick(ts, O, "rock", rng), m, rng);
                    break;
                case Biome::meadow:
                    t.floor = pick(ts, F, "grass", rng);
                    if (chance(22)) {
                        int r = int(rng.below(100));
                        add_overlay(t, pick(ts, O, r < 55 ? "bush" : r < 85 ? "tree" : "rock", rng), m, rng);
                    }
                    break;
                case Biome::forest: {
                    t.floor = pick(ts, F, chance(85) ? "grass" : "dirt", rng);
                    int n = chance(80) ? 1 + int(rng.below(3)) : 0;
                    for (int i = 0; i < n; ++i)
                        add_overlay(t, pick(ts, O, chance(70) ? "tree" : "bush", rng), m, rng);
                    break;
                }
                case Biome::dirt:
                    t.floor = pick(ts, F, "dirt", rng);
                    if (chance(5)) add_overlay(t, pick(ts, O, "wall", rng), m, rng);
                    else if (chance(14)) add_overlay(t, pick(ts, O, chance(50) ? "rock" : "bush", rng), m, rng);
                    break;
                case Biome::stone:
                    t.floor = pick(ts, F, "stone", rng);
                    if (chance(30)) add_overlay(t, pick(ts, O, "rock", rng), m, rng);
                    else if (chance(6)) add_overlay(t, pick(ts, O, "wall", rng), m, rng);
                    break;
            }
            if (t.floor < 0) t.floor = pick(ts, F, "grass", rng);  // tileset lacks that floor: grass,
            if (t.floor < 0) {                                      // else any floor at all
                std::vector<int> floors;
                for (int i = 0; i < int(ts.sprites.size()); ++i)
                    if (ts.sprites[i].kind == F) floors.push_back(i);
                t.floor = floors[rng.below(std::uint32_t(floors.size()))];  // validate() ensured one
            }
        }
    }
    return m;
}

}  // namespace isolux
