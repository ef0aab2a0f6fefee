// The editor's terrain tools: brushes, strokes, fills (editor.hpp).
#include "editor/editor.hpp"

#include <algorithm>
#include <cmath>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/hash.hpp"

namespace isolux::app {

const std::vector<ToolInfo>& tool_table() {
    static const std::vector<ToolInfo> table = {
        {Tool::lights, "lights", "Lights", 'L', "Click to place a light, drag to move (Shift: add to the selection, "
                                                "drag on empty ground: box select), right-click to remove."},
        {Tool::floor, "floor", "Floor", 'B', "Paint the chosen floor block on every tile the stroke crosses."},
        {Tool::floor_rect, "rectangle", "Rectangle", 'R', "Drag a rectangle of tiles: all take the chosen floor."},
        {Tool::floor_fill, "fill", "Fill", 'G', "Bucket fill: the tiles connected to the clicked one with its floor "
                                                "take the chosen floor."},
        {Tool::overlay_add, "place", "Place", 'O', "Place the chosen overlay (or any sprite with the chosen tag) on a "
                                                   "tile, up to three per tile."},
        {Tool::overlay_remove, "remove", "Remove", 'X', "Remove the topmost overlay of each tile the stroke crosses."},
        {Tool::eraser, "eraser", "Eraser", 'E', "Clear every overlay of each tile the stroke crosses."},
        {Tool::eyedropper, "eyedropper", "Pick", 'I', "Take the floor and the top overlay of a tile as the brush."},
    };
    return table;
}

const ToolInfo& tool_info(Tool t) {
    for (const ToolInfo& i : tool_table())
        if (i.tool == t) return i;
    return tool_table().front();
}

std::string sprite_name(const Editor& e, int sprite) {
    if (sprite < 0 || sprite >= int(e.world.tileset.sprites.size())) return "none";
    return e.world.tileset.sprites[std::size_t(sprite)].name;
}

namespace {

bool on_map(const Editor& e, int col, int row) {
    return col >= 0 && row >= 0 && col < e.world.map.width && row < e.world.map.height;
}

// The overlay the brush puts on tile (col, row): its sprite, or a sprite with
// its tag picked from the tile and the stroke (the same stroke, the same pick).
int brush_overlay(const Editor& e, int col, int row) {
    if (e.brush.overlay_tag.empty()) return e.brush.overlay;
    const std::vector<int> c = e.world.tileset.find(SpriteKind::overlay, e.brush.overlay_tag);
    if (c.empty()) return -1;
    Pcg32 rng(hash_point(e.strokes, col, row, 0x62727368ull));
    return c[rng.below(std::uint32_t(c.size()))];
}

// Tile (col, row) takes `floor` and `overlays`: the scene's edit for it
// becomes that, and the world follows in place.
void put_tile(Editor& e, int col, int row, int floor, const std::vector<int>& overlays) {
    const Tile& now = e.world.map.at(col, row);
    if (floor == now.floor && overlays == overlay_sprites(now)) return;
    set_tile_edit(e.scene.edits, e.world.seeded, e.world.tileset, col, row, floor, overlays);
    sync_world(e);
}

void apply_tool(Editor& e, int col, int row) {
    if (!on_map(e, col, row)) return;
    const Tile& t = e.world.map.at(col, row);
    std::vector<int> overlays = overlay_sprites(t);
    switch (e.brush.tool) {
        case Tool::floor:
            if (e.brush.floor >= 0) put_tile(e, col, row, e.brush.floor, overlays);
            break;
        case Tool::overlay_add: {
            const int o = brush_overlay(e, col, row);
            if (o < 0 || overlays.size() >= 3) break;
            overlays.push_back(o);
            put_tile(e, col, row, t.floor, overlays);
            break;
        }
        case Tool::overlay_remove:
            if (overlays.empty()) break;
            overlays.pop_back();
            put_tile(e, col, row, t.floor, overlays);
            break;
        case Tool::eraser:
            put_tile(e, col, row, t.floor, {});
            break;
        case Tool::eyedropper:
            e.brush.floor = t.floor;
            if (!overlays.empty()) {
                e.brush.overlay = overlays.back();
                e.brush.overlay_tag.clear();
            }
            set_status(e, "picked floor " + sprite_name(e, t.floor) +
                              (overlays.empty() ? "" : ", overlay " + sprite_name(e, overlays.back())));
            break;
        default:
            break;
    }
}

// The bucket: every tile connected (by shared edges in column and row) to
// the start with the start's floor.
void fill_floor(Editor& e, int col, int row) {
    const Map& m = e.world.map;
    const int from = m.at(col, row).floor, to = e.brush.floor;
    if (to < 0 || from == to) return;
    std::vector<char> seen(m.tiles.size(), 0);
    std::vector<std::pair<int, int>> todo = {{col, row}}, region;
    seen[std::size_t(row) * m.width + col] = 1;
    while (!todo.empty()) {
        auto [c, r] = todo.back();
        todo.pop_back();
        region.push_back({c, r});
        const int next[4][2] = {{c + 1, r}, {c - 1, r}, {c, r + 1}, {c, r - 1}};
        for (const auto& n : next) {
            if (!on_map(e, n[0], n[1])) continue;
            const std::size_t i = std::size_t(n[1]) * m.width + n[0];
            if (seen[i] || m.tiles[i].floor != from) continue;
            seen[i] = 1;
            todo.push_back({n[0], n[1]});
        }
    }
    std::sort(region.begin(), region.end(), [](auto a, auto b) { return a.second != b.second ? a.second < b.second : a.first < b.first; });
    for (auto [c, r] : region)
        set_tile_edit(e.scene.edits, e.world.seeded, e.world.tileset, c, r, to, overlay_sprites(m.at(c, r)));
    sync_world(e);
    set_status(e, "filled " + std::to_string(region.size()) + " tiles with " + sprite_name(e, to));
}

void fill_rect(Editor& e) {
    const Stroke& s = e.stroke;
    if (e.brush.floor < 0) return;
    const int c0 = std::max(0, std::min(s.col0, s.col1)), c1 = std::min(e.world.map.width - 1, std::max(s.col0, s.col1));
    const int r0 = std::max(0, std::min(s.row0, s.row1)), r1 = std::min(e.world.map.height - 1, std::max(s.row0, s.row1));
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
            set_tile_edit(e.scene.edits, e.world.seeded, e.world.tileset, c, r, e.brush.floor,
                          overlay_sprites(e.world.map.at(c, r)));
    sync_world(e);
}

}  // namespace

void begin_stroke(Editor& e, int col, int row) {
    if (e.brush.tool == Tool::lights) return;
    if (!e.scene.map.empty()) {
        set_status(e, "this scene lights a Tiled map: edit its tiles in Tiled (the terrain tools edit seeded maps)", true);
        return;
    }
    e.stroke = Stroke{true, e.scene, col, row, col, row};
    ++e.strokes;
    if (e.brush.tool == Tool::floor_fill) {
        if (on_map(e, col, row)) fill_floor(e, col, row);
    } else if (e.brush.tool != Tool::floor_rect) {
        apply_tool(e, col, row);
    }
}

void continue_stroke(Editor& e, int col, int row) {
    if (!e.stroke.active) return;
    if (col == e.stroke.col1 && row == e.stroke.row1) return;
    e.stroke.col1 = col;
    e.stroke.row1 = row;
    if (e.brush.tool == Tool::floor_rect || e.brush.tool == Tool::floor_fill || e.brush.tool == Tool::eyedropper) return;
    apply_tool(e, col, row);
}

void end_stroke(Editor& e, double now) {
    if (!e.stroke.active) return;
    if (e.brush.tool == Tool::floor_rect) fill_rect(e);
    e.stroke.active = false;
    commit_edit(e, e.stroke.before, now);
}

std::string brush_preview(const Editor& e, int col, int row) {
    if (!on_map(e, col, row)) return "";
    const Tile& t = e.world.map.at(col, row);
    const WorldOffset o = world_offset(e);
    std::string here = "tile " + std::to_string(col + o.col) + ", " + std::to_string(row + o.row) + ": " + sprite_name(e, t.floor);
    for (int s : overlay_sprites(t)) here += " + " + sprite_name(e, s);
    std::string will;
    const std::string overlay =
        e.brush.overlay_tag.empty() ? sprite_name(e, e.brush.overlay) : "any " + e.brush.overlay_tag;
    switch (e.brush.tool) {
        case Tool::lights: return here;
        case Tool::floor:
        case Tool::floor_rect:
        case Tool::floor_fill:
            will = e.brush.floor < 0 ? "choose a floor" : "floor -> " + sprite_name(e, e.brush.floor);
            if (e.brush.tool == Tool::floor_fill) will += " (every connected " + sprite_name(e, t.floor) + " tile)";
            break;
        case Tool::overlay_add:
            will = t.overlay_count >= 3 ? "full: a tile holds 3 overlays" : "+ " + overlay;
            break;
        case Tool::overlay_remove:
            will = t.overlay_count == 0 ? "no overlay to remove" : "- " + sprite_name(e, t.overlays[std::size_t(t.overlay_count - 1)].sprite);
            break;
        case Tool::eraser: will = t.overlay_count == 0 ? "nothing to erase" : "clear the overlays"; break;
        case Tool::eyedropper: will = "pick these as the brush"; break;
    }
    return here + "  |  " + will;
}

}  // namespace isolux::app
