// The editor's document: the scene and its world, edits and undo
// (editor.hpp); its files and autosave are in editor_files.cpp, its terrain
// tools and lights in editor_terrain.cpp and editor_lights.cpp.
#include "editor/editor.hpp"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <unistd.h>
#include <cmath>
#include <fstream>
#include <iterator>

#include "common/assets.hpp"
#include "common/world.hpp"
#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/hash.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

namespace {

bool same_world_fields(const Scene& a, const Scene& b) {
    return a.seed == b.seed && a.width == b.width && a.height == b.height && a.layout == b.layout &&
           a.tileset == b.tileset && a.map == b.map && a.endless == b.endless;
}

}  // namespace

void take_camera(Editor& e) {
    e.view.x = e.scene.camera.x;
    e.view.y = e.scene.camera.y;
    e.view.width = e.scene.camera.width;
    e.view.height = e.scene.camera.height;
    e.scene.camera = Camera{};
    e.world_source.camera = Camera{};
}

void fresh_frame(Editor& e) {
    const FrameOptions keep = e.frame.options;
    e.frame = FrameState{};
    e.frame.options = keep;
}

void reset_view(Editor& e) {
    e.view.x = e.view.y = 0;
    e.view.zoom = 1;
}

MapFields map_fields(const Editor& e) {
    return {e.scene.seed, e.scene.width, e.scene.height, e.scene.endless, e.scene.layout, e.scene.tileset};
}

Scene scene_to_save(const Editor& e) {
    if (e.scene.endless) {
        // The world's own pixels and tiles; the camera keeps the view's size
        // (an endless render needs one).
        Scene s = endless_world_scene(e, e.scene);
        const WorldRect& v = e.endless.last_view;
        s.camera = {e.view.x + double(e.endless.origin_x), e.view.y + double(e.endless.origin_y),
                    e.view.width > 0 ? e.view.width : v.w, e.view.height > 0 ? e.view.height : v.h};
        return s;
    }
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
    e.window = long(::getpid());
    std::string warning;
    e.settings = load_settings(config, &warning);
    if (!warning.empty()) set_status(e, warning, true);
    e.frame.options.cpu_sprites = false;
    e.frame.options.cpu_blur_and_composite = false;
    if (scene.endless) {
        const WorldRect view = default_endless_view(scene);
        open_endless(e, scene, view, "scene");
        e.view.width = scene.camera.width;
        e.view.height = scene.camera.height;
        e.fit_pending = false;  // an endless world has no whole to fit
        return e;
    }
    e.world = build_world(scene);
    e.world_source = scene;
    take_camera(e);
    return e;
}

std::size_t scene_bytes(const Scene& s) {
    std::size_t n = sizeof(Scene) + s.seed.capacity() + s.tileset.capacity() + s.lights.capacity() * sizeof(Light) +
                    s.edits.capacity() * sizeof(TileEdit);
    for (const Light& l : s.lights) n += l.name.capacity();
    for (const TileEdit& t : s.edits) {
        if (t.floor) n += t.floor->capacity();
        if (t.overlays)
            for (const std::string& o : *t.overlays) n += sizeof(std::string) + o.capacity();
    }
    return n;
}

void commit_edit(Editor& e, const Scene& before, double now) {
    if (before == e.scene) return;
    e.undo_stack.push_back(HistoryStep{before, scene_bytes(before)});
    // The oldest steps go past max_undo steps, or past max_undo_bytes (the newest always stays).
    std::size_t bytes = 0, keep = 0;
    for (auto it = e.undo_stack.rbegin(); it != e.undo_stack.rend() && keep < max_undo; ++it, ++keep)
        if ((bytes += it->bytes) > max_undo_bytes && keep > 0) break;
    e.undo_stack.erase(e.undo_stack.begin(), e.undo_stack.end() - std::ptrdiff_t(keep));
    e.redo_stack.clear();
    e.dirty = true;
    e.autosave_due = now + autosave_delay;
}

bool sync_world(Editor& e) {
    if (e.scene.endless && !same_world_fields(e.scene, e.world_source)) {
        if (sync_endless_world(e)) return true;
        e.scene.seed = e.world_source.seed;
        e.scene.layout = e.world_source.layout;
        e.scene.tileset = e.world_source.tileset;
        return false;
    }
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
        e.endless.on = false;
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

namespace {
// Undo and redo are one move between the two stacks, in opposite directions.
bool step_history(Editor& e, std::vector<HistoryStep>& from, std::vector<HistoryStep>& to, double now, const char* what) {
    if (from.empty()) return false;
    to.push_back(HistoryStep{std::move(e.scene), 0});
    to.back().bytes = scene_bytes(to.back().scene);
    e.scene = std::move(from.back().scene);
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


bool undo(Editor& e, double now) { return step_history(e, e.undo_stack, e.redo_stack, now, "undo"); }
bool redo(Editor& e, double now) { return step_history(e, e.redo_stack, e.undo_stack, now, "redo"); }



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
    e.endless.on = false;
    e.fit_pending = true;
    set_status(e, "new scene");
}

std::string window_title(const Editor& e) {
    const std::string name = e.scene_path.empty() ? "untitled" : e.scene_path.filename().string();
    return name + (e.dirty ? " *" : "") + " - isolux";
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
