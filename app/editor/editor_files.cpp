// The editor's files (editor.hpp): saving and loading scenes, presets and
// tilesets, the recent files, autosave and crash recovery, and saving a
// tileset's footprints. Every write is atomic; a failed load leaves the
// document as it was and says why in the status line.
#include <cerrno>
#include <csignal>
#include <unistd.h>

#include "common/assets.hpp"
#include "common/world.hpp"
#include "editor/editor.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

namespace {

void remember_file(Editor& e, const fs::path& path, FileKind kind) {
    add_recent(e.settings, fs::absolute(path).lexically_normal().string(), kind);
    try {
        save_settings(e.config, e.settings);
    } catch (const Error&) {
        // Settings are a convenience: failing to save them loses no work.
    }
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
            // Build first: a scene whose tileset is broken must not replace
            // the document (an endless one: its window around the camera).
            if (!loaded.endless) w = build_world(loaded, path.string(), &warnings);
        }
        Scene before = e.scene;
        if (loaded.endless) {
            open_endless(e, loaded, default_endless_view(loaded), path.string());
            e.view.width = loaded.camera.width;
            e.view.height = loaded.camera.height;
        } else {
            e.scene = loaded;
            e.world = std::move(w);
            e.world_source = loaded;
            e.endless.on = false;
            fresh_frame(e);
            take_camera(e);
        }
        commit_edit(e, before, now);
    } catch (const Error& err) {
        set_status(e, err.what(), true);
        return false;
    }
    e.selected = -1;
    e.selection.clear();
    // A scene without a camera: show all of its map (an endless world has no whole).
    e.fit_pending = !loaded.endless && e.view.width == 0;
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

fs::path autosave_path(const Editor& e) { return e.config / ("autosave-" + std::to_string(e.window) + ".json"); }

bool autosave_tick(Editor& e, double now) {
    if (e.autosave_due < 0 || now < e.autosave_due || !e.dirty) return false;
    e.autosave_due = -1;
    try {
        std::error_code ec;
        fs::create_directories(e.config, ec);
        save_scene(autosave_path(e), scene_to_save(e));
    } catch (const std::exception& err) {
        set_status(e, std::string("autosave failed: ") + err.what(), true);
        return false;
    }
    return true;
}

void discard_autosave(Editor& e) {
    std::error_code ec;
    fs::remove(autosave_path(e), ec);
}

namespace {

// Whether process `pid` runs (a window whose autosave is live).
bool window_alive(long pid) { return pid > 0 && (::kill(pid_t(pid), 0) == 0 || errno == EPERM); }

}  // namespace

fs::path recovery_path(const Editor& e) {
    fs::path best;
    fs::file_time_type newest{};
    std::error_code ec;
    int seen = 0;
    for (fs::directory_iterator it(e.config, ec); !ec && it != fs::directory_iterator() && ++seen < 10000; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        bool dead = name == "autosave.json";  // an older version's, whose window is gone
        if (!dead && name.rfind("autosave-", 0) == 0 && name.size() > 14 && name.ends_with(".json")) {
            const std::string id = name.substr(9, name.size() - 14);
            if (id.find_first_not_of("0123456789") != std::string::npos || id.size() > 9) continue;
            const long pid = std::stol(id);
            dead = pid != e.window && !window_alive(pid);
        }
        std::error_code tec;
        if (!dead || !it->is_regular_file(tec)) continue;
        const fs::file_time_type t = fs::last_write_time(it->path(), tec);
        if (best.empty() || t > newest) best = it->path(), newest = t;
    }
    return best;
}

bool has_recovery(const Editor& e) { return !recovery_path(e).empty(); }

bool recover_autosave(Editor& e, double now) {
    const fs::path p = recovery_path(e);
    if (p.empty() || !load_scene_impl(e, p, now, false)) return false;
    e.scene_path.clear();  // recovered work is unsaved until the user saves it
    e.dirty = true;
    // Kept as this window's own before the dead window's file goes.
    e.autosave_due = 0;
    if (autosave_tick(e, now)) {
        std::error_code ec;
        fs::remove(p, ec);
    }
    set_status(e, "recovered the autosaved scene: save it to keep it");
    return true;
}

void discard_recovery(Editor& e) {
    const fs::path p = recovery_path(e);
    std::error_code ec;
    if (!p.empty()) fs::remove(p, ec);
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

FileKind detect_file_kind(const fs::path& path) {
    const std::string text = read_text_file(path);  // a FIFO or a folder is refused here, by name
    if (path.extension() == ".tmx") return FileKind::scene;  // a Tiled map opens as a scene lighting it
    // By the fields only each kind has; the loader then checks the file whole.
    if (text.find("\"sprites\"") != std::string::npos) return FileKind::tileset;
    for (const char* k : {"\"seed\"", "\"lights\"", "\"edits\"", "\"width\"", "\"preset\"", "\"camera\""})
        if (text.find(k) != std::string::npos) return FileKind::scene;
    return FileKind::preset;
}

}  // namespace isolux::app
