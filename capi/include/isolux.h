/* isolux.h: isolux's lighting for games, as a plain C11 API over libisolux.
 *
 * A world is a level (a seeded map, a scene file or a Tiled map) with its
 * parameters and lights; render it into your own buffers once a frame. Every
 * call returns an isolux_status; when it is not ISOLUX_OK, isolux_last_error()
 * says what failed (the file and field, as isolux-cli does). No C++ exception
 * crosses this API. A world is used by one thread at a time; different worlds
 * may be used on different threads. A call on a world while another thread's
 * call runs on it is refused (ISOLUX_ERROR_ARGUMENT), never a race; only
 * isolux_world_cancel may come from another thread. docs/games.md walks
 * through it. */
#ifndef ISOLUX_H
#define ISOLUX_H

#include <stddef.h>
#include <stdint.h>

/* Bumped whenever a declaration below changes meaning or layout. */
#define ISOLUX_API_VERSION 2

#if defined(ISOLUX_BUILDING_API)
#define ISOLUX_API __attribute__((visibility("default")))
#else
#define ISOLUX_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum isolux_status {
    ISOLUX_OK = 0,
    ISOLUX_ERROR_INPUT = 1,    /* a file, parameter or value was refused */
    ISOLUX_ERROR_ARGUMENT = 2, /* a null pointer, an unknown light id, a buffer of the wrong size */
    ISOLUX_ERROR_MEMORY = 3,   /* out of memory; the world is as it was */
    ISOLUX_ERROR_INTERNAL = 4, /* a bug in isolux: please report the message */
    ISOLUX_ERROR_TOO_MUCH_WORK = 5, /* the frame's estimated work is over the budget (isolux_world_allow_huge) */
    ISOLUX_CANCELLED = 6       /* isolux_world_cancel stopped the call; the world is as it was before it */
} isolux_status;

typedef struct isolux_world isolux_world; /* opaque */

/* A rectangle in world pixels (the map's own frame, as scenes and
 * isolux-cli's --view use). */
typedef struct isolux_rect {
    int32_t x, y, width, height;
} isolux_rect;

/* One light. area_a, area_b <= 0 and height < 0 mean "the preset's". */
typedef struct isolux_light {
    double x, y;        /* centre, world pixels */
    int32_t area_a, area_b; /* half-extents of its a x b area, pixels */
    uint8_t r, g, b;
    double intensity;   /* scales the paper's 255 / (1 + d); 1 is the paper's */
    double height;      /* above the ground, pixels (occluders solids/shapes) */
} isolux_light;

/* The version this library was built as: compare with ISOLUX_API_VERSION. */
ISOLUX_API int isolux_api_version(void);

/* The message of this thread's last failed call ("" when none failed yet).
 * Valid until the next call on this thread. */
ISOLUX_API const char* isolux_last_error(void);

/* --- Opening a world (*out is set only on ISOLUX_OK; free with isolux_world_free) */

/* A seeded map: `seed` text, `width` x `height` tiles, `layout` "diamond",
 * "staggered" or "paper" (NULL: diamond), on the tileset manifest
 * `tileset_manifest` (NULL: isolux's default tileset, found under
 * $ISOLUX_ASSETS, else beside the installed library or add-on). No lights. */
ISOLUX_API isolux_status isolux_world_open_seeded(const char* seed, int width, int height, const char* layout,
                                                  const char* tileset_manifest, isolux_world** out);
/* A scene JSON file (seed or Tiled map, preset, lights, camera, edits). */
ISOLUX_API isolux_status isolux_world_open_scene(const char* scene_path, isolux_world** out);
/* A Tiled map (.tmx): its floors, sprites, lights and preset. */
ISOLUX_API isolux_status isolux_world_open_tmx(const char* tmx_path, isolux_world** out);
/* NULL is ignored; a world another thread's call is using is not freed
 * (isolux_last_error says so). */
ISOLUX_API void isolux_world_free(isolux_world* world);

/* --- Long work: a budget, and a way to stop */

/* Makes the call running on `world` on another thread (a render) stop within
 * milliseconds and return ISOLUX_CANCELLED, the world as it was before that
 * call (its next frame is drawn afresh). The one call allowed while another
 * thread's call runs on the world; a cancel while none runs is forgotten when
 * the next call starts. */
ISOLUX_API isolux_status isolux_world_cancel(isolux_world* world);
/* A render whose estimated work (isolux-cli's, in ray steps) is beyond
 * minutes on one core, or whose view would hold over 1 GiB at once (about 54
 * megapixels), returns ISOLUX_ERROR_TOO_MUCH_WORK with the estimate, before
 * any of it; `allow` 1 lets this world run it anyway (0: the default). */
ISOLUX_API isolux_status isolux_world_allow_huge(isolux_world* world, int allow);

/* --- Parameters, by the names of `isolux-cli params` */

/* A built-in preset name (paper, fast, quality, game: always the built-in,
 * whatever the working folder holds), else a preset JSON file's path. */
ISOLUX_API isolux_status isolux_world_load_preset(isolux_world* world, const char* preset);
/* One parameter, as text ("4", "true", "solids"); refused by name when out of range. */
ISOLUX_API isolux_status isolux_world_set_param(isolux_world* world, const char* name, const char* value);
/* Its value as text into `buf` (NUL-terminated; ISOLUX_ERROR_ARGUMENT when
 * `size` is too small; ISOLUX_ERROR_INPUT for a name set_param refuses). */
ISOLUX_API isolux_status isolux_world_get_param(const isolux_world* world, const char* name, char* buf, size_t size);
/* Threads that trace and correct lights: 0 one per core, 1 (the default) the
 * caller's thread only. The pixels are the same for any count. */
ISOLUX_API isolux_status isolux_world_set_threads(isolux_world* world, int threads);

/* --- Lights. Ids are stable for a world's life and never reused (add_light
 * refuses once a world has given out INT_MAX of them); a scene's or a map's
 * own lights have ids 0, 1, ... in their order. */

ISOLUX_API isolux_status isolux_light_init(isolux_light* light, double x, double y); /* white, intensity 1, the preset's area and height */
ISOLUX_API isolux_status isolux_world_add_light(isolux_world* world, const isolux_light* light, int* id);
/* Sets the struct's fields; the light's name, and whether it is hidden or
 * locked (a scene's own lights may be), stay as they are. */
ISOLUX_API isolux_status isolux_world_set_light(isolux_world* world, int id, const isolux_light* light);
/* A hidden light is kept but lights nothing (`hidden` 1), or shown again (0). */
ISOLUX_API isolux_status isolux_world_set_light_hidden(isolux_world* world, int id, int hidden);
ISOLUX_API isolux_status isolux_world_get_light(const isolux_world* world, int id, isolux_light* light);
ISOLUX_API isolux_status isolux_world_move_light(isolux_world* world, int id, double x, double y);
ISOLUX_API isolux_status isolux_world_remove_light(isolux_world* world, int id);
/* The ids in order into `ids` (up to `capacity`); *count is how many there are. */
ISOLUX_API isolux_status isolux_world_lights(const isolux_world* world, int* ids, int capacity, int* count);

/* --- Terrain edits (tile column and row as the layout numbers them) */

/* Tile (col, row) holds `floor` (a floor sprite's name; NULL: unchanged) and
 * the `overlay_count` overlays named in `overlays` (at most 3; overlay_count
 * < 0: unchanged). Refused by name when a name is not a sprite of the tileset
 * or the tile is outside the map; the world is then unchanged. An edit costs
 * its tile, whatever the edits before it. */
ISOLUX_API isolux_status isolux_world_set_tile(isolux_world* world, int col, int row, const char* floor,
                                               const char* const* overlays, int overlay_count);
/* Every edit undone: the seed's map again. */
ISOLUX_API isolux_status isolux_world_clear_edits(isolux_world* world);
/* The map's size in tiles. */
ISOLUX_API isolux_status isolux_world_tiles(const isolux_world* world, int* columns, int* rows);

/* --- Rendering */

/* The whole map's rectangle in world pixels. */
ISOLUX_API isolux_status isolux_world_bounds(const isolux_world* world, isolux_rect* out);
/* What `isolux-cli render` renders with no --view: the scene's camera, or
 * the whole map when it has no size. */
ISOLUX_API isolux_status isolux_world_default_view(const isolux_world* world, isolux_rect* out);
/* Renders frame number `frame` (0, 1, ...: "every l frames" counts them) of
 * `view` (x and y within 1e9 pixels; width and height in [1, 65536], at
 * most 256 megapixels). `rgba` receives the final picture and `light_rgba` the blurred
 * light texture (isolux-cli's --layer light), each view.width x view.height
 * x 4 bytes, rows top to bottom; either may be NULL. `size` and `light_size`
 * are the buffers' byte sizes. A world renders only what changed since its
 * last frame (a moved light, an edit), as the editor does. */
ISOLUX_API isolux_status isolux_world_render(isolux_world* world, isolux_rect view, int frame, uint8_t* rgba,
                                             size_t size, uint8_t* light_rgba, size_t light_size);

#ifdef __cplusplus
}
#endif
#endif /* ISOLUX_H */
