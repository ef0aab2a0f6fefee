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
 * false, -1 or an empty array on failure, and last_error() says why. */
#include <gdnative_api_struct.gen.h>
#include <isolux.h>

#include <string.h>

static const godot_gdnative_core_api_struct* api = NULL;
static const godot_gdnative_ext_nativescript_api_struct* nativescript = NULL;

typedef struct Lighting {
    isolux_world* world;
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

static int enough(int argc, int wanted) { return argc >= wanted; }

/* --- The instance */

static void* lighting_new(godot_object* owner, void* method_data) {
    (void)owner, (void)method_data;
    Lighting* l = api->godot_alloc(sizeof(Lighting));
    l->world = NULL;
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
    if ((tmx ? isolux_world_open_tmx(path, &w) : isolux_world_open_scene(path, &w)) != ISOLUX_OK)
        return bool_result(0);
    isolux_world_free(l->world);
    l->world = w;
    return bool_result(1);
}

METHOD(open_scene) { UNUSED; return enough(argc, 1) ? open_with(data, 0, args) : bool_result(0); }
METHOD(open_tmx) { UNUSED; return enough(argc, 1) ? open_with(data, 1, args) : bool_result(0); }

METHOD(load_preset) {
    UNUSED;
    Lighting* l = data;
    if (!l->world || !enough(argc, 1)) return bool_result(0);
    char name[4096];
    utf8_arg(args, 0, name, sizeof name);
    return bool_result(isolux_world_load_preset(l->world, name) == ISOLUX_OK);
}

METHOD(set_param) {
    UNUSED;
    Lighting* l = data;
    if (!l->world || !enough(argc, 2)) return bool_result(0);
    char name[256], value[256];
    utf8_arg(args, 0, name, sizeof name);
    utf8_arg(args, 1, value, sizeof value);
    return bool_result(isolux_world_set_param(l->world, name, value) == ISOLUX_OK);
}

/* add_light(x, y, rgb = 0xffffff, height = -1 (the preset's)) -> id or -1 */
METHOD(add_light) {
    UNUSED;
    Lighting* l = data;
    if (!l->world || !enough(argc, 2)) return int_result(-1);
    isolux_light light;
    isolux_light_init(&light, api->godot_variant_as_real(args[0]), api->godot_variant_as_real(args[1]));
    if (argc > 2) {
        const int64_t rgb = api->godot_variant_as_int(args[2]);
        light.r = (uint8_t)(rgb >> 16), light.g = (uint8_t)(rgb >> 8), light.b = (uint8_t)rgb;
    }
    if (argc > 3) light.height = api->godot_variant_as_real(args[3]);
    int id = -1;
    return int_result(isolux_world_add_light(l->world, &light, &id) == ISOLUX_OK ? id : -1);
}

METHOD(move_light) {
    UNUSED;
    Lighting* l = data;
    if (!l->world || !enough(argc, 3)) return bool_result(0);
    return bool_result(isolux_world_move_light(l->world, (int)api->godot_variant_as_int(args[0]),
                                               api->godot_variant_as_real(args[1]),
                                               api->godot_variant_as_real(args[2])) == ISOLUX_OK);
}

METHOD(remove_light) {
    UNUSED;
    Lighting* l = data;
    if (!l->world || !enough(argc, 1)) return bool_result(0);
    return bool_result(isolux_world_remove_light(l->world, (int)api->godot_variant_as_int(args[0])) == ISOLUX_OK);
}

/* default_view() -> Rect2: what isolux-cli renders with no --view. */
METHOD(default_view) {
    UNUSED, (void)argc, (void)args;
    Lighting* l = data;
    isolux_rect r = {0, 0, 0, 0};
    if (l->world) isolux_world_default_view(l->world, &r);
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
    if (l->world && enough(argc, 6)) {
        const isolux_rect view = {(int32_t)api->godot_variant_as_int(args[0]), (int32_t)api->godot_variant_as_int(args[1]),
                                  (int32_t)api->godot_variant_as_int(args[2]), (int32_t)api->godot_variant_as_int(args[3])};
        char layer[16];
        utf8_arg(args, 5, layer, sizeof layer);
        const int light = strcmp(layer, "light") == 0;
        if (view.width > 0 && view.height > 0 && (int64_t)view.width * view.height <= (1 << 26)) {
            const size_t size = (size_t)view.width * (size_t)view.height * 4;
            api->godot_pool_byte_array_resize(&bytes, (godot_int)size);
            godot_pool_byte_array_write_access* w = api->godot_pool_byte_array_write(&bytes);
            uint8_t* p = api->godot_pool_byte_array_write_access_ptr(w);
            const isolux_status st = isolux_world_render(l->world, view, (int)api->godot_variant_as_int(args[4]),
                                                         light ? NULL : p, light ? 0 : size, light ? p : NULL,
                                                         light ? size : 0);
            api->godot_pool_byte_array_write_access_destroy(w);
            if (st != ISOLUX_OK) api->godot_pool_byte_array_resize(&bytes, 0);
        }
    }
    godot_variant v;
    api->godot_variant_new_pool_byte_array(&v, &bytes);
    api->godot_pool_byte_array_destroy(&bytes);
    return v;
}

METHOD(last_error) {
    UNUSED, (void)data, (void)argc, (void)args;
    return string_result(isolux_last_error());
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
