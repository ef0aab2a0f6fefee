/* IsoluxLighting: isolux's own lighting inside Godot 3.2, a NativeScript class
 * (GDNative, C) over libisolux's C API. GDScript opens a level, moves lights
 * and asks for a frame's bytes:
 *
 *   var lighting = preload("res://isolux/isolux_lighting.gdns").new()
 *   if not lighting.open_scene(ProjectSettings.globalize_path("res://level.json")):
 *       push_error(lighting.last_error())
 *   var id = lighting.add_light(700, 420, 0xffd49a, 40)
 *   var bytes = lighting.render(x, y, w, h, frame, "light")  # RGBA8, rows top to bottom
 *
 * Paths are file-system paths (globalize res:// ones). Every method returns
 * false, -1 or an empty array on failure, and last_error() says why: an
 * integer outside what the C API takes (GDScript's are 64-bit) or an unknown
 * layer is refused by name, never narrowed or guessed. */
#include <gdnative_api_struct.gen.h>
#include <isolux.h>

#include <stdint.h>
#include <stdio.h>
#include <string.h>

static const godot_gdnative_core_api_struct* api = NULL;
static const godot_gdnative_ext_nativescript_api_struct* nativescript = NULL;

typedef struct Lighting {
    isolux_world* world;
    char error[1024]; /* last_error(): this instance's last refusal, its own or the library's */
} Lighting;

/* --- Variant helpers */

static void utf8_arg(godot_variant** args, int i, char* buf, size_t size) {
    godot_string s = api->godot_variant_as_string(args[i]);
    godot_char_string cs = api->godot_string_utf8(&s);
    const char* text = api->godot_char_string_get_data(&cs);
    strncpy(buf, text ? text : "", size - 1);
    buf[size - 1] = '\0';
    api->godot_char_string_destroy(&cs);
    api->godot_string_destroy(&s);
}

static godot_variant bool_result(int ok) {
    godot_variant v;
    api->godot_variant_new_bool(&v, ok ? 1 : 0);
    return v;
}

static godot_variant int_result(int64_t i) {
    godot_variant v;
    api->godot_variant_new_int(&v, i);
    return v;
}

static godot_variant string_result(const char* text) {
    godot_string s;
    godot_variant v;
    api->godot_string_new(&s);
    api->godot_string_parse_utf8(&s, text);
    api->godot_variant_new_string(&v, &s);
    api->godot_string_destroy(&s);
    return v;
}

/* The library's answer: on failure its message becomes last_error(). */
static int library_ok(Lighting* l, isolux_status status) {
    if (status != ISOLUX_OK) snprintf(l->error, sizeof l->error, "%s", isolux_last_error());
    return status == ISOLUX_OK;
}

/* GDScript's integers are 64-bit: argument i must lie in [lo, hi] before it
 * is narrowed, or the call is refused naming it (never used wrapped). */
static int int_arg(Lighting* l, const char* method, godot_variant** args, int i, const char* name, int64_t lo,
                   int64_t hi, int64_t* out) {
    const int64_t v = api->godot_variant_as_int(args[i]);
    if (v < lo || v > hi) {
        snprintf(l->error, sizeof l->error, "IsoluxLighting.%s: %s = %lld is outside [%lld, %lld]", method, name,
                 (long long)v, (long long)lo, (long long)hi);
        return 0;
    }
    *out = v;
    return 1;
}

static int enough(Lighting* l, const char* method, int argc, int wanted) {
    if (!l->world && strcmp(method, "open_scene") != 0 && strcmp(method, "open_tmx") != 0) {
        snprintf(l->error, sizeof l->error, "IsoluxLighting.%s: no level is open (open_scene or open_tmx first)", method);
        return 0;
    }
    if (argc < wanted) {
        snprintf(l->error, sizeof l->error, "IsoluxLighting.%s: takes %d arguments, got %d", method, wanted, argc);
        return 0;
    }
    return 1;
}

/* --- The instance */

static void* lighting_new(godot_object* owner, void* method_data) {
    (void)owner, (void)method_data;
    Lighting* l = api->godot_alloc(sizeof(Lighting));
    l->world = NULL;
    l->error[0] = '\0';
    return l;
}

static void lighting_delete(godot_object* owner, void* method_data, void* data) {
    (void)owner, (void)method_data;
    Lighting* l = data;
    isolux_world_free(l->world);
    api->godot_free(l);
}

#define METHOD(name)                                                                                           \
    static godot_variant name(godot_object* owner, void* method_data, void* data, int argc, godot_variant** args)
#define UNUSED (void)owner, (void)method_data

static godot_variant open_with(Lighting* l, int tmx, godot_variant** args) {
    char path[4096];
    utf8_arg(args, 0, path, sizeof path);
    isolux_world* w = NULL;
    if (!library_ok(l, tmx ? isolux_world_open_tmx(path, &w) : isolux_world_open_scene(path, &w))) return bool_result(0);
    isolux_world_free(l->world);
    l->world = w;
    return bool_result(1);
}

METHOD(open_scene) { UNUSED; return enough(data, "open_scene", argc, 1) ? open_with(data, 0, args) : bool_result(0); }
METHOD(open_tmx) { UNUSED; return enough(data, "open_tmx", argc, 1) ? open_with(data, 1, args) : bool_result(0); }

METHOD(load_preset) {
    UNUSED;
    Lighting* l = data;
    if (!enough(l, "load_preset", argc, 1)) return bool_result(0);
    char name[4096];
    utf8_arg(args, 0, name, sizeof name);
    return bool_result(library_ok(l, isolux_world_load_preset(l->world, name)));
}

METHOD(set_param) {
    UNUSED;
    Lighting* l = data;
    if (!enough(l, "set_param", argc, 2)) return bool_result(0);
    char name[256], value[256];
    utf8_arg(args, 0, name, sizeof name);
    utf8_arg(args, 1, value, sizeof value);
    return bool_result(library_ok(l, isolux_world_set_param(l->world, name, value)));
}

/* add_light(x, y, rgb = 0xffffff, height = -1 (the preset's)) -> id or -1 */
METHOD(add_light) {
    UNUSED;
    Lighting* l = data;
    if (!enough(l, "add_light", argc, 2)) return int_result(-1);
    isolux_light light;
    isolux_light_init(&light, api->godot_variant_as_real(args[0]), api->godot_variant_as_real(args[1]));
    if (argc > 2) {
        int64_t rgb = 0;
        if (!int_arg(l, "add_light", args, 2, "rgb", 0, 0xffffff, &rgb)) return int_result(-1);
        light.r = (uint8_t)(rgb >> 16), light.g = (uint8_t)(rgb >> 8), light.b = (uint8_t)rgb;
    }
    if (argc > 3) light.height = api->godot_variant_as_real(args[3]);
    int id = -1;
    return int_result(library_ok(l, isolux_world_add_light(l->world, &light, &id)) ? id : -1);
}

METHOD(move_light) {
    UNUSED;
    Lighting* l = data;
    int64_t id = 0;
    if (!enough(l, "move_light", argc, 3) || !int_arg(l, "move_light", args, 0, "id", 0, INT32_MAX, &id))
        return bool_result(0);
    return bool_result(library_ok(l, isolux_world_move_light(l->world, (int)id, api->godot_variant_as_real(args[1]),
                                                             api->godot_variant_as_real(args[2]))));
}

METHOD(remove_light) {
    UNUSED;
    Lighting* l = data;
    int64_t id = 0;
    if (!enough(l, "remove_light", argc, 1) || !int_arg(l, "remove_light", args, 0, "id", 0, INT32_MAX, &id))
        return bool_result(0);
    return bool_result(library_ok(l, isolux_world_remove_light(l->world, (int)id)));
}

/* default_view() -> Rect2: what isolux-cli renders with no --view. */
METHOD(default_view) {
    UNUSED, (void)argc, (void)args;
    Lighting* l = data;
    isolux_rect r = {0, 0, 0, 0};
    if (l->world) library_ok(l, isolux_world_default_view(l->world, &r));
    godot_rect2 rect;
    godot_variant v;
    api->godot_rect2_new(&rect, (godot_real)r.x, (godot_real)r.y, (godot_real)r.width, (godot_real)r.height);
    api->godot_variant_new_rect2(&v, &rect);
    return v;
}

/* render(x, y, w, h, frame, layer "final" or "light") -> PoolByteArray of
 * w * h RGBA8 pixels, empty on failure. */
METHOD(render) {
    UNUSED;
    Lighting* l = data;
    godot_pool_byte_array bytes;
    api->godot_pool_byte_array_new(&bytes);
    int64_t x = 0, y = 0, w = 0, h = 0, frame = 0;
    char layer[16] = "";
    if (enough(l, "render", argc, 6) && int_arg(l, "render", args, 0, "x", -1000000000, 1000000000, &x) &&
        int_arg(l, "render", args, 1, "y", -1000000000, 1000000000, &y) &&
        int_arg(l, "render", args, 2, "w", 1, 65536, &w) && int_arg(l, "render", args, 3, "h", 1, 65536, &h) &&
        int_arg(l, "render", args, 4, "frame", 0, INT32_MAX, &frame)) {
        utf8_arg(args, 5, layer, sizeof layer);
        const int light = strcmp(layer, "light") == 0;
        if (!light && strcmp(layer, "final") != 0) {
            snprintf(l->error, sizeof l->error, "IsoluxLighting.render: layer \"%s\" is unknown (final, light)", layer);
        } else if (w * h > (1 << 26)) {
            snprintf(l->error, sizeof l->error,
                     "IsoluxLighting.render: a view of %lldx%lld pixels is over the 64 megapixels a PoolByteArray of "
                     "RGBA holds here", (long long)w, (long long)h);
        } else {
            const isolux_rect view = {(int32_t)x, (int32_t)y, (int32_t)w, (int32_t)h};
            const size_t size = (size_t)w * (size_t)h * 4;
            api->godot_pool_byte_array_resize(&bytes, (godot_int)size);
            godot_pool_byte_array_write_access* wa = api->godot_pool_byte_array_write(&bytes);
            uint8_t* p = api->godot_pool_byte_array_write_access_ptr(wa);
            const isolux_status st = isolux_world_render(l->world, view, (int)frame, light ? NULL : p, light ? 0 : size,
                                                         light ? p : NULL, light ? size : 0);
            api->godot_pool_byte_array_write_access_destroy(wa);
            if (!library_ok(l, st)) api->godot_pool_byte_array_resize(&bytes, 0);
        }
    }
    godot_variant v;
    api->godot_variant_new_pool_byte_array(&v, &bytes);
    api->godot_pool_byte_array_destroy(&bytes);
    return v;
}

METHOD(last_error) {
    UNUSED, (void)argc, (void)args;
    return string_result(((Lighting*)data)->error);
}

METHOD(api_version) {
    UNUSED, (void)data, (void)argc, (void)args;
    return int_result(isolux_api_version());
}

/* --- GDNative entry points: the only symbols the library exports (GDN_EXPORT
 * is empty on Linux; everything else is hidden). */
#define ENTRY __attribute__((visibility("default")))

ENTRY void godot_gdnative_init(godot_gdnative_init_options* options) {
    api = options->api_struct;
    for (unsigned i = 0; i < api->num_extensions; ++i)
        if (api->extensions[i]->type == GDNATIVE_EXT_NATIVESCRIPT)
            nativescript = (const godot_gdnative_ext_nativescript_api_struct*)api->extensions[i];
}

ENTRY void godot_gdnative_terminate(godot_gdnative_terminate_options* options) {
    (void)options;
    api = NULL;
    nativescript = NULL;
}

ENTRY void godot_nativescript_init(void* handle) {
    godot_instance_create_func create = {lighting_new, NULL, NULL};
    godot_instance_destroy_func destroy = {lighting_delete, NULL, NULL};
    nativescript->godot_nativescript_register_class(handle, "IsoluxLighting", "Reference", create, destroy);
    static const struct {
        const char* name;
        godot_variant (*fn)(godot_object*, void*, void*, int, godot_variant**);
    } methods[] = {
        {"open_scene", open_scene},   {"open_tmx", open_tmx},         {"load_preset", load_preset},
        {"set_param", set_param},     {"add_light", add_light},       {"move_light", move_light},
        {"remove_light", remove_light}, {"default_view", default_view}, {"render", render},
        {"last_error", last_error},   {"api_version", api_version},
    };
    godot_method_attributes attributes = {GODOT_METHOD_RPC_MODE_DISABLED};
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; ++i) {
        godot_instance_method m = {methods[i].fn, NULL, NULL};
        nativescript->godot_nativescript_register_method(handle, "IsoluxLighting", methods[i].name, attributes, m);
    }
}
