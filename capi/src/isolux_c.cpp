// The C API (isolux.h) over isolux::core: a world is a Scene, its World and
// the FrameState that keeps what the last frame built, so a game's frame redoes
// only what changed. Every entry point catches everything: no exception
// crosses into C.
#include "isolux.h"

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <string>
#include <system_error>
#include <vector>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;
using namespace isolux;

struct isolux_world {
    Scene scene;                 // its edits are the opened file's; world.edits holds the level's
    World world;
    FrameState state;
    std::vector<int> light_ids;  // light_ids[i] names scene.lights[i]
    int next_id = 0;             // never reused; add_light refuses once it reaches INT_MAX
    std::string source;          // the file it came from, for messages
    bool allow_huge = false;     // isolux_world_allow_huge
    // A call is running on the world (one thread at a time): a second call
    // meanwhile is refused instead of racing it. isolux_world_cancel alone
    // may come from another thread: it sets `cancel`, which the running
    // frame reads (FrameOptions::control) and each call clears as it starts.
    mutable std::atomic<bool> busy{false};
    std::atomic<bool> cancel{false};
};

namespace {

thread_local std::string last_error;

// Runs `body`, turning every exception into a status and this thread's message.
template <class F>
isolux_status guarded(const char* call, F&& body) {
    try {
        body();
        return ISOLUX_OK;
    } catch (const Cancelled&) {
        last_error = std::string(call) + ": cancelled by isolux_world_cancel";
        return ISOLUX_CANCELLED;
    } catch (const Error& e) {
        last_error = printable(e.what());
        return ISOLUX_ERROR_INPUT;
    } catch (const std::bad_alloc&) {
        last_error = std::string(call) + ": out of memory";
        return ISOLUX_ERROR_MEMORY;
    } catch (const std::exception& e) {
        last_error = std::string(call) + ": " + printable(e.what());
        return ISOLUX_ERROR_INTERNAL;
    } catch (...) {
        last_error = std::string(call) + ": unknown failure";
        return ISOLUX_ERROR_INTERNAL;
    }
}

isolux_status argument_error(const std::string& message) {
    last_error = message;
    return ISOLUX_ERROR_ARGUMENT;
}

// Holds a world for one call: `held` is false (and the call must be refused)
// when another call is running on it, from another thread.
class Busy {
public:
    explicit Busy(const isolux_world* w) : w_(w) {
        bool idle = false;
        held_ = w_->busy.compare_exchange_strong(idle, true, std::memory_order_acquire);
        if (held_) const_cast<isolux_world*>(w_)->cancel.store(false, std::memory_order_relaxed);
    }
    ~Busy() {
        if (held_) w_->busy.store(false, std::memory_order_release);
    }
    Busy(const Busy&) = delete;
    Busy& operator=(const Busy&) = delete;
    bool held() const { return held_; }

private:
    const isolux_world* w_;
    bool held_ = false;
};

isolux_status busy_error(const char* call) {
    return argument_error(std::string(call) +
                          ": the world is in use by another call (a world is used by one thread at a time; "
                          "isolux_world_cancel alone may come from another thread)");
}

// The start of every call on a world: null and busy worlds refused.
#define ISOLUX_HOLD(world, call)                                                        \
    if (!(world)) return argument_error(std::string(call) + ": world must not be NULL"); \
    const Busy hold_##world(world);                                                       \
    if (!hold_##world.held()) return busy_error(call)

// The default tileset beside the library: $ISOLUX_ASSETS, else
// <libdir>/../share/isolux/assets (an installed prefix), else
// <libdir>/../assets (the Godot add-on's folder), found from this library's
// own path: a game may live anywhere, the library knows where it was put.
fs::path default_tileset() {
    const fs::path rel = fs::path("default") / "tileset.json";
    std::error_code ec;
    if (const char* env = std::getenv("ISOLUX_ASSETS"); env && *env && fs::exists(fs::path(env) / rel, ec))
        return fs::path(env) / rel;
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&isolux_api_version), &info) && info.dli_fname) {
        const fs::path lib = fs::weakly_canonical(fs::path(info.dli_fname), ec);
        const fs::path up = lib.parent_path().parent_path();
        for (const fs::path& beside : {up / "share" / "isolux" / "assets" / rel, up / "assets" / rel})
            if (!ec && fs::exists(beside, ec)) return beside;
    }
#ifdef ISOLUX_SOURCE_ASSETS
    if (fs::exists(fs::path(ISOLUX_SOURCE_ASSETS) / rel, ec)) return fs::path(ISOLUX_SOURCE_ASSETS) / rel;
#endif
    throw Error("default tileset not found: set ISOLUX_ASSETS to isolux's assets/ folder or pass a tileset manifest");
}

// The world for a scene: its Tiled map, or its seed on its tileset.
World build_world(const Scene& s, const std::string& source) {
    if (!s.map.empty()) return load_tiled(s.map).world;
    const fs::path manifest = s.tileset.empty() ? default_tileset() : fs::path(s.tileset);
    return make_world(load_tileset(manifest), s, source);
}

isolux_world* new_world(Scene scene, World world, std::string source) {
    auto* w = new isolux_world;
    w->scene = std::move(scene);
    w->world = std::move(world);
    w->source = std::move(source);
    w->state.options.control.cancel = &w->cancel;  // kept when a cancelled frame resets the state
    for (std::size_t i = 0; i < w->scene.lights.size(); ++i) w->light_ids.push_back(w->next_id++);
    return w;
}

// Index of light `id` in the scene, or -1.
int light_index(const isolux_world* w, int id) {
    const auto it = std::find(w->light_ids.begin(), w->light_ids.end(), id);
    return it == w->light_ids.end() ? -1 : int(it - w->light_ids.begin());
}

Light to_light(const isolux_light& c) {
    Light l;
    l.x = c.x;
    l.y = c.y;
    if (c.area_a > 0) l.area_a = c.area_a;
    if (c.area_b > 0) l.area_b = c.area_b;
    l.r = c.r;
    l.g = c.g;
    l.b = c.b;
    l.intensity = c.intensity;
    if (c.height >= 0) l.height = c.height;
    return l;
}

isolux_light from_light(const Light& l) {
    isolux_light c{};
    c.x = l.x;
    c.y = l.y;
    c.area_a = l.area_a.value_or(0);
    c.area_b = l.area_b.value_or(0);
    c.r = l.r;
    c.g = l.g;
    c.b = l.b;
    c.intensity = l.intensity;
    c.height = l.height.value_or(-1);
    return c;
}

// A light's fields in range, named; the scene file's limits.
void check_light(const isolux_light& c, const char* call) {
    const std::string where = std::string(call) + ": light ";
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || std::abs(c.x) > 1e9 || std::abs(c.y) > 1e9)
        throw Error(where + "x, y must be finite and within 1e9 pixels");
    if (!std::isfinite(c.intensity) || c.intensity < 0 || c.intensity > 1000)
        throw Error(where + "intensity must be in [0, 1000]");
    if (c.area_a > max_area || c.area_b > max_area)
        throw Error(where + "area_a, area_b must be at most " + std::to_string(max_area));
    if (!std::isfinite(c.height) || c.height > 1e6) throw Error(where + "height must be finite and at most 1e6");
}

}  // namespace

extern "C" {

int isolux_api_version(void) { return ISOLUX_API_VERSION; }

const char* isolux_last_error(void) { return last_error.c_str(); }

isolux_status isolux_world_open_seeded(const char* seed, int width, int height, const char* layout,
                                       const char* tileset_manifest, isolux_world** out) {
    if (!seed || !out) return argument_error("isolux_world_open_seeded: seed and out must not be NULL");
    return guarded("isolux_world_open_seeded", [&] {
        Scene s;
        s.seed = seed;
        if (!map_size_ok(width, height))
            throw Error(std::string("isolux_world_open_seeded: width x height: ") + map_size_rule());
        s.width = width;
        s.height = height;
        if (layout) s.layout = parse_layout(layout, "isolux_world_open_seeded: layout");
        if (tileset_manifest) s.tileset = tileset_manifest;
        World w = build_world(s, "isolux_world_open_seeded");
        *out = new_world(std::move(s), std::move(w), "seed");
    });
}

isolux_status isolux_world_open_scene(const char* scene_path, isolux_world** out) {
    if (!scene_path || !out) return argument_error("isolux_world_open_scene: scene_path and out must not be NULL");
    return guarded("isolux_world_open_scene", [&] {
        Scene s = load_scene(scene_path);
        World w = build_world(s, scene_path);
        *out = new_world(std::move(s), std::move(w), scene_path);
    });
}

isolux_status isolux_world_open_tmx(const char* tmx_path, isolux_world** out) {
    if (!tmx_path || !out) return argument_error("isolux_world_open_tmx: tmx_path and out must not be NULL");
    return guarded("isolux_world_open_tmx", [&] {
        TiledMap t = load_tiled(tmx_path);
        *out = new_world(std::move(t.scene), std::move(t.world), tmx_path);
    });
}

void isolux_world_free(isolux_world* world) {
    if (!world) return;
    if (world->busy.load(std::memory_order_acquire)) {
        // Freed while another thread's call runs on it: kept (a leak) rather
        // than pulled from under that call.
        last_error = "isolux_world_free: the world is in use by another call; not freed";
        return;
    }
    delete world;
}

isolux_status isolux_world_cancel(isolux_world* w) {
    if (!w) return argument_error("isolux_world_cancel: world must not be NULL");
    w->cancel.store(true, std::memory_order_relaxed);
    return ISOLUX_OK;
}

isolux_status isolux_world_allow_huge(isolux_world* w, int allow) {
    ISOLUX_HOLD(w, "isolux_world_allow_huge");
    w->allow_huge = allow != 0;
    return ISOLUX_OK;
}

isolux_status isolux_world_load_preset(isolux_world* w, const char* preset) {
    ISOLUX_HOLD(w, "isolux_world_load_preset");
    if (!preset) return argument_error("isolux_world_load_preset: preset must not be NULL");
    return guarded("isolux_world_load_preset", [&] { w->scene.params = preset_named(preset); });
}

isolux_status isolux_world_set_param(isolux_world* w, const char* name, const char* value) {
    ISOLUX_HOLD(w, "isolux_world_set_param");
    if (!name || !value) return argument_error("isolux_world_set_param: name and value must not be NULL");
    return guarded("isolux_world_set_param", [&] {
        Params p = w->scene.params;
        set_param(p, name, value, std::string("isolux_world_set_param: ") + name);
        validate(p, "isolux_world_set_param");
        w->scene.params = p;
    });
}

isolux_status isolux_world_get_param(const isolux_world* w, const char* name, char* buf, size_t size) {
    ISOLUX_HOLD(w, "isolux_world_get_param");
    if (!name || !buf) return argument_error("isolux_world_get_param: name and buf must not be NULL");
    std::string value;
    const isolux_status st = guarded("isolux_world_get_param", [&] {
        if (!find_param(name))  // what set_param refuses, get_param refuses too
            throw Error(std::string("isolux_world_get_param: unknown parameter \"") + printable(name) +
                        "\" (isolux-cli params lists them)");
        value = get_param(w->scene.params, name);
    });
    if (st != ISOLUX_OK) return st;
    if (value.size() + 1 > size)
        return argument_error("isolux_world_get_param: " + std::string(name) + " needs a buffer of " +
                              std::to_string(value.size() + 1) + " bytes");
    std::memcpy(buf, value.c_str(), value.size() + 1);
    return ISOLUX_OK;
}

isolux_status isolux_world_set_threads(isolux_world* w, int threads) {
    ISOLUX_HOLD(w, "isolux_world_set_threads");
    if (threads < 0 || threads > 256) return argument_error("isolux_world_set_threads: threads must be in [0, 256]");
    w->state.options.threads = threads;
    return ISOLUX_OK;
}

isolux_status isolux_light_init(isolux_light* light, double x, double y) {
    if (!light) return argument_error("isolux_light_init: light must not be NULL");
    Light l;
    l.x = x;
    l.y = y;
    *light = from_light(l);
    return ISOLUX_OK;
}

isolux_status isolux_world_add_light(isolux_world* w, const isolux_light* light, int* id) {
    ISOLUX_HOLD(w, "isolux_world_add_light");
    if (!light) return argument_error("isolux_world_add_light: light must not be NULL");
    return guarded("isolux_world_add_light", [&] {
        check_light(*light, "isolux_world_add_light");
        if (w->next_id == INT_MAX)
            throw Error("isolux_world_add_light: this world has given out every light id (ids are never reused); "
                        "open a new world");
        w->scene.lights.push_back(to_light(*light));
        w->light_ids.push_back(w->next_id);
        if (id) *id = w->next_id;
        ++w->next_id;
    });
}

isolux_status isolux_world_set_light(isolux_world* w, int id, const isolux_light* light) {
    ISOLUX_HOLD(w, "isolux_world_set_light");
    if (!light) return argument_error("isolux_world_set_light: light must not be NULL");
    const int i = light_index(w, id);
    if (i < 0) return argument_error("isolux_world_set_light: no light with id " + std::to_string(id));
    return guarded("isolux_world_set_light", [&] {
        check_light(*light, "isolux_world_set_light");
        Light& now = w->scene.lights[std::size_t(i)];
        Light l = to_light(*light);
        // What the struct does not carry stays as it is.
        l.name = now.name;
        l.hidden = now.hidden;
        l.locked = now.locked;
        now = l;
    });
}

isolux_status isolux_world_set_light_hidden(isolux_world* w, int id, int hidden) {
    ISOLUX_HOLD(w, "isolux_world_set_light_hidden");
    const int i = light_index(w, id);
    if (i < 0) return argument_error("isolux_world_set_light_hidden: no light with id " + std::to_string(id));
    w->scene.lights[std::size_t(i)].hidden = hidden != 0;
    return ISOLUX_OK;
}

isolux_status isolux_world_get_light(const isolux_world* w, int id, isolux_light* light) {
    ISOLUX_HOLD(w, "isolux_world_get_light");
    if (!light) return argument_error("isolux_world_get_light: light must not be NULL");
    const int i = light_index(w, id);
    if (i < 0) return argument_error("isolux_world_get_light: no light with id " + std::to_string(id));
    *light = from_light(w->scene.lights[std::size_t(i)]);
    return ISOLUX_OK;
}

isolux_status isolux_world_move_light(isolux_world* w, int id, double x, double y) {
    ISOLUX_HOLD(w, "isolux_world_move_light");
    const int i = light_index(w, id);
    if (i < 0) return argument_error("isolux_world_move_light: no light with id " + std::to_string(id));
    isolux_light c = from_light(w->scene.lights[std::size_t(i)]);
    c.x = x;
    c.y = y;
    return guarded("isolux_world_move_light", [&] {
        check_light(c, "isolux_world_move_light");
        w->scene.lights[std::size_t(i)].x = x;
        w->scene.lights[std::size_t(i)].y = y;
    });
}

isolux_status isolux_world_remove_light(isolux_world* w, int id) {
    ISOLUX_HOLD(w, "isolux_world_remove_light");
    const int i = light_index(w, id);
    if (i < 0) return argument_error("isolux_world_remove_light: no light with id " + std::to_string(id));
    w->scene.lights.erase(w->scene.lights.begin() + i);
    w->light_ids.erase(w->light_ids.begin() + i);
    return ISOLUX_OK;
}

isolux_status isolux_world_lights(const isolux_world* w, int* ids, int capacity, int* count) {
    ISOLUX_HOLD(w, "isolux_world_lights");
    if (!count || (capacity > 0 && !ids))
        return argument_error("isolux_world_lights: count must not be NULL (ids neither, with a capacity)");
    *count = int(w->light_ids.size());
    for (int i = 0; i < std::min(capacity, *count); ++i) ids[i] = w->light_ids[std::size_t(i)];
    return ISOLUX_OK;
}

isolux_status isolux_world_set_tile(isolux_world* w, int col, int row, const char* floor, const char* const* overlays,
                                    int overlay_count) {
    ISOLUX_HOLD(w, "isolux_world_set_tile");
    if (overlay_count > 3) return argument_error("isolux_world_set_tile: at most 3 overlays");
    if (overlay_count > 0 && !overlays) return argument_error("isolux_world_set_tile: overlays must not be NULL");
    for (int i = 0; i < overlay_count; ++i)
        if (!overlays[i])
            return argument_error("isolux_world_set_tile: overlays[" + std::to_string(i) + "] must not be NULL");
    const std::string where = "isolux_world_set_tile(" + std::to_string(col) + ", " + std::to_string(row) + ")";
    return guarded("isolux_world_set_tile", [&] {
        const Map& m = w->world.map;
        if (!w->scene.map.empty() || m.tiles.empty() || w->world.seeded.tiles.empty())
            throw Error(where + ": only a seeded map's tiles are edited");
        if (col < 0 || row < 0 || col >= m.width || row >= m.height)
            throw Error(where + ": the tile is outside the " + std::to_string(m.width) + "x" +
                        std::to_string(m.height) + " map");
        // The names, resolved (and refused by name) as a scene file's edit is.
        TileEdit e{col, row, {}, {}};
        if (floor) e.floor = floor;
        if (overlay_count >= 0) e.overlays.emplace(overlays, overlays + overlay_count);
        const ResolvedEdit r = resolve_edits({e}, w->world.tileset, where).at(0);
        const Tile& now = m.at(col, row);
        set_tile(w->world, col, row, r.floor.value_or(now.floor), r.overlays.value_or(overlay_sprites(now)));
    });
}

isolux_status isolux_world_clear_edits(isolux_world* w) {
    ISOLUX_HOLD(w, "isolux_world_clear_edits");
    return guarded("isolux_world_clear_edits", [&] {
        if (w->world.edits.empty()) return;
        set_edits(w->world, {}, "isolux_world_clear_edits");
    });
}

isolux_status isolux_world_tiles(const isolux_world* w, int* columns, int* rows) {
    ISOLUX_HOLD(w, "isolux_world_tiles");
    if (!columns || !rows) return argument_error("isolux_world_tiles: columns and rows must not be NULL");
    *columns = w->world.map.width;
    *rows = w->world.map.height;
    return ISOLUX_OK;
}

isolux_status isolux_world_bounds(const isolux_world* w, isolux_rect* out) {
    ISOLUX_HOLD(w, "isolux_world_bounds");
    if (!out) return argument_error("isolux_world_bounds: out must not be NULL");
    const Rect r = w->world.placed.bounds;
    *out = {r.x, r.y, r.w, r.h};
    return ISOLUX_OK;
}

isolux_status isolux_world_default_view(const isolux_world* w, isolux_rect* out) {
    ISOLUX_HOLD(w, "isolux_world_default_view");
    if (!out) return argument_error("isolux_world_default_view: out must not be NULL");
    return guarded("isolux_world_default_view", [&] {
        const Rect r = camera_view(w->scene.camera, w->world);
        *out = {r.x, r.y, r.w, r.h};
    });
}

isolux_status isolux_world_render(isolux_world* w, isolux_rect view, int frame, uint8_t* rgba, size_t size,
                                  uint8_t* light_rgba, size_t light_size) {
    ISOLUX_HOLD(w, "isolux_world_render");
    if (view.width < 1 || view.height < 1 || view.width > max_image_side || view.height > max_image_side)
        return argument_error("isolux_world_render: view width and height must be in [1, " +
                              std::to_string(max_image_side) + "]");
    if (std::int64_t(view.width) * view.height > max_render_pixels)
        return argument_error("isolux_world_render: the view is over the 256-megapixel limit");
    if (std::abs(std::int64_t(view.x)) > 1000000000 || std::abs(std::int64_t(view.y)) > 1000000000)
        return argument_error("isolux_world_render: view x and y must be within 1e9 pixels");  // x + width fits an int
    if (frame < 0) return argument_error("isolux_world_render: frame must be 0 or more");
    const std::size_t bytes = std::size_t(view.width) * std::size_t(view.height) * 4;
    if (rgba && size != bytes)
        return argument_error("isolux_world_render: rgba holds " + std::to_string(size) + " bytes; the view needs " +
                              std::to_string(bytes));
    if (light_rgba && light_size != bytes)
        return argument_error("isolux_world_render: light_rgba holds " + std::to_string(light_size) +
                              " bytes; the view needs " + std::to_string(bytes));
    // The work budget isolux-cli keeps (--allow-huge), before any of it.
    const double steps = render_work(w->scene, Rect{view.x, view.y, view.width, view.height}, 1);
    if (steps > huge_trace_steps && !w->allow_huge) {
        char text[32];
        std::snprintf(text, sizeof text, "%.2g", steps);
        last_error = std::string("isolux_world_render: this frame would trace about ") + text +
                     " ray steps (minutes or more): use a smaller area or view, border rays, or "
                     "isolux_world_allow_huge(world, 1)";
        return ISOLUX_ERROR_TOO_MUCH_WORK;
    }
    const double memory = render_memory(Rect{view.x, view.y, view.width, view.height});
    if (memory > huge_render_bytes && !w->allow_huge) {
        last_error = "isolux_world_render: this frame would hold " + about_gib(memory) +
                     " at once (its view's pixels): render a smaller view, or isolux_world_allow_huge(world, 1)";
        return ISOLUX_ERROR_TOO_MUCH_WORK;
    }
    return guarded("isolux_world_render", [&] {
        w->state.options.view_light_texture = light_rgba != nullptr;
        Camera cam = w->scene.camera;
        cam.x = view.x;
        cam.y = view.y;
        cam.width = view.width;
        cam.height = view.height;
        render_frame(w->state, w->world, w->scene, cam, frame);
        if (rgba) std::memcpy(rgba, w->state.final.rgba.data(), bytes);
        if (light_rgba) {
            const Image light = light_texture_image(w->state.light);
            std::memcpy(light_rgba, light.rgba.data(), bytes);
        }
    });
}

}  // extern "C"
