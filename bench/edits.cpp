#include "edits.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <string>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "ratio.hpp"

namespace isolux::bench {

namespace {

const Tileset& tileset() {
    static Tileset t = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json");
    return t;
}

// A map of side x side tiles with the app's frame options (the GPU draws
// sprites, blurs and composites) and 16 lights of the default area (257 x
// 257): either a 1280x720 view centred on the map's middle tile with the
// lights spread over it (the same neighbourhood on every map: a larger map
// extends a smaller one), or the whole map in view (as View › Fit map shows
// it) with 15 lights on a grid over the map and one beside the edited tile.
struct EditScene {
    Scene scene;
    World world;
    FrameState frame;
    Camera camera;
    int col = 0, row = 0;
    long f = 0;
};

std::unique_ptr<EditScene> make_edit_scene(int side, bool whole_map) {
    auto e = std::make_unique<EditScene>();
    e->scene.width = e->scene.height = side;
    e->world = make_world(tileset(), e->scene);
    e->col = side / 2;
    e->row = side / 2;
    int tx = 0, ty = 0;
    tile_center(e->world.map.layout, e->world.map.tile_width, e->world.map.tile_height, e->col, e->row, tx, ty);
    tx += e->world.placed.shift_x;
    ty += e->world.placed.shift_y;
    if (whole_map) {
        e->camera = Camera{};
        const Rect b = e->world.placed.bounds;
        for (int i = 0; i < 15; ++i)
            e->scene.lights.push_back(
                Light{b.x + b.w * (0.125 + 0.25 * (i % 4)) + 0.5, b.y + b.h * (0.125 + 0.25 * (i / 4)) + 0.5});
        e->scene.lights.push_back(Light{tx + 60.5, ty + 30.5});  // one beside the edited tile: it is retraced
    } else {
        e->camera = {double(tx - 640), double(ty - 360), 1280, 720};
        for (int i = 0; i < 16; ++i)
            e->scene.lights.push_back(Light{tx - 560.5 + 75.0 * i, ty - 300.5 + 40.0 * (i % 16)});
    }
    e->frame.options.cpu_sprites = false;
    e->frame.options.cpu_blur_and_composite = false;
    render_frame(e->frame, e->world, e->scene, e->camera, e->f++);
    return e;
}

EditScene& edit_scene(int side, bool whole_map = false) {
    static std::map<std::pair<int, bool>, std::unique_ptr<EditScene>> cache;
    auto& slot = cache[{side, whole_map}];
    if (!slot) slot = make_edit_scene(side, whole_map);
    return *slot;
}

// One edit and the frame after it: a tree placed on the middle tile (or,
// every other time, taken away again), as a brush stroke does it.
FrameReport edit_once(EditScene& e) {
    if (e.scene.edits.empty()) {
        TileEdit t;
        t.col = e.col;
        t.row = e.row;
        t.overlays = std::vector<std::string>{"oak"};
        e.scene.edits.push_back(t);
    } else {
        e.scene.edits.clear();
    }
    set_edits(e.world, e.scene.edits);
    return render_frame(e.frame, e.world, e.scene, e.camera, e.f++);
}

// The same scene rebuilt from nothing: the map generated and placed, and a
// first frame (obstacle map, every light traced).
void full_rebuild(const EditScene& e) {
    World w = make_world(tileset(), e.scene);
    FrameState fs;
    fs.options = e.frame.options;
    benchmark::DoNotOptimize(render_frame(fs, w, e.scene, e.camera, 0));
}

}  // namespace

void register_edits() {
    for (int side : {16, 64, 256, -64})  // -64: the whole 64 x 64 map in view
        benchmark::RegisterBenchmark(side > 0 ? ("edit/tree/map:" + std::to_string(side)).c_str() : "edit/tree/whole_map:64",
                                     [side](benchmark::State& st) {
            EditScene& e = side > 0 ? edit_scene(side) : edit_scene(-side, true);
            double traced = 0, n = 0;
            std::array<double, stage_count> ms{};
            for (auto _ : st) {
                const FrameReport r = edit_once(e);
                traced += r.lights_traced;
                for (int k = 0; k < stage_count; ++k) ms[std::size_t(k)] += r.ms[std::size_t(k)];
                ++n;
            }
            st.counters["lights_retraced"] = traced / n;
            for (int k = 0; k < stage_count; ++k)
                if (ms[std::size_t(k)] > 0) st.counters[std::string(to_string(Stage(k))) + "_ms"] = ms[std::size_t(k)] / n;
        })->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("edit/full_rebuild/whole_map:64", [](benchmark::State& st) {
        const EditScene& e = edit_scene(64, true);
        for (auto _ : st) full_rebuild(e);
    })->Unit(benchmark::kMillisecond);
}

void print_edit_ratios() {
    EditScene& small = edit_scene(16);
    EditScene& large = edit_scene(256);
    EditScene& whole = edit_scene(64, true);
    const Ratio map = interleaved([&] { edit_once(large); }, 40, [&] { edit_once(small); }, 40, 15);
    print_ratio("edit_cost_map_ratio", map, "<= 1.5");
    const Ratio full = interleaved([&] { edit_once(whole); }, 20, [&] { full_rebuild(whole); }, 1, 15);
    print_ratio("edit_cost_vs_full", full, "<= 0.05", 4);
}

}  // namespace isolux::bench
