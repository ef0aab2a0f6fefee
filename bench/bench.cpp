// isolux-bench: the tracer against the paper's transcription, libtcod's field
// of view and the floor (writing intensities with no visibility test), and
// frames that do only what their scene calls for. `--ratios` prints the
// figures of docs/performance.md, measured side by side in this one run.
#include <benchmark/benchmark.h>
#include <libtcod/fov.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <thread>

#include "isolux/accuracy.hpp"
#include "isolux/blur.hpp"
#include "isolux/isolux.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/truth.hpp"
#include "frame/ray_tree.hpp"
#include "edits.hpp"
#include "endless.hpp"
#include "gpu_trace.hpp"
#include "ratio.hpp"
#include "whole_frame.hpp"
#include "scenes.hpp"
#include "frame/trace_hooks.hpp"
#include "frame/frame_cache.hpp"

using namespace isolux;
using isolux::bench::trace_scene;
using isolux::bench::TraceScene;

namespace {

Rect area_of(const TraceScene& s, int a) { return {s.cx - a, s.cy - a, 2 * a + 1, 2 * a + 1}; }

// isolux's tracer: what Algorithm 2 draws for one light (its intensities
// over the area), the same bytes as the transcription's.
void trace_isolux(const TraceScene& s, int a, int k, LightMask& out) {
    Params p;
    p.ray_skip = k;
    const Rect area = area_of(s, a);
    out = trace_light(s.obstacles, s.cx, s.cy, a, a, p, area, area_is_clear(s.obstacles, area));
}

// The paper's Algorithm 2, transcribed (core's reference implementation).
void trace_paper(const TraceScene& s, int a, int k, std::vector<std::uint8_t>& tex) {
    std::fill(tex.begin(), tex.end(), 0);
    const auto border = border_offsets(a, a);
    for (std::size_t i = 0; i < border.size(); i += std::size_t(k))
        trace_light_ray_paper(s.obstacles, s.cx, s.cy, s.cx + border[i].first, s.cy + border[i].second, area_of(s, a), tex);
}

// libtcod's map of the same area and obstacles, built once.
struct TcodArea {
    TCOD_Map* map = nullptr;
    std::vector<std::uint8_t> table;  // intensity by distance
    int a = 0;
};
TcodArea& tcod_area(const TraceScene& s, int a) {
    static std::map<std::pair<std::string, int>, TcodArea> cache;
    auto key = std::make_pair(s.name, a);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    TcodArea t;
    t.a = a;
    t.map = TCOD_map_new(2 * a + 1, 2 * a + 1);
    for (int y = -a; y <= a; ++y)
        for (int x = -a; x <= a; ++x) {
            const bool clear = !s.obstacles.get(s.cx + x, s.cy + y);
            TCOD_map_set_properties(t.map, x + a, y + a, clear, clear);
        }
    for (int d = 0; d <= a; ++d) t.table.push_back(falloff(d, 1.0));
    return cache.emplace(key, t).first->second;
}

void trace_tcod(TcodArea& t, TCOD_fov_algorithm_t algo, std::vector<std::uint8_t>& tex) {
    const int a = t.a, w = 2 * a + 1;
    TCOD_map_compute_fov(t.map, a, a, 0, false, algo);
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x)
            tex[std::size_t(y) * w + x] =
                TCOD_map_is_in_fov(t.map, x, y) ? t.table[std::max(std::abs(x - a), std::abs(y - a))] : 0;
}

// The floor: every pixel of the area gets its intensity, no visibility test.
void fill_floor(int a, const std::vector<std::uint8_t>& table, std::vector<std::uint8_t>& tex) {
    const int w = 2 * a + 1;
    for (int y = 0; y < w; ++y) {
        std::uint8_t* row = &tex[std::size_t(y) * w];
        const int dy = std::abs(y - a);
        for (int x = 0; x < w; ++x) row[x] = table[std::max(std::abs(x - a), dy)];
    }
}

const char* scenes[] = {"empty", "default", "forest", "corridors"};
const int areas[] = {64, 128, 256};  // half-extents: 129^2, 257^2, 513^2

void register_tracers() {
    for (const char* sc : scenes)
        for (int a : areas) {
            const std::string suffix = std::string("/") + sc + "/" + std::to_string(2 * a + 1);
            benchmark::RegisterBenchmark(("trace/isolux" + suffix).c_str(), [sc, a](benchmark::State& st) {
                const TraceScene& s = trace_scene(sc);
                LightMask m;
                for (auto _ : st) {
                    trace_isolux(s, a, 1, m);
                    benchmark::DoNotOptimize(m.value.data());
                }
                st.counters["ns_per_pixel"] = benchmark::Counter(double((2 * a + 1) * (2 * a + 1)),
                                                                 benchmark::Counter::kIsIterationInvariantRate |
                                                                     benchmark::Counter::kInvert);
            });
            benchmark::RegisterBenchmark(("trace/paper" + suffix).c_str(), [sc, a](benchmark::State& st) {
                const TraceScene& s = trace_scene(sc);
                std::vector<std::uint8_t> tex(std::size_t(2 * a + 1) * (2 * a + 1));
                for (auto _ : st) {
                    trace_paper(s, a, 1, tex);
                    benchmark::DoNotOptimize(tex.data());
                }
            });
            for (auto [name, algo] : {std::pair{"tcod_basic", FOV_BASIC}, {"tcod_shadowcast", FOV_SYMMETRIC_SHADOWCAST}})
                benchmark::RegisterBenchmark(("trace/" + std::string(name) + suffix).c_str(),
                                             [sc, a, algo = algo](benchmark::State& st) {
                                                 TcodArea& t = tcod_area(trace_scene(sc), a);
                                                 std::vector<std::uint8_t> tex(std::size_t(2 * a + 1) * (2 * a + 1));
                                                 for (auto _ : st) {
                                                     trace_tcod(t, algo, tex);
                                                     benchmark::DoNotOptimize(tex.data());
                                                 }
                                             });
            benchmark::RegisterBenchmark(("trace/floor" + suffix).c_str(), [a](benchmark::State& st) {
                std::vector<std::uint8_t> table, tex(std::size_t(2 * a + 1) * (2 * a + 1));
                for (int d = 0; d <= a; ++d) table.push_back(falloff(d, 1.0));
                for (auto _ : st) {
                    fill_floor(a, table, tex);
                    benchmark::DoNotOptimize(tex.data());
                }
            });
        }
}

// Beyond the paper: one light traced against solids estimated from the
// sprites on the default map, at 32 px: its ground pass and its sprite pass.
void register_solids() {
    // On one thread, and on two (a light's passes walking the tree's
    // subtrees on both, as a frame tracing one light does): wall time.
    for (int a : {64, 128})
        for (int threads : {1, 2}) {
            const std::string suffix = "/default/" + std::to_string(2 * a + 1) +
                                       (threads > 1 ? "/threads:" + std::to_string(threads) : "");
            for (bool sprites : {false, true})
                benchmark::RegisterBenchmark(
                    (std::string(sprites ? "trace/solids_sprites" : "trace/solids_ground") + suffix).c_str(),
                    [a, sprites, threads](benchmark::State& st) {
                        const World& w = bench::world("default", 24);
                        Params p;
                        p.occluders = Occluders::solids;
                        static const OccluderMap occ = build_occluders(w, p, w.placed.bounds);
                        const std::int64_t cx = w.placed.bounds.x + w.placed.bounds.w / 2,
                                           cy = w.placed.bounds.y + w.placed.bounds.h / 2;
                        const Rect area{int(cx) - a, int(cy) - a, 2 * a + 1, 2 * a + 1};
                        LightMask m = trace_light_solids(occ, cx, cy, a, a, 32, p, area);
                        for (auto _ : st) {
                            if (sprites)
                                light_sprite_points(m, occ, 32, p, threads);
                            else
                                m = trace_light_solids(occ, cx, cy, a, a, 32, p, area, threads);
                            benchmark::DoNotOptimize(m.value.data());
                        }
                    })
                    ->UseRealTime();
        }
}

// A view's obstacle region (a 1280x720 view, its lights' areas and the
// 256-px margin) before and after a pan of 256 px right, on the 24x24 map.
std::pair<Rect, Rect> pan_regions(const World& w) {
    const Rect b = w.placed.bounds, from = intersect(Rect{b.x + 200, b.y + 100, 2048, 1480}, b);
    return {from, intersect(Rect{from.x + 256, from.y, from.w, from.h}, b)};
}

// Beyond the paper: what a frame builds when the obstacle map's region is
// made (the first frame, Δy or n changed), over the default 24x24 map: the
// occluder map (spans, surface, the points each ground pixel holds; sprites'
// solids kept, as the frame keeps them), the sprites' solids themselves, the
// surfaces' reach for the blur within surfaces, and a floor: copying the
// surface's ids, 4 bytes a pixel, once; and what a pan past the region's
// margin builds (update_occluders) against building the panned region whole.
void register_occluder_map() {
    const World& w = bench::world("default", 24);
    static Params p;
    p.occluders = Occluders::solids;
    const Rect region = w.placed.bounds;
    benchmark::RegisterBenchmark("occluders/build/solids/default", [region](benchmark::State& st) {
        const World& w = bench::world("default", 24);
        SolidsCache cache;
        benchmark::DoNotOptimize(build_occluders(w, p, region, &cache).flags.data());
        for (auto _ : st) benchmark::DoNotOptimize(build_occluders(w, p, region, &cache).flags.data());
        st.counters["ns_per_pixel"] = benchmark::Counter(double(region.w) * region.h,
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    })->Unit(benchmark::kMillisecond);
    // The same map rebuilt in the storage it holds, as the frame does when a
    // parameter changes and the camera stays.
    benchmark::RegisterBenchmark("occluders/rebuild/solids/default", [region](benchmark::State& st) {
        const World& w = bench::world("default", 24);
        SolidsCache cache;
        OccluderMap m = build_occluders(w, p, region, &cache);
        for (auto _ : st) {
            rebuild_occluders(m, w, p, region, &cache);
            benchmark::DoNotOptimize(m.flags.data());
        }
        st.counters["ns_per_pixel"] = benchmark::Counter(double(region.w) * region.h,
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    })->Unit(benchmark::kMillisecond);
    // A pan past the obstacle region's margin, in a view's region: the
    // update (the 256-px strip that came in, the rest copied, the index
    // whole) against building that region whole.
    for (const bool update : {true, false})
        benchmark::RegisterBenchmark(update ? "occluders/pan_update/solids/default" : "occluders/pan_build/solids/default",
                                     [update](benchmark::State& st) {
            const World& w = bench::world("default", 24);
            const auto [from, to] = pan_regions(w);
            SolidsCache cache;
            // Back and forth: each update pans the map it keeps by 256 px.
            OccluderMap m = build_occluders(w, p, from, &cache);
            bool there = false;
            for (auto _ : st) {
                if (update) update_occluders(m, w, p, there ? from : to, Rect{}, &cache), there = !there;
                else m = build_occluders(w, p, to, &cache);
                benchmark::DoNotOptimize(m.flags.data());
            }
            st.counters["ns_per_pixel"] = benchmark::Counter(double(to.w) * to.h,
                                                             benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
        })->Unit(benchmark::kMillisecond);
    // The first frame with solids estimates every sprite's solids once.
    benchmark::RegisterBenchmark("occluders/sprite_solids/default", [](benchmark::State& st) {
        const World& w = bench::world("default", 24);
        for (auto _ : st)
            for (const Sprite& s : w.tileset.sprites)
                if (s.kind == SpriteKind::overlay) benchmark::DoNotOptimize(sprite_solids(w.tileset, s, p).heights.data());
    })->Unit(benchmark::kMillisecond);
    static const OccluderMap occ = build_occluders(w, p, region);
    // The coarse map occluder_scale 2 traces over, made from the map whole
    // (after a build, a pan or an edit).
    benchmark::RegisterBenchmark("occluders/coarse/scale:2/default", [](benchmark::State& st) {
        for (auto _ : st) benchmark::DoNotOptimize(coarse_occluders(occ, 2).flags.data());
        st.counters["ns_per_pixel"] = benchmark::Counter(double(occ.spans.size()),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    })->Unit(benchmark::kMillisecond);
    // The same pan's coarse map and picks at occluder_scale 2, updated in
    // place (pan_coarse_occluders) and made whole.
    for (const bool update : {true, false})
        benchmark::RegisterBenchmark(update ? "occluders/pan_coarse_update/scale:2/default" : "occluders/pan_coarse_build/scale:2/default",
                                     [update](benchmark::State& st) {
            const World& w = bench::world("default", 24);
            const auto [from, to] = pan_regions(w);
            SolidsCache cache;
            const OccluderMap maps[2] = {build_occluders(w, p, from, &cache), build_occluders(w, p, to, &cache)};
            OccluderMap c = coarse_occluders(maps[0], 2);
            std::vector<std::uint8_t> picks = coarse_picks(maps[0].surface, c, 2);
            int at = 0;
            for (auto _ : st) {
                const OccluderMap& next = maps[1 - at];
                if (update) pan_coarse_occluders(c, picks, next, maps[at].rect, 2);
                else c = coarse_occluders(next, 2), picks = coarse_picks(next.surface, c, 2);
                at = 1 - at;
                benchmark::DoNotOptimize(picks.data());
            }
            st.counters["ns_per_pixel"] = benchmark::Counter(double(to.w) * to.h,
                                                             benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
        })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("occluders/coarse_picks/scale:2/default", [](benchmark::State& st) {
        const OccluderMap c = coarse_occluders(occ, 2);
        for (auto _ : st) benchmark::DoNotOptimize(coarse_picks(occ.surface, c, 2).data());
        st.counters["ns_per_pixel"] = benchmark::Counter(double(occ.spans.size()),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("occluders/index_surfaces/default", [](benchmark::State& st) {
        SurfaceIds ids{occ.surface.rect, occ.surface.instance, {}};
        for (auto _ : st) {
            index_surfaces(ids);
            benchmark::DoNotOptimize(ids.reach.data());
        }
        st.counters["ns_per_pixel"] = benchmark::Counter(double(ids.id.size()),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("occluders/floor_memcpy_ids/default", [](benchmark::State& st) {
        std::vector<std::int32_t> copy(occ.surface.instance.size());
        for (auto _ : st) {
            std::memcpy(copy.data(), occ.surface.instance.data(), copy.size() * sizeof(std::int32_t));
            benchmark::DoNotOptimize(copy.data());
        }
        st.counters["ns_per_pixel"] = benchmark::Counter(double(copy.size()),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    })->Unit(benchmark::kMillisecond);
}

// ------------------------------------------------------------------ frames

Scene lights_scene(const World& w, int n, std::uint64_t seed, int a = 128) {
    Scene s;
    s.params.area_a = s.params.area_b = a;
    s.params.blur_radius = 0;
    Pcg32 rng(seed);
    for (int i = 0; i < n; ++i)
        s.lights.push_back(Light{double(rng.below(std::uint32_t(w.placed.bounds.w))) + 0.5,
                                 double(rng.below(std::uint32_t(w.placed.bounds.h))) + 0.5});
    return s;
}

FrameState lighting_state(int threads) {
    FrameState st;
    st.options.cpu_sprites = false;  // the app's split: sprites, blur, composite on the GPU
    st.options.cpu_blur_and_composite = false;
    st.options.threads = threads;
    return st;
}

// Every iteration moves every light by one pixel, so each frame retraces all.
void frame_lights(benchmark::State& st, int n, int threads) {
    const World& w = bench::world("default", 24);
    Scene s = lights_scene(w, n, 7);
    FrameState fs = lighting_state(threads);
    long f = 0;
    render_frame(fs, w, s, Camera{}, f++);
    for (auto _ : st) {
        for (Light& l : s.lights) l.x += (f % 2) ? 1 : -1;
        benchmark::DoNotOptimize(render_frame(fs, w, s, Camera{}, f++));
    }
}

// The walks' camera at frame f: 6 px right and 3 down a frame, back to its
// start every 64 frames; and the light it carries, at its centre.
Camera walk_camera(long f) { return {300.0 + 6.0 * double(f % 64), 200.0 + 3.0 * double(f % 64), 960, 540}; }
Light walk_light(const Camera& cam) { return Light{cam.x + 480.5, cam.y + 270.5}; }

// A walk: the camera moves 6 px a frame with a light carried at its centre,
// 16 frames an iteration; tracing every l frames, against what `o` says stops rays.
void frame_walk(benchmark::State& st, int l, Occluders o) {
    const World& w = bench::world("default", 24);
    Scene s = lights_scene(w, 8, 11);
    s.params.trace_every = l;
    s.params.occluders = o;
    FrameState fs = lighting_state(1);
    long f = 0;
    double tracing_ms = 0, correction_ms = 0, frames = 0;
    for (auto _ : st) {
        for (int i = 0; i < 16; ++i, ++f) {
            const Camera cam = walk_camera(f);
            Scene sf = s;
            sf.lights.push_back(walk_light(cam));
            const FrameReport r = render_frame(fs, w, sf, cam, f);
            tracing_ms += r.ms[int(Stage::trace)] + r.ms[int(Stage::opacity_correction)];
            correction_ms += r.ms[int(Stage::opacity_correction)];
            ++frames;
        }
    }
    // The tracing stages' own time per frame (trace, drawing into the light
    // texture, opacity correction), as the frame reports it; and the
    // correction's alone (against solids: the sprite pass).
    st.counters["tracing_ms_per_frame"] = tracing_ms / frames;
    st.counters["correction_ms_per_frame"] = correction_ms / frames;
}

// 8 lights in a 960x540 view, and 992 more elsewhere on a 64x64-tile map.
void frame_offscreen(benchmark::State& st, bool with_offscreen) {
    const World& w = bench::world("default", 64);
    const Camera cam{3000, 1500, 960, 540};
    Scene s;
    s.params.blur_radius = 0;
    Pcg32 rng(5);
    for (int i = 0; i < 8; ++i) s.lights.push_back(Light{cam.x + 100 + 100.0 * i, cam.y + 100 + 40.0 * i});
    if (with_offscreen)
        while (s.lights.size() < 1000) {
            const double x = rng.below(std::uint32_t(w.placed.bounds.w)), y = rng.below(std::uint32_t(w.placed.bounds.h));
            if (x > cam.x - 400 && x < cam.x + 1400 && y > cam.y - 400 && y < cam.y + 1000) continue;
            s.lights.push_back(Light{x, y});
        }
    FrameState fs = lighting_state(1);
    long f = 0;
    render_frame(fs, w, s, cam, f++);
    for (auto _ : st) {
        for (std::size_t i = 0; i < 8; ++i) s.lights[i].x += (f % 2) ? 1 : -1;  // the visible ones move
        benchmark::DoNotOptimize(render_frame(fs, w, s, cam, f++));
    }
}

// A full retrace frame (every light traced again) against a frame where
// nothing changed; the CPU's whole frame, sprites and composite included.
void frame_static(benchmark::State& st, bool still) {
    const World& w = bench::world("default", 24);
    Scene s = lights_scene(w, 16, 3);
    s.params.blur_radius = 2;
    FrameState fs;
    long f = 0;
    render_frame(fs, w, s, Camera{}, f++);
    for (auto _ : st) {
        if (!still) fs.cache->lights.clear(), fs.cache->trace_lights.clear();  // forget the traces: all again
        benchmark::DoNotOptimize(render_frame(fs, w, s, Camera{}, f++));
    }
}

// The same view and lights on maps of growing size.
void frame_map_size(benchmark::State& st, int side) {
    const World& w = bench::world("default", side);
    // The view centred on tile (8, 8): the same tiles on every map (a larger
    // map extends a smaller one), wherever the layout puts them in the world.
    int tx = 0, ty = 0;
    tile_center(w.map.layout, w.map.tile_width, w.map.tile_height, 8, 8, tx, ty);
    const Camera cam{double(tx + w.placed.shift_x - 480), double(ty + w.placed.shift_y - 270), 960, 540};
    Scene s;
    s.params.blur_radius = 2;
    for (int i = 0; i < 4; ++i) s.lights.push_back(Light{cam.x + 200 + 180.0 * i, cam.y + 150 + 60.0 * i});
    FrameState fs;
    long f = 0;
    for (auto _ : st) {
        fs = FrameState{};  // a first frame: obstacle map, sprites, traces, composite
        benchmark::DoNotOptimize(render_frame(fs, w, s, cam, f++));
    }
}

void register_frames() {
    for (int n : {1, 16, 256})
        for (int t : {1, 2})
            benchmark::RegisterBenchmark(("frame/lights:" + std::to_string(n) + "/threads:" + std::to_string(t)).c_str(),
                                         [n, t](benchmark::State& st) { frame_lights(st, n, t); })
                ->UseRealTime();
    for (int l : {1, 4})
        benchmark::RegisterBenchmark(("frame/walk/trace_every:" + std::to_string(l)).c_str(),
                                     [l](benchmark::State& st) { frame_walk(st, l, Occluders::footprints); });
    benchmark::RegisterBenchmark("frame/walk/occluders:solids",
                                 [](benchmark::State& st) { frame_walk(st, 1, Occluders::solids); });
    benchmark::RegisterBenchmark("frame/offscreen/lights:8", [](benchmark::State& st) { frame_offscreen(st, false); });
    benchmark::RegisterBenchmark("frame/offscreen/lights:1000", [](benchmark::State& st) { frame_offscreen(st, true); });
    benchmark::RegisterBenchmark("frame/static", [](benchmark::State& st) { frame_static(st, true); });
    benchmark::RegisterBenchmark("frame/full_retrace", [](benchmark::State& st) { frame_static(st, false); });
    for (int side : {16, 64, 256})
        benchmark::RegisterBenchmark(("frame/map_size:" + std::to_string(side)).c_str(),
                                     [side](benchmark::State& st) { frame_map_size(st, side); });
}

// ------------------------------------------------------------------ --ratios

// The truth (truth.hpp): the 3D reference of the default scene (two lights,
// 257x257 areas, the whole map in view), and a sweep of 48 settings against it.
// Targets: <= 2 s and <= 3 minutes on one core (docs/accuracy.md).
void register_truth() {
    static const Scene scene = load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/default.json");
    static const World w = make_world(load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json"), scene);
    benchmark::RegisterBenchmark("truth/3d/default_scene", [](benchmark::State& st) {
        const Rect view = camera_view(scene.camera, w);
        for (auto _ : st) benchmark::DoNotOptimize(reference_texture(w, scene, view, Reference::three_d));
    })->Unit(benchmark::kMillisecond)->Iterations(3);
    benchmark::RegisterBenchmark("truth/sweep48/default_scene", [](benchmark::State& st) {
        std::vector<SweepAxis> axes = {{"ray_skip", {"1", "2", "4", "8"}},
                                       {"blur_radius", {"0", "2", "4"}},
                                       {"light_height", {"8", "16", "32", "64"}}};
        SweepOptions opt;
        opt.frames = 2;
        opt.repeats = 1;
        opt.references = {Reference::three_d};
        for (auto _ : st) benchmark::DoNotOptimize(run_sweep(w, scene, axes, opt));
    })->Unit(benchmark::kMillisecond)->Iterations(1);
}

// Touches each node of the two trees a light of half-extents a (a square
// area) has against solids once, `frames` times: a node's area index and
// depth, its flag read (bit 4: the subtree climbs above the light's area,
// skipped) and its falloff written. `tallest`: the occluder map's tallest
// point, in rows. Returns the milliseconds.
std::function<double()> tree_touch_floor(int a, int tallest, int frames) {
    struct Walk {
        std::vector<std::uint32_t> at;  // area index << 10 | depth
        std::vector<std::int32_t> end;
        std::vector<std::uint8_t> flags, value;
    };
    auto walk_of = [](int ta, int tb, int away_rows) {
        const auto tree = ray_tree(ta, tb, 1);
        Walk k;
        const std::int32_t centre = tb * (2 * ta + 1) + ta;
        for (std::size_t i = 0; i < tree->end.size(); ++i)
            k.at.push_back(std::uint32_t(centre + tree->offset[i]) << 10 | tree->depth[i]);
        k.end = tree->end;
        k.flags.assign(std::size_t(2 * ta + 1) * (2 * tb + 1), 0);
        std::fill_n(k.flags.begin(), std::size_t(2 * ta + 1) * away_rows, std::uint8_t(4));
        k.value.resize(k.flags.size());
        return k;
    };
    auto walks = std::make_shared<std::array<Walk, 2>>(
        std::array<Walk, 2>{walk_of(a, a, 0), walk_of(a, a + tallest, tallest)});
    std::vector<std::uint8_t> table(1024);
    for (std::size_t d = 0; d < table.size(); ++d) table[d] = falloff(std::int64_t(d), 1.0);
    return [walks, table, frames] {
        const auto t0 = std::chrono::steady_clock::now();
        for (int f = 0; f < frames; ++f)
            for (Walk& k : *walks) {
                const std::uint32_t* at = k.at.data();
                const std::int32_t* end = k.end.data();
                const std::uint8_t* flags = k.flags.data();
                std::uint8_t* value = k.value.data();
                for (std::int32_t i = 0, n = std::int32_t(k.at.size()); i < n;) {
                    const std::uint32_t w = at[i];
                    if (flags[w >> 10] & 4) {
                        i = end[i];
                        continue;
                    }
                    value[w >> 10] = table[w & 1023];
                    ++i;
                }
                benchmark::DoNotOptimize(k.value.data());
            }
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    };
}

// Of the nodes tree_touch_floor touches for the walk's carried light (its
// 64 positions) over `occ`, the share at or behind a span: those an exact
// pass must step with the shades their rays carry. Ground tree, then sprite tree.
std::array<double, 2> nodes_behind_spans(const OccluderMap& occ, int a) {
    std::array<double, 2> all{}, behind{};
    for (int f = 0; f < 64; ++f) {
        const Light l = walk_light(walk_camera(f));
        const int cx = int(l.x), cy = int(l.y);
        for (int t = 0; t < 2; ++t) {
            const auto tree = ray_tree(a, t == 0 ? a : a + occ.tallest, 1);
            std::int32_t shaded_until = -1;  // the end of the subtree of the span node the walk is below
            for (std::int32_t i = 0; i < std::int32_t(tree->end.size());) {
                if (tree->dy[std::size_t(i)] < -a) {  // climbs above the light's area
                    i = tree->end[std::size_t(i)];
                    continue;
                }
                const int x = cx + tree->dx[std::size_t(i)], y = cy + tree->dy[std::size_t(i)];
                const std::uint8_t flags = occ.flags[std::size_t(y - occ.rect.y) * occ.rect.w + std::size_t(x - occ.rect.x)];
                ++all[std::size_t(t)];
                if (i < shaded_until) ++behind[std::size_t(t)];
                else if (flags & OccluderMap::has_span) ++behind[std::size_t(t)], shaded_until = tree->end[std::size_t(i)];
                ++i;
            }
        }
    }
    return {behind[0] / all[0], behind[1] / all[1]};
}

// Every figure of docs/performance.md, each the median of ratios of its two
// sides measured interleaved (A, B, A, B, ...) in this one run, with the
// spread over the pairs: a load that comes and goes hits both sides.
// Tracing time per frame (trace, drawing into the texture, correction, from
// the frame report) of a walking camera carrying a light, tracing every l
// frames, against what stops the rays.
void print_walk_ratios(int pairs) {
    auto walk = [](int l, Occluders o, int threads = 1) {
        return [l, o, st = lighting_state(threads), f = long(0), s = lights_scene(bench::world("default", 24), 8, 11)]() mutable {
            const World& w = bench::world("default", 24);
            s.params.trace_every = l;
            s.params.occluders = o;
            double ms = 0;
            for (int i = 0; i < 16; ++i, ++f) {
                const Camera cam = walk_camera(f);
                Scene sf = s;
                sf.lights.push_back(walk_light(cam));
                const FrameReport r = render_frame(st, w, sf, cam, f);
                ms += r.ms[int(Stage::trace)] + r.ms[int(Stage::opacity_correction)];
            }
            return ms;
        };
    };
    // Every 4 frames against every frame.
    auto walk4 = walk(4, Occluders::footprints), walk1 = walk(1, Occluders::footprints);
    bench::print_ratio("trace_every4_cost", bench::interleaved_costs(walk4, walk1, pairs), "<= 0.3");
    // Beyond the paper: against solids estimated from the sprites (ground rays
    // and the sprite pass) over the paper's whole light (Algorithm 2 and the
    // opacity correction), every frame.
    auto walk_solids = walk(1, Occluders::solids), walk_footprints = walk(1, Occluders::footprints);
    bench::print_ratio("solids_trace_cost", bench::interleaved_costs(walk_solids, walk_footprints, pairs), "<= 6");
    // The same on two threads (the app's on this machine): one light moves,
    // so its rays against solids spread over both; the paper's light takes one.
    auto walk_solids2 = walk(1, Occluders::solids, 2), walk_footprints2 = walk(1, Occluders::footprints, 2);
    bench::print_ratio("solids_trace_cost_threads2", bench::interleaved_costs(walk_solids2, walk_footprints2, pairs), nullptr);
    // The floor of any pass over the border rays' trees: the same 16 frames
    // of the carried light with every node its two passes can walk touched
    // once (its flag byte read, its falloff written: no span, no shade),
    // over the paper's whole light. The ground tree is the light's area's;
    // the sprite tree runs to the border of the area grown by the tallest
    // point's rows, less the subtrees that climb above the light's area
    // (the sprite pass leaves those at their first node).
    Params solids;
    solids.occluders = Occluders::solids;
    const World& w = bench::world("default", 24);
    const OccluderMap occ = build_occluders(w, solids, w.placed.bounds);
    bench::print_ratio("solids_tree_floor",
                       bench::interleaved_costs(tree_touch_floor(128, occ.tallest, 16), walk_footprints, pairs), nullptr);
    // The carried light's two passes against solids (the ground pass and the
    // sprite pass, at the walk's 16 positions, one thread) over the floor
    // walk of the same light's trees: how far the passes run above the
    // structure they walk.
    auto passes = [&occ, solids] {
        const auto t0 = std::chrono::steady_clock::now();
        for (long f = 0; f < 16; ++f) {
            const Light l = walk_light(walk_camera(f));
            const std::int64_t cx = std::int64_t(std::floor(l.x)), cy = std::int64_t(std::floor(l.y));
            const Rect area{int(cx) - 128, int(cy) - 128, 257, 257};
            LightMask m = trace_light_solids(occ, cx, cy, 128, 128, light_height(l, solids), solids, area);
            light_sprite_points(m, occ, light_height(l, solids), solids);
            benchmark::DoNotOptimize(m.value.data());
        }
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    };
    bench::print_ratio("solids_over_floor", bench::interleaved_costs(passes, tree_touch_floor(128, occ.tallest, 16), pairs),
                       "<= 2");
    const auto behind = nodes_behind_spans(occ, 128);
    std::printf("solids_nodes_behind_spans ground %.3f sprites %.3f (of the nodes solids_tree_floor touches)\n", behind[0],
                behind[1]);
    // A pan past the obstacle region's margin with solids: update_occluders
    // (the strip that came in, the index whole) over building the region whole.
    const auto [from, to] = pan_regions(w);
    const Params& p = solids;
    SolidsCache cache;
    OccluderMap panned = build_occluders(w, p, from, &cache), built;
    bool there = false;  // back and forth: each update pans the map it keeps by 256 px
    auto update = [&] {
        update_occluders(panned, w, p, there ? from : to, Rect{}, &cache), there = !there;
        benchmark::DoNotOptimize(panned.flags.data());
    };
    auto build = [&] { built = build_occluders(w, p, to, &cache), benchmark::DoNotOptimize(built.flags.data()); };
    bench::print_ratio("pan_occluders_cost", bench::interleaved(update, 2, build, 2, pairs), "<= 0.5");
    // The frame's obstacle stage when the camera passes the region's margin
    // (a 1280x720 view moved 320 px, back and forth: each frame moves the
    // region, its size the same), against the same frames with the kept maps
    // dropped first (each built whole), per model; 8 frames a side.
    for (const Occluders o : {Occluders::footprints, Occluders::solids}) {
        auto panning = [o](bool whole) {
            return [o, whole, st = lighting_state(1), f = long(0)]() mutable {
                const World& w = bench::world("default", 24);
                Scene s;
                s.params.occluders = o;
                double ms = 0;
                for (int i = 0; i < 8; ++i, ++f) {
                    const Camera cam{600.0 + 320.0 * (f % 2), 300.0, 1280, 720};
                    s.lights = {Light{cam.x + 640.5, cam.y + 360.5}};
                    if (whole) st.obstacles = Mask{}, st.occluders = OccluderMap{}, st.cache->ground = GroundLines{};
                    ms += render_frame(st, w, s, cam, f).ms[int(Stage::obstacle_map)];
                }
                return ms;
            };
        };
        bench::print_ratio(o == Occluders::solids ? "pan_obstacle_stage_cost_solids" : "pan_obstacle_stage_cost",
                           bench::interleaved_costs(panning(false), panning(true), pairs), "<= 0.5");
    }
}

int ratios() {
    const char* ratio_scene = "default";
    const int a = 128;
    const int pairs = 11;
    // Byte-identical at k = 1: isolux's texture against the transcription's.
    const TraceScene& s = trace_scene(ratio_scene);
    LightMask ours;
    std::vector<std::uint8_t> paper(std::size_t(2 * a + 1) * (2 * a + 1));
    bresenham_steps() = 0;
    trace_isolux(s, a, 1, ours);
    const double steps = double(bresenham_steps());
    trace_paper(s, a, 1, paper);
    // The transcription's own steps: each ray up to and including its first obstacle.
    double paper_steps = 0;
    for (auto [bx, by] : border_offsets(a, a))
        for (BresenhamRay r(s.cx, s.cy, s.cx + bx, s.cy + by); !r.done(); r.step()) {
            ++paper_steps;
            if (s.obstacles.get(int(r.x), int(r.y))) break;
        }
    const bool identical = ours.value == paper;
    const double pixels = double(2 * a + 1) * (2 * a + 1);

    // The tracer against the transcription, libtcod and the floor.
    auto isolux = [&] { trace_isolux(s, a, 1, ours); benchmark::DoNotOptimize(ours.value.data()); };
    auto transcription = [&] { trace_paper(s, a, 1, paper); benchmark::DoNotOptimize(paper.data()); };
    bench::print_ratio("speedup_vs_paper", bench::interleaved(transcription, 10, isolux, 10, pairs), ">= 8", 2);
    std::vector<std::uint8_t> tex(std::size_t(2 * a + 1) * (2 * a + 1));
    TcodArea& tcod = tcod_area(s, a);
    for (auto [name, algo] : {std::pair{"tcod_basic", FOV_BASIC}, {"tcod_shadowcast", FOV_SYMMETRIC_SHADOWCAST}}) {
        // libtcod's field of view alone, and with the write of the same intensities (an out-of-line
        // TCOD_map_is_in_fov call per pixel, which alone costs more than isolux's whole trace).
        auto fov = [&, algo = algo] { TCOD_map_compute_fov(tcod.map, a, a, 0, false, algo); };
        auto fov_and_write = [&, algo = algo] { trace_tcod(tcod, algo, tex); benchmark::DoNotOptimize(tex.data()); };
        bench::print_ratio(("speedup_vs_" + std::string(name) + "_fov_only").c_str(),
                           bench::interleaved(fov, 10, isolux, 10, pairs), nullptr, 2);
        bench::print_ratio(("speedup_vs_" + std::string(name)).c_str(),
                           bench::interleaved(fov_and_write, 10, isolux, 10, pairs), nullptr, 2);
    }
    // The floor: memset of the light's area, the bytes its texture must be written with.
    std::vector<std::uint8_t> area_bytes(tex.size());
    auto floor_memset = [&] { std::memset(area_bytes.data(), area_bytes[0] ^ 1, area_bytes.size()); benchmark::DoNotOptimize(area_bytes.data()); };
    bench::print_ratio("tracer_times_floor", bench::interleaved(isolux, 10, floor_memset, 100, pairs), nullptr, 1);
    std::vector<std::uint8_t> table;
    for (int d = 0; d <= a; ++d) table.push_back(falloff(d, 1.0));
    auto scalar_fill = [&] { fill_floor(a, table, tex); benchmark::DoNotOptimize(tex.data()); };
    bench::print_ratio("times_scalar_fill", bench::interleaved(isolux, 10, scalar_fill, 10, pairs), "<= 20", 2);

    // Frames (the app's split: the CPU traces, the GPU blurs and composites).
    struct Moving {
        const World& w = bench::world("default", 24);
        Scene scene;
        FrameState st;
        long f = 0;
        Moving(int n, int threads) : scene(lights_scene(w, n, 7)), st(lighting_state(threads)) { render_frame(st, w, scene, Camera{}, f++); }
        void operator()() {
            for (Light& l : scene.lights) l.x += (f % 2) ? 1 : -1;
            render_frame(st, w, scene, Camera{}, f++);
        }
    };
    Moving one(16, 1), two(16, 2);
    bench::print_ratio("threads2_speedup", bench::interleaved([&] { one(); }, 5, [&] { two(); }, 5, pairs), ">= 1.7", 2);

    print_walk_ratios(pairs);

    // 1000 lights of which 8 are in view, against those 8 alone (the 8 move each frame).
    auto offscreen = [](bool more) {
        const World& w = bench::world("default", 64);
        const Camera cam{3000, 1500, 960, 540};
        Scene sc;
        sc.params.blur_radius = 0;
        Pcg32 rng(5);
        for (int i = 0; i < 8; ++i) sc.lights.push_back(Light{cam.x + 100 + 100.0 * i, cam.y + 100 + 40.0 * i});
        while (more && sc.lights.size() < 1000) {
            const double x = rng.below(std::uint32_t(w.placed.bounds.w)), y = rng.below(std::uint32_t(w.placed.bounds.h));
            if (x > cam.x - 400 && x < cam.x + 1400 && y > cam.y - 400 && y < cam.y + 1000) continue;
            sc.lights.push_back(Light{x, y});
        }
        return [&w, cam, sc, st = lighting_state(1), f = long(0)]() mutable {
            for (std::size_t i = 0; i < 8; ++i) sc.lights[i].x += (f % 2) ? 1 : -1;
            render_frame(st, w, sc, cam, f++);
        };
    };
    auto with_1000 = offscreen(true), with_8 = offscreen(false);
    bench::print_ratio("offscreen_lights_cost", bench::interleaved(with_1000, 5, with_8, 5, pairs), "<= 1.2");

    // A frame where nothing changed against a full retrace frame (sprites, blur, composite on the CPU).
    const World& w24 = bench::world("default", 24);
    Scene still_scene = lights_scene(w24, 16, 3);
    still_scene.params.blur_radius = 2;
    FrameState still_state, full_state;
    long f_still = 0, f_full = 0;
    render_frame(still_state, w24, still_scene, Camera{}, f_still++);
    render_frame(full_state, w24, still_scene, Camera{}, f_full++);
    bench::print_ratio("static_frame_cost", bench::interleaved([&] { render_frame(still_state, w24, still_scene, Camera{}, f_still++); }, 1000, [&] {
        full_state.cache->lights.clear(), full_state.cache->trace_lights.clear();  // forget the traces: all again
        render_frame(full_state, w24, still_scene, Camera{}, f_full++);
    }, 1, pairs), "<= 0.05", 5);

    bench::print_floor_ratios();
    bench::print_edit_ratios();
    bench::print_endless_ratios();
    bench::print_gpu_figures();

    std::printf("ns_per_area_pixel %.3f (median of %d runs of 10)\n", [&] {
        std::vector<double> t;
        for (int i = 0; i < pairs; ++i) t.push_back(bench::seconds_per(isolux, 10) * 1e9 / pixels);
        std::sort(t.begin(), t.end());
        return t[t.size() / 2];
    }(), pairs);
    std::printf("bresenham_steps_per_pixel %.3f\n", steps / pixels);
    std::printf("paper_bresenham_steps_per_pixel %.3f\n", paper_steps / pixels);
    std::printf("identical_to_paper_at_k1 %d\n", identical ? 1 : 0);
    std::printf("# tracer figures: scene %s, area %dx%d, one light, k = 1; %u hardware threads\n", ratio_scene, 2 * a + 1,
                2 * a + 1, std::thread::hardware_concurrency());
    return identical ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    register_tracers();
    register_solids();
    register_occluder_map();
    register_frames();
    register_truth();
    bench::register_edits();
    bench::register_whole_frames();
    for (int i = 1; i < argc; ++i)
        if (std::strcmp(argv[i], "--ratios") == 0) return ratios();
        else if (std::strcmp(argv[i], "--endless-ratios") == 0) return bench::print_endless_ratios(), 0;  // those alone
        else if (std::strcmp(argv[i], "--solids-frame-ratios") == 0) return bench::print_solids_frame_ratios(11), 0;  // those alone
        else if (std::strcmp(argv[i], "--gpu-figures") == 0) return bench::print_gpu_figures(), 0;  // gpu_trace_identical, solids_gpu_cpu_ms
        else if (std::strcmp(argv[i], "--walk-ratios") == 0) return print_walk_ratios(11), 0;  // trace_every4_cost, solids_trace_cost
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
