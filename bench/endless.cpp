#include "endless.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <malloc.h>
#include <string>
#include <vector>

#include "isolux/endless.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/tileset_file.hpp"
#include "ratio.hpp"
#include "scenes.hpp"

namespace isolux::bench {

namespace {

// This process's resident memory now, bytes (/proc/self/status VmRSS).
double resident_bytes() {
    std::ifstream in("/proc/self/status");
    std::string key;
    double kb = 0;
    while (in >> key) {
        if (key == "VmRSS:") {
            in >> kb;
            return kb * 1024;
        }
        in.ignore(1 << 12, '\n');
    }
    return 0;
}

const Tileset& tileset() {
    static const Tileset t = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json");
    return t;
}

// The game's view: 960x540 with a light carried at its centre and four more
// standing around it, the default preset's lights.
Scene walk_scene(std::int64_t x, std::int64_t y) {
    Scene s;
    s.endless = true;
    s.params.falloff_scale = 8;
    s.lights.push_back(Light{double(x) + 480.5, double(y) + 270.5});
    for (int i = 0; i < 4; ++i) s.lights.push_back(Light{double(x) + 150.5 + 220 * i, double(y) + 120.5 + 90 * (i % 2)});
    return s;
}

}  // namespace

void print_endless_ratios() {
    const Tileset& ts = tileset();
    // Memory: a camera walks along a row of tiles, a tile (64 px) a frame for
    // the first 1,000, then 990 tiles a frame for 100 frames more (the same
    // distance in fewer, larger steps); the peak of this process's resident
    // memory over each part, the second over the first.
    {
        EndlessState st;
        std::int64_t x0 = 0, y0 = 0;
        endless_tile_center(Layout::diamond, ts.tile_width, ts.tile_height, 5'000'000, -5'000'000, x0, y0);
        const double tile = ts.tile_width / 2;  // a column's step along the row, in x (and half that in y)
        double first = 0, second = 0;
        long f = 0;
        std::vector<double> window_ms, steady_ms;  // the first part's frames that made a window, and the rest
        auto step = [&](double tiles_walked) {
            const std::int64_t x = x0 + std::int64_t(tiles_walked * tile), y = y0 + std::int64_t(tiles_walked * tile / 2);
            const std::uint64_t windows = st.windows_built;
            const double ms = seconds_per([&] { render_endless_frame(st, ts, walk_scene(x, y), WorldRect{x, y, 960, 540}, f++); }, 1) * 1e3;
            if (tiles_walked <= 1000 && f > 1) (st.windows_built != windows ? window_ms : steady_ms).push_back(ms);
            return resident_bytes();
        };
        // The walk's own memory: the process's resident memory over what it
        // held before the walk (what other figures of the run left). The heap
        // gives its free pages back first: else the walk's first part reuses
        // what earlier figures freed and looks smaller than it is alone.
        malloc_trim(0);
        const double before = resident_bytes();
        for (int i = 1; i <= 1000; ++i) first = std::max(first, step(i) - before);
        for (int i = 1; i <= 100; ++i) second = std::max(second, step(1000 + 990.0 * i) - before);
        std::printf("endless_walk_memory %.3f (the walk's peak resident memory: %.0f MB walking tiles 1,000 to 100,000 "
                    "over %.0f MB for the first 1,000; %llu windows; target <= 1.1)\n",
                    second / first, second / 1e6, first / 1e6, (unsigned long long)st.windows_built);
        auto median = [](std::vector<double> v) {
            std::sort(v.begin(), v.end());
            return v.empty() ? 0.0 : v[v.size() / 2];
        };
        std::printf("endless_window_frame_ms %.1f (median of the %zu frames of the first 1,000 tiles that made a new "
                    "window; the other %zu: %.2f ms)\n",
                    median(window_ms), window_ms.size(), steady_ms.size(), median(steady_ms));
    }
    // A moving frame: a camera walking 8 px right and 4 down a frame with its
    // lights, on an endless world (onwards, its windows remade as it goes)
    // and on a 64x64 map (to and fro across its middle; the map's tiles are
    // the endless world's 0..63, so both show the same kind of terrain).
    {
        const World& map = world("default", 64);
        const Rect b = map.placed.bounds;
        const int cx = b.x + b.w / 2 - 480, cy = b.y + b.h / 2 - 270;
        EndlessState endless;
        FrameState finite;
        long fe = 0, ff = 0;
        auto pos = [](long f) { return int(f % 400 < 200 ? f % 400 : 400 - f % 400) * 8; };
        auto on_endless = [&] {
            const std::int64_t x = cx + 8 * fe - map.placed.shift_x, y = cy + 4 * fe - map.placed.shift_y;
            render_endless_frame(endless, ts, walk_scene(x, y), WorldRect{x, y, 960, 540}, fe++);
        };
        auto on_map = [&] {
            const int x = cx + pos(ff), y = cy + pos(ff) / 2;
            Scene s = walk_scene(x, y);
            s.endless = false;
            s.width = s.height = 64;
            render_frame(finite, map, s, Camera{double(x), double(y), 960, 540}, ff++);
        };
        const std::uint64_t before = endless.windows_built;
        print_ratio("endless_frame_cost", interleaved(on_endless, 16, on_map, 16, 11), "<= 1.2");
        std::printf("# endless_frame_cost: %ld frames each, %llu windows made on the way\n", fe,
                    (unsigned long long)(endless.windows_built - before));
    }
    // One chunk's sprites and obstacle map, and that over memset of its pixels.
    {
        Scene s;
        s.endless = true;
        long k = 0;
        Rect bounds;
        auto chunk = [&] {
            const ChunkRange c{chunk_tiles * (k % 97), chunk_tiles * (k / 97), chunk_tiles, chunk_tiles};
            ++k;
            const EndlessWindow w = make_endless_window(ts, s, c);
            const Mask obstacles = build_obstacle_map(w.world.tileset, w.world.placed, s.params, w.world.placed.bounds);
            bounds = w.world.placed.bounds;
            return obstacles.bits.size();
        };
        chunk();
        std::vector<std::uint8_t> bytes(std::size_t(bounds.w) * bounds.h);
        auto floor = [&] { std::memset(bytes.data(), int(bytes[0] ^ 1), bytes.size()); };
        const double us = seconds_per(chunk, 5) * 1e6;
        std::printf("chunk_build_us %.0f (one %dx%d-tile chunk: its sprites placed and its obstacle map, %dx%d px)\n", us,
                    chunk_tiles, chunk_tiles, bounds.w, bounds.h);
        print_ratio("chunk_build_over_floor", interleaved(chunk, 1, floor, 20, 11), nullptr, 1);
    }
}

}  // namespace isolux::bench
