/* walk: a character carrying a light walks across a seeded map lit by two
 * torches (the paper's Figure 8), through libisolux's C API only.
 *
 *   walk [--level FILE] [--out DIR] [--frames N]
 *
 * With a display (and built with GLFW): a window; WASD or the arrows walk,
 * Esc quits. With --out, or with no display: N frames (default 48) of a walk
 * from the map's west to its east corner are written to DIR (default
 * walk-frames) as frame-NNN.pam, with frames.txt saying, per frame, the view,
 * the character's light and the rectangle its figure covers: what a test
 * needs to render the same frame with isolux-cli. */
#include <isolux.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#ifdef WALK_WINDOW
#include <GLFW/glfw3.h>
#endif

#ifndef WALK_LEVEL
#define WALK_LEVEL "level.json"
#endif

enum { VIEW_W = 640, VIEW_H = 360, FIGURE_W = 10, FIGURE_H = 26 };

typedef struct Game {
    isolux_world* world;
    int carried; /* the character's light id */
    double x, y; /* the character's feet, world pixels */
    isolux_rect view;
    uint8_t* rgba;
    uint8_t* light;
    size_t bytes;
} Game;

static int fail(const char* what) {
    fprintf(stderr, "walk: %s: %s\n", what, isolux_last_error());
    return 2;
}

/* The camera follows the character. */
static void follow(Game* g) {
    g->view.x = (int32_t)g->x - VIEW_W / 2;
    g->view.y = (int32_t)g->y - VIEW_H / 2;
}

/* The figure's rectangle in view pixels: it stands on its feet. */
static isolux_rect figure(const Game* g) {
    isolux_rect r = {(int32_t)g->x - FIGURE_W / 2 - g->view.x, (int32_t)g->y - FIGURE_H - g->view.y, FIGURE_W, FIGURE_H};
    return r;
}

/* A plain figure (a cloak and a head), lit by the light texture at its feet:
 * the game draws its own characters over isolux's frame. */
static void draw_figure(Game* g) {
    const isolux_rect r = figure(g);
    const int fx = (int)g->x - g->view.x, fy = (int)g->y - 1 - g->view.y;
    const uint8_t* at = g->light + ((size_t)fy * VIEW_W + (size_t)fx) * 4;
    const int lit = at[0] > at[1] ? (at[0] > at[2] ? at[0] : at[2]) : (at[1] > at[2] ? at[1] : at[2]);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            const int dx = 2 * x - (r.width - 1), head = y < 8;
            if (head && dx * dx + (2 * y - 7) * (2 * y - 7) > 49) continue;
            uint8_t* p = g->rgba + ((size_t)(r.y + y) * VIEW_W + (size_t)(r.x + x)) * 4;
            const int base[3] = {head ? 230 : 150, head ? 190 : 40, head ? 160 : 40};
            for (int c = 0; c < 3; ++c) p[c] = (uint8_t)(base[c] * (60 + lit) / 315);
        }
}

static int step(Game* g, int frame) {
    if (isolux_world_move_light(g->world, g->carried, g->x, g->y) != ISOLUX_OK) return fail("move");
    follow(g);
    if (isolux_world_render(g->world, g->view, frame, g->rgba, g->bytes, g->light, g->bytes) != ISOLUX_OK)
        return fail("render");
    draw_figure(g);
    return 0;
}

static int write_pam(const char* path, const uint8_t* rgba) {
    FILE* f = fopen(path, "wb");
    if (!f) return 0;
    fprintf(f, "P7\nWIDTH %d\nHEIGHT %d\nDEPTH 4\nMAXVAL 255\nTUPLTYPE RGB_ALPHA\nENDHDR\n", VIEW_W, VIEW_H);
    const int ok = fwrite(rgba, 1, (size_t)VIEW_W * VIEW_H * 4, f) == (size_t)VIEW_W * VIEW_H * 4;
    return fclose(f) == 0 && ok;
}

/* Headless: a walk from the map's west corner to its east one. */
static int walk_headless(Game* g, const char* dir, int frames) {
    isolux_rect b;
    isolux_world_bounds(g->world, &b);
    mkdir(dir, 0777);
    char path[4096];
    snprintf(path, sizeof path, "%s/frames.txt", dir);
    FILE* log = fopen(path, "w");
    if (!log) {
        fprintf(stderr, "walk: could not write %s\n", path);
        return 2;
    }
    fprintf(log, "# frame view_x view_y view_w view_h light_x light_y figure_x figure_y figure_w figure_h\n");
    const int x0 = b.x + b.width / 8, x1 = b.x + b.width - b.width / 8, y = b.y + b.height / 2;
    for (int f = 0; f < frames; ++f) {
        g->x = x0 + (double)((x1 - x0) * f / (frames > 1 ? frames - 1 : 1));
        g->y = y + (double)((f % 8) < 4 ? f % 8 : 8 - f % 8) * 4; /* a little sway */
        const int code = step(g, f);
        if (code) return code;
        snprintf(path, sizeof path, "%s/frame-%03d.pam", dir, f);
        if (!write_pam(path, g->rgba)) {
            fprintf(stderr, "walk: could not write %s\n", path);
            return 2;
        }
        const isolux_rect r = figure(g);
        fprintf(log, "%d %d %d %d %d %.0f %.0f %d %d %d %d\n", f, g->view.x, g->view.y, VIEW_W, VIEW_H, g->x, g->y,
                r.x, r.y, r.width, r.height);
    }
    fclose(log);
    printf("walk: wrote %d frames to %s\n", frames, dir);
    return 0;
}

#ifdef WALK_WINDOW
static int walk_window(Game* g, GLFWwindow* win) {
    isolux_rect b;
    isolux_world_bounds(g->world, &b);
    g->x = b.x + b.width / 2;
    g->y = b.y + b.height / 2;
    for (int f = 0; !glfwWindowShouldClose(win); ++f) {
        glfwPollEvents();
        if (glfwGetKey(win, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
        const double speed = 3;
        if (glfwGetKey(win, GLFW_KEY_A) == GLFW_PRESS || glfwGetKey(win, GLFW_KEY_LEFT) == GLFW_PRESS) g->x -= speed;
        if (glfwGetKey(win, GLFW_KEY_D) == GLFW_PRESS || glfwGetKey(win, GLFW_KEY_RIGHT) == GLFW_PRESS) g->x += speed;
        if (glfwGetKey(win, GLFW_KEY_W) == GLFW_PRESS || glfwGetKey(win, GLFW_KEY_UP) == GLFW_PRESS) g->y -= speed / 2;
        if (glfwGetKey(win, GLFW_KEY_S) == GLFW_PRESS || glfwGetKey(win, GLFW_KEY_DOWN) == GLFW_PRESS) g->y += speed / 2;
        const int code = step(g, f);
        if (code) return code;
        /* Rows top to bottom: draw from the top-left corner downwards. */
        glRasterPos2f(-1, 1);
        glPixelZoom(1, -1);
        glDrawPixels(VIEW_W, VIEW_H, GL_RGBA, GL_UNSIGNED_BYTE, g->rgba);
        glfwSwapBuffers(win);
    }
    return 0;
}
#endif

int main(int argc, char** argv) {
    const char* level = WALK_LEVEL;
    const char* out = NULL;
    int frames = 48;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--level") == 0 && i + 1 < argc) level = argv[++i];
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out = argv[++i];
        else if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc) frames = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: walk [--level FILE] [--out DIR] [--frames N]\n");
            return 2;
        }
    }
    if (frames < 1 || frames > 10000) {
        fprintf(stderr, "walk: --frames must be in [1, 10000]\n");
        return 2;
    }
    Game g = {0};
    g.bytes = (size_t)VIEW_W * VIEW_H * 4;
    g.view.width = VIEW_W;
    g.view.height = VIEW_H;
    if (isolux_world_open_scene(level, &g.world) != ISOLUX_OK) return fail("open");
    isolux_light carried;
    isolux_light_init(&carried, 0, 0);
    carried.r = 255, carried.g = 236, carried.b = 200, carried.height = 28;
    if (isolux_world_add_light(g.world, &carried, &g.carried) != ISOLUX_OK) return fail("add light");
    g.rgba = malloc(g.bytes);
    g.light = malloc(g.bytes);
    if (!g.rgba || !g.light) return fail("memory");
    int code = -1;
#ifdef WALK_WINDOW
    if (!out && glfwInit()) {
        GLFWwindow* win = glfwCreateWindow(VIEW_W, VIEW_H, "isolux walk", NULL, NULL);
        if (win) {
            glfwMakeContextCurrent(win);
            glfwSwapInterval(1);
            code = walk_window(&g, win);
            glfwDestroyWindow(win);
        }
        glfwTerminate();
    }
#endif
    if (code < 0) {
        if (!out) {
            out = "walk-frames";
            fprintf(stderr, "walk: no display: writing %d frames to %s/ instead\n", frames, out);
        }
        code = walk_headless(&g, out, frames);
    }
    free(g.rgba);
    free(g.light);
    isolux_world_free(g.world);
    return code;
}
