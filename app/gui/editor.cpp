#include "gui/editor.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "common/assets.hpp"
#include "common/world.hpp"
#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/hash.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

namespace {

bool same_world_fields(const Scene& a, const Scene& b) {
    return a.seed == b.seed && a.width == b.width && a.height == b.height && a.layout == b.layout &&
           a.tileset == b.tileset && a.map == b.map;
}

void remember_file(Editor& e, const fs::path& path, FileKind kind) {
    add_recent(e.settings, fs::absolute(path).lexically_normal().string(), kind);
    try {
        save_settings(e.config, e.settings);
    } catch (const Error&) {
        // Settings are a convenience: failing to save them loses no work.
    }
}

// A new world: the frame's caches start over, its options stay.
void fresh_frame(Editor& e) {
    const FrameOptions keep = e.frame.options;
    e.frame = FrameState{};
    e.frame.options = keep;
}

// A scene's camera becomes the view; the document keeps none while editing.
void take_camera(Editor& e) {
    e.view.x = e.scene.camera.x;
    e.view.y = e.scene.camera.y;
    e.view.width = e.scene.camera.width;
    e.view.height = e.scene.camera.height;
    e.scene.camera = Camera{};
    e.world_source.camera = Camera{};
}

}  // namespace

void reset_view(Editor& e) {
    e.view.x = e.view.y = 0;
    e.view.zoom = 1;
}

MapFields map_fields(const Editor& e) {
    return {e.scene.seed, e.scene.width, e.scene.height, e.scene.layout, e.scene.tileset};
}

Scene scene_to_save(const Editor& e) {
    Scene s = e.scene;
    s.camera = {e.view.x, e.view.y, e.view.width, e.view.height};
    return s;
}

void set_status(Editor& e, std::string text, bool error) {
    e.status = std::move(text);
    e.status_error = error;
}

Editor make_editor(const Scene& scene, const fs::path& config) {
    Editor e;
    e.scene = scene;
    e.config = config;
    std::string warning;
    e.settings = load_settings(config, &warning);
    if (!warning.empty()) set_status(e, warning, true);
    e.world = build_world(scene);
    e.world_source = scene;
    e.frame.options.cpu_sprites = false;
    e.frame.options.cpu_blur_and_composite = false;
    take_camera(e);
    return e;
}

void commit_edit(Editor& e, const Scene& before, double now) {
    if (before == e.scene) return;
    e.undo_stack.push_back(before);
    if (e.undo_stack.size() > max_undo) e.undo_stack.erase(e.undo_stack.begin());
    e.redo_stack.clear();
    e.dirty = true;
    e.autosave_due = now + autosave_delay;
}

bool sync_world(Editor& e) {
    if (same_world_fields(e.scene, e.world_source)) {
        if (e.scene.edits == e.world.edits) return true;
        try {
            set_edits(e.world, e.scene.edits, "edits");  // in place: only the tiles that differ
            return true;
        } catch (const Error& err) {
            set_status(e, err.what(), true);
            e.scene.edits = e.world.edits;
            return false;
        }
    }
    try {
        std::vector<std::string> warnings;
        World w = build_world(e.scene, "edits", &warnings);
        e.world = std::move(w);
        e.world_source = e.scene;
        fresh_frame(e);
        return true;
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        e.scene.seed = e.world_source.seed;
        e.scene.width = e.world_source.width;
        e.scene.height = e.world_source.height;
        e.scene.layout = e.world_source.layout;
        e.scene.tileset = e.world_source.tileset;
        return false;
    }
}

void place_light(Editor& e, double x, double y, double now) {
    Scene before = e.scene;
    Light l;
    l.x = std::floor(x) + 0.5;
    l.y = std::floor(y) + 0.5;
    e.scene.lights.push_back(l);
    select_light(e, int(e.scene.lights.size()) - 1);
    commit_edit(e, before, now);
    if (e.frame.obstacles.get(int(std::floor(x)), int(std::floor(y))))
        set_status(e, "light " + std::to_string(e.selected + 1) +
                          " sits on an obstacle pixel: it lights nothing (Algorithm 2 tests the centre first)",
                    true);
    else
        set_status(e, "placed light " + std::to_string(e.selected + 1));
}

void remove_light(Editor& e, int index, double now) {
    if (index < 0 || index >= int(e.scene.lights.size())) return;
    if (e.scene.lights[std::size_t(index)].locked) {
        set_status(e, light_label(e.scene, index) + " is locked: unlock it in the Lights panel to remove it", true);
        return;
    }
    Scene before = e.scene;
    const std::string label = light_label(e.scene, index);
    e.scene.lights.erase(e.scene.lights.begin() + index);
    std::vector<int> kept;
    for (int i : e.selection)
        if (i != index) kept.push_back(i > index ? i - 1 : i);
    e.selection = kept;
    if (e.selected == index) e.selected = -1;
    else if (e.selected > index) --e.selected;
    commit_edit(e, before, now);
    set_status(e, "removed " + label);
}

void move_light(Editor& e, int index, double x, double y) {
    if (index < 0 || index >= int(e.scene.lights.size()) || e.scene.lights[std::size_t(index)].locked) return;
    e.scene.lights[index].x = std::floor(x) + 0.5;
    e.scene.lights[index].y = std::floor(y) + 0.5;
}

void set_params(Editor& e, const Params& p, double now) {
    try {
        validate(p, "parameters");
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return;
    }
    Scene before = e.scene;
    e.scene.params = p;
    commit_edit(e, before, now);
}

int edits_outside(const Scene& s) {
    int n = 0;
    for (const TileEdit& t : s.edits) n += t.col < 0 || t.row < 0 || t.col >= s.width || t.row >= s.height;
    return n;
}

void regenerate(Editor& e, const std::string& seed, int width, int height, Layout layout, double now,
                bool keep_edits) {
    Scene before = e.scene;
    e.scene.seed = seed;
    e.scene.width = width;
    e.scene.height = height;
    e.scene.layout = layout;
    if (!keep_edits) e.scene.edits.clear();
    if (sync_world(e)) {
        commit_edit(e, before, now);
        e.fit_pending = true;
        std::string msg = "generated \"" + seed + "\" (" + std::to_string(width) + "x" + std::to_string(height) + ")";
        const int outside = edits_outside(e.scene);
        if (outside > 0)
            msg += "; " + std::to_string(outside) + " edit" + (outside == 1 ? " lies" : "s lie") +
                   " outside the map: kept in the scene, applied again if it grows";
        set_status(e, msg, outside > 0);
    } else {
        e.scene.edits = before.edits;
    }
}

// ---------------------------------------------------------------- terrain tools

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
    std::string here = "tile " + std::to_string(col) + ", " + std::to_string(row) + ": " + sprite_name(e, t.floor);
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

namespace {
// Undo and redo are one move between the two stacks, in opposite directions.
bool step_history(Editor& e, std::vector<Scene>& from, std::vector<Scene>& to, double now, const char* what) {
    if (from.empty()) return false;
    to.push_back(e.scene);
    e.scene = from.back();
    from.pop_back();
    sync_world(e);
    if (e.selected >= int(e.scene.lights.size())) e.selected = -1;
    std::erase_if(e.selection, [&](int i) { return i >= int(e.scene.lights.size()); });
    e.dirty = true;
    e.autosave_due = now + autosave_delay;
    set_status(e, what);
    return true;
}
}  // namespace

bool open_recent(Editor& e, const RecentFile& file, double now) {
    switch (file.kind) {
        case FileKind::scene: return load_scene_from(e, file.path, now);
        case FileKind::preset: return import_preset(e, file.path, now);
        case FileKind::tileset: return load_tileset_from(e, file.path, now);
    }
    return false;
}

bool undo(Editor& e, double now) { return step_history(e, e.undo_stack, e.redo_stack, now, "undo"); }
bool redo(Editor& e, double now) { return step_history(e, e.redo_stack, e.undo_stack, now, "redo"); }

bool save_scene_to(Editor& e, const fs::path& path) {
    try {
        save_scene(path, scene_to_save(e));
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
    e.scene_path = path;
    e.dirty = false;
    e.autosave_due = -1;
    discard_autosave(e);
    remember_file(e, path, FileKind::scene);
    set_status(e, "saved " + path.string());
    return true;
}

namespace {
bool load_scene_impl(Editor& e, const fs::path& path, double now, bool remember) {
    std::vector<std::string> warnings;
    Scene loaded;
    try {
        World w;
        if (path.extension() == ".tmx") {
            // A Tiled map: a new scene lighting it (saved as JSON beside it, never over it).
            TiledMap t = load_tiled(path);
            loaded = t.scene;
            loaded.map = path.string();
            w = std::move(t.world);
            warnings = t.warnings;
        } else {
            loaded = load_scene(path, &warnings);
            // Build first: a scene whose tileset is broken must not replace the document.
            w = build_world(loaded, path.string(), &warnings);
        }
        Scene before = e.scene;
        e.scene = loaded;
        e.world = std::move(w);
        e.world_source = loaded;
        fresh_frame(e);
        take_camera(e);
        commit_edit(e, before, now);
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
    e.selected = -1;
    e.selection.clear();
    e.fit_pending = e.view.width == 0;  // a scene without a camera: show all of its map
    e.scene_path = path.extension() == ".tmx" ? fs::path() : path;
    e.dirty = false;
    e.autosave_due = -1;
    if (remember) remember_file(e, path, FileKind::scene);
    set_status(e, warnings.empty() ? "loaded " + path.string() : warnings.front(), !warnings.empty());
    return true;
}
}  // namespace

bool load_scene_from(Editor& e, const fs::path& path, double now) { return load_scene_impl(e, path, now, true); }

bool export_preset(Editor& e, const fs::path& path) {
    try {
        save_preset(path, e.scene.params);
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
    remember_file(e, path, FileKind::preset);
    set_status(e, "exported preset " + path.string());
    return true;
}

bool import_preset(Editor& e, const fs::path& path, double now) {
    std::vector<std::string> warnings;
    try {
        Params p = load_preset(path, &warnings);
        set_params(e, p, now);
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
    remember_file(e, path, FileKind::preset);
    set_status(e, warnings.empty() ? "loaded preset " + path.string() : warnings.front(), !warnings.empty());
    return true;
}

bool load_tileset_from(Editor& e, const fs::path& manifest, double now) {
    Scene before = e.scene;
    e.scene.tileset = manifest.string();
    if (!sync_world(e)) return false;
    commit_edit(e, before, now);
    e.fit_pending = true;
    remember_file(e, manifest, FileKind::tileset);
    set_status(e, "loaded tileset " + manifest.string());
    return true;
}

fs::path autosave_path(const Editor& e) { return e.config / "autosave.json"; }

bool autosave_tick(Editor& e, double now) {
    if (e.autosave_due < 0 || now < e.autosave_due || !e.dirty) return false;
    e.autosave_due = -1;
    try {
        std::error_code ec;
        fs::create_directories(e.config, ec);
        save_scene(autosave_path(e), scene_to_save(e));
    } catch (const Error& err) {
        set_status(e, std::string("autosave failed: ") + err.what(), true);
        return false;
    }
    return true;
}

bool has_recovery(const Editor& e) { return fs::exists(autosave_path(e)); }

bool recover_autosave(Editor& e, double now) {
    const fs::path p = autosave_path(e);
    if (!load_scene_impl(e, p, now, false)) return false;
    e.scene_path.clear();  // recovered work is unsaved until the user saves it
    e.dirty = true;
    set_status(e, "recovered the autosaved scene: save it to keep it");
    return true;
}

void discard_autosave(Editor& e) {
    std::error_code ec;
    fs::remove(autosave_path(e), ec);
}

std::filesystem::path tileset_manifest(const Editor& e) {
    return e.scene.tileset.empty() ? default_tileset_manifest() : fs::path(e.scene.tileset);
}

void set_sprite_footprint(Editor& e, int sprite, const FootprintSpec& spec) {
    if (sprite < 0 || sprite >= int(e.world.tileset.sprites.size())) return;
    FootprintSpec& f = e.world.tileset.sprites[std::size_t(sprite)].footprint;
    if (f == spec) return;
    f = spec;
    touch(e.world);  // the obstacle map and opacity maps are rebuilt
    e.footprints_unsaved = true;
}

bool save_footprints(Editor& e) {
    const fs::path manifest = tileset_manifest(e);
    try {
        save_manifest_footprints(manifest, e.world.tileset);
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
    e.footprints_unsaved = false;
    set_status(e, "saved the footprints into " + manifest.string());
    return true;
}

bool walk_character(Editor& e, double dx, double dy) {
    Character& c = e.character;
    auto free_at = [&](double x, double y) {
        int col = 0, row = 0;
        if (!tile_at(e.world.map, e.world.placed, x, y, col, row)) return false;  // off the map
        return !e.frame.obstacles.get(int(std::floor(x)), int(std::floor(y)));
    };
    // Small steps, so a fast frame does not jump over a thin obstacle.
    const int steps = std::max(1, int(std::ceil(std::max(std::abs(dx), std::abs(dy)) / 2.0)));
    bool moved = false;
    for (int i = 0; i < steps; ++i) {
        const double sx = dx / steps, sy = dy / steps;
        if (free_at(c.x + sx, c.y + sy)) c.x += sx, c.y += sy, moved = true;
        else if (sx != 0 && free_at(c.x + sx, c.y)) c.x += sx, moved = true;
        else if (sy != 0 && free_at(c.x, c.y + sy)) c.y += sy, moved = true;
    }
    return moved;
}

Scene render_scene(const Editor& e) {
    Scene s = e.scene;
    if (e.character.enabled) {
        Light l = e.character.light;
        l.x = e.character.x;
        l.y = e.character.y;
        s.lights.push_back(l);
    }
    return s;
}

int light_at(const Editor& e, double x, double y, double radius) {
    int best = -1;
    double best_d = radius;
    for (int i = 0; i < int(e.scene.lights.size()); ++i) {
        const double d = std::hypot(e.scene.lights[i].x - x, e.scene.lights[i].y - y);
        if (d <= best_d) {
            best_d = d;
            best = i;
        }
    }
    return best;
}

// ---------------------------------------------------------------- lights

std::string light_label(const Scene& s, int i) {
    if (i < 0 || i >= int(s.lights.size())) return "no light";
    const Light& l = s.lights[std::size_t(i)];
    return l.name.empty() ? "light " + std::to_string(i + 1) : l.name;
}

bool is_selected(const Editor& e, int i) { return std::binary_search(e.selection.begin(), e.selection.end(), i); }

void select_light(Editor& e, int i, bool add) {
    if (i < 0 || i >= int(e.scene.lights.size())) {
        if (!add) e.selection.clear(), e.selected = -1;
        return;
    }
    if (!add) {
        e.selection = {i};
        e.selected = i;
        return;
    }
    auto it = std::lower_bound(e.selection.begin(), e.selection.end(), i);
    if (it != e.selection.end() && *it == i) {
        e.selection.erase(it);
        if (e.selected == i) e.selected = e.selection.empty() ? -1 : e.selection.back();
    } else {
        e.selection.insert(it, i);
        e.selected = i;
    }
}

void select_lights_in(Editor& e, Rect r, bool add) {
    if (!add) e.selection.clear();
    for (int i = 0; i < int(e.scene.lights.size()); ++i) {
        const Light& l = e.scene.lights[std::size_t(i)];
        if (l.x >= r.x && l.y >= r.y && l.x < r.x + r.w && l.y < r.y + r.h && !is_selected(e, i)) {
            e.selection.insert(std::lower_bound(e.selection.begin(), e.selection.end(), i), i);
        }
    }
    e.selected = e.selection.empty() ? -1 : e.selection.back();
}

void move_selection(Editor& e, double dx, double dy) {
    for (int i : e.selection) {
        Light& l = e.scene.lights[std::size_t(i)];
        if (l.locked) continue;
        l.x += dx;
        l.y += dy;
    }
}

void delete_selection(Editor& e, double now) {
    Scene before = e.scene;
    int removed = 0, locked = 0;
    for (auto it = e.selection.rbegin(); it != e.selection.rend(); ++it) {
        if (e.scene.lights[std::size_t(*it)].locked) {
            ++locked;
            continue;
        }
        e.scene.lights.erase(e.scene.lights.begin() + *it);
        ++removed;
    }
    e.selection.clear();
    e.selected = -1;
    commit_edit(e, before, now);
    set_status(e, "removed " + std::to_string(removed) + " light" + (removed == 1 ? "" : "s") +
                      (locked ? " (" + std::to_string(locked) + " locked kept)" : ""),
               locked > 0);
}

void copy_selection(Editor& e) {
    e.clipboard.clear();
    for (int i : e.selection) e.clipboard.push_back(e.scene.lights[std::size_t(i)]);
    set_status(e, "copied " + std::to_string(e.clipboard.size()) + " light" + (e.clipboard.size() == 1 ? "" : "s"));
}

namespace {
// Adds `lights` to the scene, selected, as one undo step.
void add_lights(Editor& e, const std::vector<Light>& lights, double dx, double dy, double now, const char* what) {
    if (lights.empty()) return;
    Scene before = e.scene;
    e.selection.clear();
    for (Light l : lights) {
        l.x = std::floor(l.x + dx) + 0.5;
        l.y = std::floor(l.y + dy) + 0.5;
        l.locked = false;
        e.scene.lights.push_back(l);
        e.selection.push_back(int(e.scene.lights.size()) - 1);
    }
    e.selected = e.selection.back();
    commit_edit(e, before, now);
    set_status(e, std::string(what) + " " + std::to_string(lights.size()) + " light" + (lights.size() == 1 ? "" : "s"));
}
}  // namespace

void duplicate_selection(Editor& e, double now) {
    std::vector<Light> copies;
    for (int i : e.selection) copies.push_back(e.scene.lights[std::size_t(i)]);
    add_lights(e, copies, 16, 16, now, "duplicated");
}

void paste_lights(Editor& e, double x, double y, double now) {
    if (e.clipboard.empty()) return;
    double cx = 0, cy = 0;
    for (const Light& l : e.clipboard) cx += l.x, cy += l.y;
    cx /= double(e.clipboard.size());
    cy /= double(e.clipboard.size());
    add_lights(e, e.clipboard, x - cx, y - cy, now, "pasted");
}

// ---------------------------------------------------------------- files and the window

void new_scene(Editor& e, double now) {
    Scene fresh;
    World w;
    try {
        w = build_world(fresh);
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return;
    }
    Scene before = e.scene;
    e.scene = fresh;
    e.world = std::move(w);
    e.world_source = fresh;
    fresh_frame(e);
    commit_edit(e, before, now);  // New can be undone
    e.scene_path.clear();
    e.dirty = false;
    e.autosave_due = -1;
    e.selected = -1;
    e.selection.clear();
    e.view = View{};
    e.fit_pending = true;
    set_status(e, "new scene");
}

std::string window_title(const Editor& e) {
    const std::string name = e.scene_path.empty() ? "untitled" : e.scene_path.filename().string();
    return name + (e.dirty ? " *" : "") + " - isolux";
}

FileKind detect_file_kind(const fs::path& path) {
    check_input_file(path, max_text_file_bytes);  // a FIFO or a folder is refused here, by name
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path.string() + ": cannot open");
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (path.extension() == ".tmx") return FileKind::scene;  // a Tiled map opens as a scene lighting it
    // By the fields only each kind has; the loader then checks the file whole.
    if (text.find("\"sprites\"") != std::string::npos) return FileKind::tileset;
    for (const char* k : {"\"seed\"", "\"lights\"", "\"edits\"", "\"width\"", "\"preset\"", "\"camera\""})
        if (text.find(k) != std::string::npos) return FileKind::scene;
    return FileKind::preset;
}

void fit_view(View& v, Rect world, Rect area) {
    if (world.empty() || area.empty()) return;
    const double margin = 16;
    const double zx = (area.w - 2 * margin) / double(world.w), zy = (area.h - 2 * margin) / double(world.h);
    v.zoom = std::clamp(std::min(zx, zy), min_zoom, max_zoom);
    v.x = world.x + world.w / 2.0 - (area.x + area.w / 2.0) / v.zoom;
    v.y = world.y + world.h / 2.0 - (area.y + area.h / 2.0) / v.zoom;
}

}  // namespace isolux::app
