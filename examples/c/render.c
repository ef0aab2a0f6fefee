/* Renders a scene JSON or a Tiled map through libisolux's C API and writes the
 * final picture (and, when asked, the light texture) as PAM images: what
 * `isolux-cli render --scene F` (or --map F) and `--layer light` write, byte for
 * byte. Build: cc render.c $(pkg-config --cflags --libs isolux)
 *
 * Usage: render SCENE.json|MAP.tmx OUT.pam [LIGHT.pam] */
#include <isolux.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int write_pam(const char* path, const uint8_t* rgba, int w, int h) {
    FILE* f = fopen(path, "wb");
    if (!f) return 0;
    fprintf(f, "P7\nWIDTH %d\nHEIGHT %d\nDEPTH 4\nMAXVAL 255\nTUPLTYPE RGB_ALPHA\nENDHDR\n", w, h);
    const size_t n = (size_t)w * (size_t)h * 4;
    const int ok = fwrite(rgba, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

static int fail(const char* what) {
    fprintf(stderr, "render: %s: %s\n", what, isolux_last_error());
    return 2;
}

int main(int argc, char** argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: render SCENE.json|MAP.tmx OUT.pam [LIGHT.pam]\n");
        return 2;
    }
    if (isolux_api_version() != ISOLUX_API_VERSION) {
        fprintf(stderr, "render: libisolux speaks API %d, this program %d\n", isolux_api_version(), ISOLUX_API_VERSION);
        return 2;
    }
    const char* in = argv[1];
    const size_t len = strlen(in);
    isolux_world* world = NULL;
    const int tmx = len > 4 && strcmp(in + len - 4, ".tmx") == 0;
    if ((tmx ? isolux_world_open_tmx(in, &world) : isolux_world_open_scene(in, &world)) != ISOLUX_OK)
        return fail("open");
    isolux_rect view;
    isolux_world_default_view(world, &view);
    const size_t bytes = (size_t)view.width * (size_t)view.height * 4;
    uint8_t* rgba = malloc(bytes);
    uint8_t* light = argc > 3 ? malloc(bytes) : NULL;
    int code = 0;
    if (!rgba || (argc > 3 && !light)) {
        fprintf(stderr, "render: out of memory\n");
        code = 2;
    } else if (isolux_world_render(world, view, 0, rgba, bytes, light, light ? bytes : 0) != ISOLUX_OK) {
        code = fail("render");
    } else if (!write_pam(argv[2], rgba, view.width, view.height) ||
               (light && !write_pam(argv[3], light, view.width, view.height))) {
        fprintf(stderr, "render: could not write %s\n", argv[2]);
        code = 2;
    } else {
        printf("rendered %s: %dx%d at (%d, %d)\n", in, view.width, view.height, view.x, view.y);
    }
    free(rgba);
    free(light);
    isolux_world_free(world);
    return code;
}
