/* The C API's contract, from C: statuses, messages that name the field,
 * stable light ids, edits refused by name with the world unchanged, buffers
 * checked, NULL handled, and a moved light changing only what it should;
 * and against a hostile caller: a second thread on a busy world, work over
 * the budget, a cancel from another thread, a light texture asked for again
 * after frames without it, hidden lights kept hidden, unknown parameters. */
#include <isolux.h>

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static int failures = 0, passes = 0;
#define CHECK(cond, ...)                                         \
    do {                                                         \
        if (cond) {                                              \
            ++passes;                                            \
        } else {                                                 \
            ++failures;                                          \
            printf("FAIL line %d: %s: ", __LINE__, #cond);       \
            printf(__VA_ARGS__);                                 \
            printf(" (last error: %s)\n", isolux_last_error());  \
        }                                                        \
    } while (0)

/* A render on another thread, and what it returned. */
struct render_job {
    isolux_world* world;
    isolux_rect view;
    isolux_status status;
};
static void* render_thread(void* arg) {
    struct render_job* job = arg;
    job->status = isolux_world_render(job->world, job->view, 0, NULL, 0, NULL, 0);
    return NULL;
}

static void sleep_ms(int ms) {
    struct timespec t = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&t, NULL);
}

static size_t differing(const uint8_t* a, const uint8_t* b, size_t bytes) {
    size_t n = 0;
    for (size_t i = 0; i < bytes; i += 4) n += memcmp(a + i, b + i, 4) != 0;
    return n;
}

int main(int argc, char** argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: api_test TILESET_MANIFEST\n");
        return 2;
    }
    const char* tileset = argv[1];
    CHECK(isolux_api_version() == ISOLUX_API_VERSION, "version %d", isolux_api_version());

    /* Opening: bad inputs are refused by name; *out untouched. */
    isolux_world* w = NULL;
    CHECK(isolux_world_open_scene("/nonexistent/dir/level.json", &w) == ISOLUX_ERROR_INPUT && w == NULL, "missing");
    CHECK(strstr(isolux_last_error(), "level.json") != NULL, "names the file");
    {
        /* A scene naming a Tiled map and an endless size contradicts itself:
         * refused, as isolux-cli refuses it, naming the field. */
        char path[64];
        snprintf(path, sizeof path, "/tmp/isolux_api_test_%ld.json", (long)getpid());
        FILE* f = fopen(path, "w");
        CHECK(f != NULL, "temp scene");
        if (f) {
            fputs("{\"width\": \"endless\", \"height\": \"endless\", \"map\": \"level.tmx\"}", f);
            fclose(f);
            CHECK(isolux_world_open_scene(path, &w) == ISOLUX_ERROR_INPUT && w == NULL, "map and endless");
            CHECK(strstr(isolux_last_error(), "map") != NULL && strstr(isolux_last_error(), "endless") != NULL,
                  "names both");
            remove(path);
        }
    }
    CHECK(isolux_world_open_seeded("s", 0, 4, NULL, tileset, &w) == ISOLUX_ERROR_INPUT, "width 0");
    CHECK(strstr(isolux_last_error(), "width") != NULL, "names the field");
    CHECK(isolux_world_open_seeded("s", 4, 4, "hexagonal", tileset, &w) == ISOLUX_ERROR_INPUT, "layout");
    CHECK(isolux_world_open_seeded(NULL, 4, 4, NULL, tileset, &w) == ISOLUX_ERROR_ARGUMENT, "NULL seed");
    CHECK(isolux_world_open_seeded("isolux", 8, 8, NULL, tileset, &w) == ISOLUX_OK && w, "open");
    if (!w) return 1;

    /* Parameters by the table's names. */
    char buf[64];
    CHECK(isolux_world_set_param(w, "ray_skip", "2") == ISOLUX_OK, "ray_skip");
    CHECK(isolux_world_get_param(w, "ray_skip", buf, sizeof buf) == ISOLUX_OK && strcmp(buf, "2") == 0, "got %s", buf);
    CHECK(isolux_world_set_param(w, "ray_skip", "-3") == ISOLUX_ERROR_INPUT, "out of range");
    CHECK(strstr(isolux_last_error(), "ray_skip") != NULL, "names it");
    CHECK(isolux_world_get_param(w, "ray_skip", buf, sizeof buf) == ISOLUX_OK && strcmp(buf, "2") == 0,
          "unchanged after a refusal: %s", buf);
    CHECK(isolux_world_set_param(w, "no_such_param", "1") == ISOLUX_ERROR_INPUT, "unknown name");
    CHECK(strstr(isolux_last_error(), "no_such_param") != NULL, "names it");
    CHECK(isolux_world_get_param(w, "ray_skip", buf, 1) == ISOLUX_ERROR_ARGUMENT, "small buffer");
    CHECK(isolux_world_load_preset(w, "no-such-preset") == ISOLUX_ERROR_INPUT, "unknown preset");
    CHECK(isolux_world_load_preset(w, "paper") == ISOLUX_OK, "paper");
    CHECK(isolux_world_get_param(w, "ray_skip", buf, sizeof buf) == ISOLUX_OK && strcmp(buf, "2") != 0,
          "the preset replaced it: %s", buf);

    /* Lights: stable ids across removal. */
    isolux_light l;
    int a = -1, b = -1, c = -1, ids[8], count = 0;
    isolux_light_init(&l, 500, 300);
    CHECK(isolux_world_add_light(w, &l, &a) == ISOLUX_OK, "add a");
    l.x = 700;
    l.r = 200;
    CHECK(isolux_world_add_light(w, &l, &b) == ISOLUX_OK, "add b");
    CHECK(isolux_world_add_light(w, &l, &c) == ISOLUX_OK && a != b && b != c, "ids %d %d %d", a, b, c);
    CHECK(isolux_world_remove_light(w, b) == ISOLUX_OK, "remove b");
    CHECK(isolux_world_lights(w, ids, 8, &count) == ISOLUX_OK && count == 2 && ids[0] == a && ids[1] == c, "ids");
    CHECK(isolux_world_move_light(w, b, 1, 1) == ISOLUX_ERROR_ARGUMENT, "removed id");
    CHECK(isolux_world_get_light(w, c, &l) == ISOLUX_OK && l.x == 700 && l.r == 200, "c kept: %g", l.x);
    l.intensity = -1;
    CHECK(isolux_world_set_light(w, c, &l) == ISOLUX_ERROR_INPUT && strstr(isolux_last_error(), "intensity"),
          "negative intensity");
    CHECK(isolux_world_move_light(w, c, 1e300, 0) == ISOLUX_ERROR_INPUT, "far away");
    CHECK(isolux_world_remove_light(w, c) == ISOLUX_OK, "remove c");

    /* Rendering: buffers checked; a moved light changes the picture and
     * moving it back gives the same bytes again. */
    isolux_rect view;
    CHECK(isolux_world_default_view(w, &view) == ISOLUX_OK && view.width > 0 && view.height > 0, "view");
    const size_t bytes = (size_t)view.width * (size_t)view.height * 4;
    uint8_t* first = malloc(bytes);
    uint8_t* moved = malloc(bytes);
    uint8_t* back = malloc(bytes);
    uint8_t* light = malloc(bytes);
    CHECK(isolux_world_render(w, view, 0, first, bytes - 4, NULL, 0) == ISOLUX_ERROR_ARGUMENT, "short buffer");
    CHECK(strstr(isolux_last_error(), "rgba") != NULL, "names the buffer");
    isolux_rect empty = {0, 0, 0, 10};
    CHECK(isolux_world_render(w, empty, 0, NULL, 0, NULL, 0) == ISOLUX_ERROR_ARGUMENT, "empty view");
    isolux_rect past_int = {2147483600, 0, 100, 10}; /* x + width beyond an int32 */
    CHECK(isolux_world_render(w, past_int, 0, NULL, 0, NULL, 0) == ISOLUX_ERROR_ARGUMENT &&
              strstr(isolux_last_error(), "within 1e9") != NULL,
          "a view far beyond any map");
    CHECK(isolux_world_render(w, view, 0, first, bytes, light, bytes) == ISOLUX_OK, "render");
    CHECK(isolux_world_move_light(w, a, 520, 330) == ISOLUX_OK, "move");
    CHECK(isolux_world_render(w, view, 1, moved, bytes, NULL, 0) == ISOLUX_OK, "render moved");
    CHECK(differing(first, moved, bytes) > 100, "moving a light changes the picture");
    CHECK(isolux_world_move_light(w, a, 500, 300) == ISOLUX_OK, "move back");
    CHECK(isolux_world_render(w, view, 2, back, bytes, NULL, 0) == ISOLUX_OK, "render back");
    CHECK(differing(first, back, bytes) == 0, "back where it was: %zu pixels differ", differing(first, back, bytes));

    /* Edits: refused by name with the world unchanged; applied; undone. */
    int cols = 0, rows = 0;
    CHECK(isolux_world_tiles(w, &cols, &rows) == ISOLUX_OK && cols == 8 && rows == 8, "%dx%d", cols, rows);
    const char* bad[] = {"no-such-sprite"};
    CHECK(isolux_world_set_tile(w, 3, 3, NULL, bad, 1) == ISOLUX_ERROR_INPUT, "unknown overlay");
    CHECK(strstr(isolux_last_error(), "no-such-sprite") != NULL, "names it");
    const char* null_name[] = {"bush", NULL};
    CHECK(isolux_world_set_tile(w, 3, 3, NULL, null_name, 2) == ISOLUX_ERROR_ARGUMENT &&
              strstr(isolux_last_error(), "overlays[1]") != NULL,
          "a NULL overlay name is the caller's error, named");
    CHECK(isolux_world_set_tile(w, 8, 0, NULL, NULL, 0) == ISOLUX_ERROR_INPUT, "outside");
    CHECK(strstr(isolux_last_error(), "outside") != NULL, "says so");
    CHECK(isolux_world_render(w, view, 3, moved, bytes, NULL, 0) == ISOLUX_OK && differing(first, moved, bytes) == 0,
          "refused edits change nothing");
    int cleared = 0;
    for (int row = 0; row < rows; ++row)
        for (int col = 0; col < cols; ++col)
            cleared += isolux_world_set_tile(w, col, row, NULL, NULL, 0) == ISOLUX_OK;
    CHECK(cleared == cols * rows, "every tile's overlays removed: %d", cleared);
    CHECK(isolux_world_render(w, view, 4, moved, bytes, NULL, 0) == ISOLUX_OK && differing(first, moved, bytes) > 100,
          "removing every overlay changes the picture");
    CHECK(isolux_world_clear_edits(w) == ISOLUX_OK, "clear");
    CHECK(isolux_world_render(w, view, 5, back, bytes, NULL, 0) == ISOLUX_OK && differing(first, back, bytes) == 0,
          "cleared edits give the seed's picture again: %zu", differing(first, back, bytes));

    /* A parameter get_param does not know is refused as set_param refuses it. */
    CHECK(isolux_world_get_param(w, "no_such_param", buf, sizeof buf) == ISOLUX_ERROR_INPUT &&
              strstr(isolux_last_error(), "no_such_param") != NULL,
          "unknown name read");

    /* A light texture asked for again after frames without it is the
     * current one, not the last one made: a fresh world's bytes. */
    {
        isolux_world* x = NULL;
        isolux_world* fresh = NULL;
        CHECK(isolux_world_open_seeded("isolux", 8, 8, NULL, tileset, &x) == ISOLUX_OK, "open x");
        CHECK(isolux_world_open_seeded("isolux", 8, 8, NULL, tileset, &fresh) == ISOLUX_OK, "open fresh");
        int id = -1, fid = -1;
        isolux_light_init(&l, 500, 300);
        CHECK(isolux_world_add_light(x, &l, &id) == ISOLUX_OK, "add");
        CHECK(isolux_world_render(x, view, 0, NULL, 0, light, bytes) == ISOLUX_OK, "frame 0 with its light");
        CHECK(isolux_world_move_light(x, id, 620, 380) == ISOLUX_OK, "move");
        CHECK(isolux_world_render(x, view, 1, moved, bytes, NULL, 0) == ISOLUX_OK, "frame 1 without");
        CHECK(isolux_world_render(x, view, 2, moved, bytes, light, bytes) == ISOLUX_OK, "frame 2 with it again");
        l.x = 620;
        l.y = 380;
        CHECK(isolux_world_add_light(fresh, &l, &fid) == ISOLUX_OK, "add to fresh");
        CHECK(isolux_world_render(fresh, view, 0, NULL, 0, back, bytes) == ISOLUX_OK, "fresh");
        CHECK(differing(light, back, bytes) == 0, "the light texture after a frame without it: %zu pixels stale",
              differing(light, back, bytes));

        /* A hidden light stays hidden through get_light and set_light. */
        CHECK(isolux_world_render(fresh, view, 1, back, bytes, NULL, 0) == ISOLUX_OK, "lit");
        CHECK(isolux_world_set_light_hidden(fresh, fid, 1) == ISOLUX_OK, "hide");
        CHECK(isolux_world_get_light(fresh, fid, &l) == ISOLUX_OK, "get");
        l.r = 10;
        CHECK(isolux_world_set_light(fresh, fid, &l) == ISOLUX_OK, "set");
        CHECK(isolux_world_render(fresh, view, 2, moved, bytes, NULL, 0) == ISOLUX_OK, "hidden");
        CHECK(isolux_world_remove_light(fresh, fid) == ISOLUX_OK, "remove");
        CHECK(isolux_world_render(fresh, view, 3, first, bytes, NULL, 0) == ISOLUX_OK, "unlit");
        CHECK(differing(moved, first, bytes) == 0 && differing(back, first, bytes) > 100,
              "set_light kept the light hidden: %zu pixels differ from no light", differing(moved, first, bytes));
        CHECK(isolux_world_set_light_hidden(fresh, fid, 0) == ISOLUX_ERROR_ARGUMENT, "a removed id");

        /* Ids are never reused. */
        int again = -1;
        CHECK(isolux_world_add_light(fresh, &l, &again) == ISOLUX_OK && again != fid, "new id %d after %d", again, fid);
        isolux_world_free(x);
        isolux_world_free(fresh);
    }

    /* Work over the budget: refused with its estimate, before any of it; a
     * second thread's call on the busy world refused; a cancel stops it. */
    {
        isolux_world* h = NULL;
        CHECK(isolux_world_open_seeded("isolux", 8, 8, NULL, tileset, &h) == ISOLUX_OK, "open h");
        CHECK(isolux_world_set_param(h, "rays", "every_pixel") == ISOLUX_OK, "every pixel");
        isolux_light_init(&l, 500, 300);
        l.area_a = l.area_b = 4096;
        int id = -1;
        CHECK(isolux_world_add_light(h, &l, &id) == ISOLUX_OK, "a huge light");
        CHECK(isolux_world_render(h, view, 0, NULL, 0, NULL, 0) == ISOLUX_ERROR_TOO_MUCH_WORK &&
                  strstr(isolux_last_error(), "ray steps") != NULL &&
                  strstr(isolux_last_error(), "isolux_world_allow_huge") != NULL,
              "refused with its estimate");
        /* A view whose memory is over the budget (8000x8000 pixels: about
         * 1.2 GiB): refused with its estimate before any buffer is touched. */
        isolux_world* m = NULL;
        CHECK(isolux_world_open_seeded("isolux", 8, 8, NULL, tileset, &m) == ISOLUX_OK, "open m");
        isolux_rect wide = {0, 0, 8000, 8000};
        CHECK(isolux_world_render(m, wide, 0, NULL, 0, NULL, 0) == ISOLUX_ERROR_TOO_MUCH_WORK &&
                  strstr(isolux_last_error(), "GiB") != NULL,
              "a view over the memory budget");
        isolux_world_free(m);
        CHECK(isolux_world_allow_huge(h, 1) == ISOLUX_OK, "allowed");
        struct render_job job = {h, view, ISOLUX_OK};
        pthread_t thread;
        CHECK(pthread_create(&thread, NULL, render_thread, &job) == 0, "thread");
        sleep_ms(300);
        CHECK(isolux_world_get_param(h, "rays", buf, sizeof buf) == ISOLUX_ERROR_ARGUMENT &&
                  strstr(isolux_last_error(), "in use") != NULL,
              "a second thread's call on a busy world is refused");
        CHECK(isolux_world_move_light(h, id, 1, 1) == ISOLUX_ERROR_ARGUMENT, "and changes nothing");
        const time_t asked = time(NULL);
        CHECK(isolux_world_cancel(h) == ISOLUX_OK, "cancel");
        pthread_join(thread, NULL);
        CHECK(job.status == ISOLUX_CANCELLED, "the render was cancelled: status %d", (int)job.status);
        CHECK(time(NULL) - asked <= 5, "within seconds: %ld s", (long)(time(NULL) - asked));
        CHECK(isolux_world_get_light(h, id, &l) == ISOLUX_OK && l.x == 500 && l.area_a == 4096,
              "the world as it was before the cancelled call");
        /* The world goes on: with the light back to a small area, a frame is the one a fresh world draws. */
        l.area_a = l.area_b = 64;
        CHECK(isolux_world_set_light(h, id, &l) == ISOLUX_OK, "smaller");
        CHECK(isolux_world_set_param(h, "rays", "border") == ISOLUX_OK, "border rays");
        CHECK(isolux_world_render(h, view, 1, moved, bytes, NULL, 0) == ISOLUX_OK, "a frame after the cancel");
        isolux_world* fresh = NULL;
        CHECK(isolux_world_open_seeded("isolux", 8, 8, NULL, tileset, &fresh) == ISOLUX_OK, "fresh");
        CHECK(isolux_world_add_light(fresh, &l, NULL) == ISOLUX_OK, "same light");
        CHECK(isolux_world_render(fresh, view, 0, back, bytes, NULL, 0) == ISOLUX_OK, "fresh frame");
        CHECK(differing(moved, back, bytes) == 0, "after a cancel, a fresh world's bytes: %zu differ",
              differing(moved, back, bytes));
        isolux_world_free(fresh);
        isolux_world_free(h);
    }

    /* Many edits: each costs its tile, not the edits before it (8,000 on a
     * 128x128 map within the bad-input budget, 10 s). */
    {
        isolux_world* m = NULL;
        CHECK(isolux_world_open_seeded("many edits", 128, 128, NULL, tileset, &m) == ISOLUX_OK, "open m");
        const char* bush[] = {"bush"};
        const time_t start = time(NULL);
        int ok = 0;
        for (int i = 0; i < 8000; ++i) ok += isolux_world_set_tile(m, i % 128, i / 128, NULL, bush, 1) == ISOLUX_OK;
        const long seconds = (long)(time(NULL) - start);
        CHECK(ok == 8000, "%d of 8000 edits", ok);
        CHECK(seconds <= 10, "8000 edits took %ld s", seconds);
        isolux_world_free(m);
    }

    /* NULL handles are refused, not crashed on. */
    CHECK(isolux_world_render(NULL, view, 0, first, bytes, NULL, 0) == ISOLUX_ERROR_ARGUMENT, "NULL world");
    CHECK(isolux_world_set_param(w, NULL, "1") == ISOLUX_ERROR_ARGUMENT, "NULL name");
    isolux_world_free(NULL);

    free(first);
    free(moved);
    free(back);
    free(light);
    isolux_world_free(w);
    printf("capi_api: %d passed, %d failed\n", passes, failures);
    return failures ? 1 : 0;
}
