#include "whole_frame.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cstring>
#include <ctime>
#include <functional>
#include <map>
#include <memory>
#include <string>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "isolux/blur.hpp"
#include "base/cpu.hpp"
#include "isolux/composite.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/world.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/truth.hpp"
#include "ratio.hpp"
#include "scenes.hpp"
#include "frame/trace_hooks.hpp"
#include "frame/frame_cache.hpp"

namespace isolux::bench {

namespace {

// The frame: a 1920x1080 view in the middle of a 64x64-tile map, 32
// lights of a = b = 128 spread over it, blur radius 2, everything on the CPU.
struct ScreenScene {
    const World* world = nullptr;
    Scene scene;
    Camera camera;
    FrameState frame;
    long f = 0;
    std::vector<std::uint8_t> floor_src, floor_dst;  // memcpy's bytes
};

std::unique_ptr<ScreenScene> make_screen(const std::string& map, int threads, int lights = 32,
                                         const std::function<void(Params&)>& tune = nullptr) {
    auto s = std::make_unique<ScreenScene>();
    s->world = &world(map, 64);
    const Rect b = s->world->placed.bounds;
    s->camera = Camera{double(b.x + (b.w - 1920) / 2), double(b.y + (b.h - 1080) / 2), 1920, 1080};
    s->scene.params.area_a = s->scene.params.area_b = 128;
    s->scene.params.blur_radius = 2;
    if (tune) tune(s->scene.params);
    Pcg32 rng(17);
    for (int i = 0; i < lights; ++i)
        s->scene.lights.push_back(Light{s->camera.x + rng.below(1920) + 0.5, s->camera.y + rng.below(1080) + 0.5});
    s->frame.options.threads = threads;
    s->frame.options.view_light_texture = false;  // nobody reads the view's copy: the composite reads in place
    render_frame(s->frame, *s->world, s->scene, s->camera, s->f++);
    return s;
}

ScreenScene& screen(const std::string& map, int threads) {
    static std::map<std::pair<std::string, int>, std::unique_ptr<ScreenScene>> cache;
    auto& s = cache[{map, threads}];
    if (!s) s = make_screen(map, threads);
    return *s;
}

// One frame in which `moved` of the lights (the first ones) moved a pixel.
FrameReport step(ScreenScene& s, std::size_t moved) {
    const double dx = (s.f % 2) ? 1 : -1;
    for (std::size_t i = 0; i < moved && i < s.scene.lights.size(); ++i) s.scene.lights[i].x += dx;
    return render_frame(s.frame, *s.world, s.scene, s.camera, s.f++);
}

std::size_t area_bytes(const ScreenScene& s) {
    std::size_t n = 0;
    for (const Light& l : s.scene.lights) {
        const Rect r = light_area(l, s.scene.params);
        n += std::size_t(r.w) * r.h;
    }
    return n;
}

// Copies of the frame's traced masks, for a stage to work on in place.
std::vector<LightMask> traced_masks(const ScreenScene& s) {
    std::vector<LightMask> masks;
    for (const auto& t : s.frame.cache->lights) masks.push_back(t.mask);
    return masks;
}

// memcpy of n bytes into a buffer of its own (kept between calls, as the
// frame keeps its buffers).
struct Copy {
    mutable std::vector<std::uint8_t> src, dst;
    explicit Copy(std::size_t n) : src(n, 1), dst(n, 0) {}
    void operator()() const {
        std::memcpy(dst.data(), src.data(), src.size());
        benchmark::DoNotOptimize(dst.data());
    }
};
struct Set {
    mutable std::vector<std::uint8_t> dst;
    explicit Set(std::size_t n) : dst(n, 0) {}
    void operator()() const {
        std::memset(dst.data(), int(dst[0] ^ 1), dst.size());
        benchmark::DoNotOptimize(dst.data());
    }
};

// The correction's bytes without its rule: over each light's rows, its
// ground lines read and its mask read and written (value ^= below8), in the
// correction's vector width, with its prefetch of the lines eight rows ahead
// (core/src/base/rows_ahead.hpp).
// Its ratio to the memset of the areas says how much of
// correction_times_floor is the traffic itself.
template <class XorRow>
void correction_streams(const GroundLines& lines, std::vector<LightMask>& masks, XorRow xor_row) {
    const std::size_t stride = std::size_t(lines.rect.w);
    for (LightMask& m : masks) {
        const Rect r = intersect(m.clip, lines.rect);
        for (int y = r.y; y < r.y + r.h; ++y) {
            const std::uint8_t* b = &lines.below8[std::size_t(y - lines.rect.y) * stride + std::size_t(r.x - lines.rect.x)];
            std::uint8_t* v = &m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(r.x - m.clip.x)];
            if (y == r.y)
                for (int k = 0; k < 8 && y + k < r.y + r.h; ++k)
                    for (int x = 0; x < r.w; x += 64) __builtin_prefetch(b + std::size_t(k) * stride + std::size_t(x));
            if (y + 8 < r.y + r.h)
                for (int x = 0; x < r.w; x += 64) __builtin_prefetch(b + 8 * stride + std::size_t(x));
            xor_row(v, b, r.w);
        }
        benchmark::DoNotOptimize(m.value.data());
    }
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) inline void xor_row_avx2(std::uint8_t* v, const std::uint8_t* b, int w) {
    int x = 0;
    for (; x + 32 <= w; x += 32) {
        __m256i* at = reinterpret_cast<__m256i*>(v + x);
        _mm256_storeu_si256(at, _mm256_xor_si256(_mm256_loadu_si256(at), _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + x))));
    }
    for (; x < w; ++x) v[x] ^= b[x];
}
__attribute__((target("avx2"))) void correction_streams_avx2(const GroundLines& lines, std::vector<LightMask>& masks) {
    correction_streams(lines, masks, xor_row_avx2);
}
#endif

struct CorrectionStreams {
    const GroundLines& lines;
    std::vector<LightMask>& masks;
    void operator()() const {
#if defined(__x86_64__)
        if (wide_kernels()) return correction_streams_avx2(lines, masks);
#endif
        correction_streams(lines, masks, [](std::uint8_t* __restrict v, const std::uint8_t* __restrict b, int w) {
            for (int x = 0; x < w; ++x) v[x] ^= b[x];
        });
    }
};

void stage_counters(benchmark::State& st, const std::array<double, stage_count>& ms, double n) {
    for (int k = 0; k < stage_count; ++k)
        if (ms[std::size_t(k)] > 0) st.counters[std::string(to_string(Stage(k))) + "_ms"] = ms[std::size_t(k)] / n;
}

}  // namespace

void register_whole_frames() {
    for (const char* map : {"default", "forest"})
        for (int threads : {1, 2})
            for (int moved : {32, 1}) {
                const std::string name = std::string("whole_frame/") + map + "/moved:" + std::to_string(moved) +
                                         "_of_32/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), [map, threads, moved](benchmark::State& st) {
                    ScreenScene& s = screen(map, threads);
                    std::array<double, stage_count> ms{};
                    double n = 0, composited = 0;
                    const TreeTraces trees_before = tree_traces();
                    for (auto _ : st) {
                        const FrameReport r = step(s, std::size_t(moved));
                        for (int k = 0; k < stage_count; ++k) ms[std::size_t(k)] += r.ms[std::size_t(k)];
                        for (const Rect& z : r.touched_parts[int(Stage::composite)]) composited += double(z.w) * z.h;
                        ++n;
                    }
                    stage_counters(st, ms, n);
                    // The share of the view each frame composited again (its changed parts).
                    st.counters["composited_share"] = composited / n / (double(s.camera.width) * s.camera.height);
                    // Lights whose ray tree was walked (too many obstacles to prune) or pruned, per
                    // frame; counted per thread, so only where this thread traces them all.
                    if (threads == 1) {
                        st.counters["trees_walked"] = double(tree_traces().walked - trees_before.walked) / n;
                        st.counters["trees_pruned"] = double(tree_traces().pruned - trees_before.pruned) / n;
                    }
                })->Unit(benchmark::kMillisecond)->UseRealTime();
            }
    // Each stage alone on the frame's own buffers, one thread.
    // The blur at each radius of its fused pass (1 to 7) and one past it, on
    // the frame's grey texture (its 32 lights are white) and on the same
    // texels as RGB (a coloured light's layout).
    for (int radius : {1, 2, 3, 4, 5, 7, 8})
        for (const bool rgb : {false, true})
            benchmark::RegisterBenchmark(("stage/blur" + std::string(rgb ? "_rgb" : "") + "/radius:" + std::to_string(radius)).c_str(),
                                         [radius, rgb](benchmark::State& st) {
                                             ScreenScene& s = screen("default", 1);
                                             const LightTexture tex = rgb ? rgb_texture(s.frame.traced) : s.frame.traced;
                                             LightTexture out(tex.rect, tex.channels);
                                             for (auto _ : st) box_blur_into(tex, radius, tex.rect, out);
                                         })
                ->Unit(benchmark::kMillisecond);
    // The whole frame with every light moved, per model of what stops the
    // rays (solids_frame_cost's two sides), one thread.
    for (const Occluders o : {Occluders::footprints, Occluders::solids})
        benchmark::RegisterBenchmark((std::string("frame/screen/occluders:") + (o == Occluders::solids ? "solids" : "footprints")).c_str(),
                                     [o](benchmark::State& st) {
                                         auto s = make_screen("default", 1, 32, [o](Params& p) { p.occluders = o; });
                                         for (auto _ : st) step(*s, 32);
                                     })
            ->Unit(benchmark::kMillisecond);
    // The same against solids with the sprites shaded by their normals
    // (sprite_shading_cost's first side).
    benchmark::RegisterBenchmark("frame/screen/occluders:solids/sprite_shading:solids", [](benchmark::State& st) {
        auto s = make_screen("default", 1, 32, [](Params& p) {
            p.occluders = Occluders::solids;
            p.sprite_shading = SpriteShading::solids;
        });
        for (auto _ : st) step(*s, 32);
    })->Unit(benchmark::kMillisecond);
    // Beyond the paper: the blur within the surfaces the view shows (occluders
    // solids or shapes), radius 2, grey.
    benchmark::RegisterBenchmark("stage/blur_within/radius:2", [](benchmark::State& st) {
        ScreenScene& s = screen("default", 1);
        const Surface surface = build_surface(*s.world, s.frame.traced.rect, s.scene.params.opacity_threshold);
        SurfaceIds ids{s.frame.traced.rect, surface.instance, {}};
        index_surfaces(ids);
        LightTexture out(s.frame.traced.rect, s.frame.traced.channels);
        for (auto _ : st) box_blur_within_into(s.frame.traced, 2, ids, s.frame.traced.rect, out);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("stage/composite", [](benchmark::State& st) {
        ScreenScene& s = screen("default", 1);
        Image out(s.frame.view.w, s.frame.view.h);
        for (auto _ : st)
            composite_into(s.frame.sprites, s.frame.view, s.frame.cache->blurred, s.scene.params, s.frame.view, out);
    })->Unit(benchmark::kMillisecond);
    // The same composite over the whole view in vertical strips: the same
    // pixels in shorter pieces of rows (what the frame's join_gap is for).
    for (int strip : {1920, 960, 480})
        benchmark::RegisterBenchmark(("stage/composite_strips/" + std::to_string(strip)).c_str(), [strip](benchmark::State& st) {
            ScreenScene& s = screen("default", 1);
            Image out(s.frame.view.w, s.frame.view.h);
            const Rect v = s.frame.view;
            for (auto _ : st)
                for (int x = 0; x < v.w; x += strip)
                    composite_into(s.frame.sprites, v, s.frame.cache->blurred, s.scene.params,
                                   Rect{v.x + x, v.y, std::min(strip, v.w - x), v.h}, out);
        })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("stage/correction/forest", [](benchmark::State& st) {
        ScreenScene& s = screen("forest", 1);
        std::vector<LightMask> masks = traced_masks(s);
        for (auto _ : st)
            for (LightMask& m : masks) correct_with_ground_lines(m, s.frame.cache->ground);
    })->Unit(benchmark::kMillisecond);
    // The same, each mask corrected 8 times in a row (its lines and mask then
    // come from L2, not L3): per pass, time / 8. As fast as the cold one
    // when the pass is bound by its work per row, not by memory.
    benchmark::RegisterBenchmark("stage/correction_8_in_a_row/forest", [](benchmark::State& st) {
        ScreenScene& s = screen("forest", 1);
        std::vector<LightMask> masks = traced_masks(s);
        for (auto _ : st)
            for (LightMask& m : masks)
                for (int i = 0; i < 8; ++i) correct_with_ground_lines(m, s.frame.cache->ground);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("stage/correction_reference/forest", [](benchmark::State& st) {
        ScreenScene& s = screen("forest", 1);
        std::vector<LightMask> masks = traced_masks(s);
        for (auto _ : st)
            for (LightMask& m : masks) correct_with_opacity_maps(m, s.world->placed, s.frame.opacity);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("stage/floor/memcpy_traced", [](benchmark::State& st) {
        Copy copy(screen("default", 1).frame.traced.texels.size());
        for (auto _ : st) copy();
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("stage/floor/memset_forest_areas", [](benchmark::State& st) {
        Set set(area_bytes(screen("forest", 1)));
        for (auto _ : st) set();
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("stage/floor/correction_streams/forest", [](benchmark::State& st) {
        ScreenScene& s = screen("forest", 1);
        std::vector<LightMask> masks = traced_masks(s);
        const CorrectionStreams streams{s.frame.cache->ground, masks};
        for (auto _ : st) streams();
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("whole_frame/floor/memcpy_final_memset_areas", [](benchmark::State& st) {
        ScreenScene& s = screen("default", 1);
        Copy copy(s.frame.final.rgba.size());
        Set set(area_bytes(s));
        for (auto _ : st) copy(), set();
    })->Unit(benchmark::kMillisecond)->UseRealTime();
}

void print_solids_frame_ratios(int pairs) {
    // Beyond the paper: the whole CPU frame (every light moved) with solids
    // over the same frame with the paper's footprints, the same threads.
    {
        auto solids = [](Params& p) { p.occluders = Occluders::solids; };
        auto solids_frame = make_screen("default", 1, 32, solids), footprints_frame = make_screen("default", 1, 32);
        print_ratio("solids_frame_cost",
                    interleaved([&] { step(*solids_frame, 32); }, 1, [&] { step(*footprints_frame, 32); }, 3, pairs),
                    "<= 5", 2);
    }

    // Beyond the paper: the occluders at half resolution (occluder_scale 2):
    // the whole CPU frame with solids so, over the same frame with
    // footprints (solids_frame_cost's measure), and over the solids frame
    // at full resolution (what the knob saves).
    {
        auto solids = [](Params& p) { p.occluders = Occluders::solids; };
        auto half = [](Params& p) {
            p.occluders = Occluders::solids;
            p.occluder_scale = 2;
        };
        auto half_frame = make_screen("default", 1, 32, half), full_frame = make_screen("default", 1, 32, solids),
             footprints_frame = make_screen("default", 1, 32);
        print_ratio("solids_frame_cost_scale2",
                    interleaved([&] { step(*half_frame, 32); }, 1, [&] { step(*footprints_frame, 32); }, 3, pairs),
                    nullptr, 2);
        print_ratio("occluder_scale2_over_full",
                    interleaved([&] { step(*half_frame, 32); }, 1, [&] { step(*full_frame, 32); }, 1, pairs), nullptr, 3);
    }
}

std::vector<double> solids_frame_thread_ms(const LightTracer& tracer, int frames, bool& same) {
    auto solids = [](Params& p) { p.occluders = Occluders::solids; };
    auto gpu = make_screen("default", 1, 32, solids), cpu = make_screen("default", 1, 32, solids);
    gpu->frame.options.tracer = tracer;
    gpu->frame.options.cpu_sprites = gpu->frame.options.cpu_blur_and_composite = false;
    auto thread_ms = [] {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
    };
    std::vector<double> ms;
    same = true;
    step(*gpu, 32);  // warm: the occluder map uploaded
    step(*cpu, 32);
    for (int i = 0; i < frames; ++i) {
        const double t0 = thread_ms();
        const FrameReport rep = step(*gpu, 32);
        ms.push_back(thread_ms() - t0);
        step(*cpu, 32);
        same = same && rep.tracer == "gpu" && gpu->frame.traced.texels == cpu->frame.traced.texels;
    }
    return ms;
}

void print_floor_ratios() {
    ScreenScene& one = screen("default", 1);
    ScreenScene& two = screen("default", 2);
    ScreenScene& forest = screen("forest", 1);
    const int pairs = 11;

    Copy final_copy(one.frame.final.rgba.size());
    Set areas_set(area_bytes(one));
    print_ratio("frame_times_floor", interleaved([&] { step(one, 32); }, 3, [&] { final_copy(), areas_set(); }, 30, pairs),
                "<= 12", 2);

    // Each stage alone, one thread, into the buffer the frame keeps.
    const LightTexture& traced = one.frame.traced;
    LightTexture blurred(traced.rect);
    Copy traced_copy(traced.texels.size());
    print_ratio("blur_times_floor",
                interleaved([&] { box_blur_into(traced, 2, traced.rect, blurred); }, 5, traced_copy, 30, pairs), "<= 4",
                2);

    // The baseline build of the blur over its AVX2 build (base/cpu.hpp), when the CPU has AVX2.
    if (wide_kernels()) {
        auto baseline = [&] {
            set_wide_kernels(false);
            box_blur_into(traced, 2, traced.rect, blurred);
            set_wide_kernels(true);
        };
        print_ratio("blur_avx2_speedup",
                    interleaved(baseline, 5, [&] { box_blur_into(traced, 2, traced.rect, blurred); }, 5, pairs), nullptr, 2);
    }

    // Beyond the paper: the blur within surfaces (occluders solids or shapes)
    // over the plain blur, the same texture, the surfaces the view shows.
    const Surface surface = build_surface(*one.world, traced.rect, one.scene.params.opacity_threshold);
    SurfaceIds ids{traced.rect, surface.instance, {}};
    index_surfaces(ids);
    print_ratio("blur_within_cost",
                interleaved([&] { box_blur_within_into(traced, 2, ids, traced.rect, blurred); }, 2,
                            [&] { box_blur_into(traced, 2, traced.rect, blurred); }, 5, pairs),
                "<= 6", 2);

    // The composite reads the view's sprites (RGBA) and the light at the view
    // (grey here, the frame's lights being white: one byte a texel).
    const Rect view = one.frame.view;
    Copy composite_copy(std::size_t(view.w) * view.h * std::size_t(4 + blurred.channels));
    Image out(view.w, view.h);
    print_ratio("composite_times_floor", interleaved([&] {
                    composite_into(one.frame.sprites, view, blurred, one.scene.params, view, out);
                }, 5, composite_copy, 30, pairs), "<= 4", 2);
    // Beyond the paper: tone_map reinhard_knee's composite over the clamp's
    // (its light scaled into the headroom: a few more float steps a pixel).
    Params toned = one.scene.params;
    toned.tone_map = ToneMap::reinhard_knee;
    print_ratio("composite_tone_knee_cost", interleaved([&] {
                    composite_into(one.frame.sprites, view, blurred, toned, view, out);
                }, 5, [&] { composite_into(one.frame.sprites, view, blurred, one.scene.params, view, out); }, 5, pairs),
                nullptr, 2);

    // The correction of the forest's 32 lights, on their traced masks, in
    // place as the frame does it. The correction is idempotent (each pixel
    // kept, set to its falloff or cleared by the ground lines alone), so
    // correcting the same masks again does the same work on the same bytes.
    std::vector<LightMask> masks = traced_masks(forest);
    Set forest_areas(area_bytes(forest));
    print_ratio("correction_times_floor", interleaved([&] {
                    for (LightMask& m : masks)
                        correct_with_ground_lines(m, forest.frame.cache->ground);
                }, 3, forest_areas, 30, pairs), "<= 4", 2);
    // The same areas' bytes read and written as the correction moves them, with no rule.
    std::vector<LightMask> stream_masks = traced_masks(forest);
    const CorrectionStreams streams{forest.frame.cache->ground, stream_masks};
    print_ratio("correction_streams_times_floor", interleaved(streams, 3, forest_areas, 30, pairs), nullptr, 2);

    print_ratio("threads2_frame_speedup", interleaved([&] { step(one, 32); }, 3, [&] { step(two, 32); }, 3, pairs),
                ">= 1.6", 2);
    print_ratio("one_light_moved_cost", interleaved([&] { step(one, 1); }, 10, [&] { step(one, 32); }, 3, pairs),
                "<= 0.1", 3);

    // Beyond the paper: one hand edit's occluder-map update with solids (the
    // edit's reach filled, the sprite index listed anew in its columns only)
    // over a full rebuild of the same region: the whole-frame view and its
    // lights' margin, the sprites' solids estimated once (warm in both). The
    // edit puts a tree on the tile at the map's centre, then takes it away.
    {
        World w = *one.world;
        Params p = one.scene.params;
        p.occluders = Occluders::solids;
        const Rect region{int(one.camera.x) - 256, int(one.camera.y) - 256, one.camera.width + 512, one.camera.height + 512};
        SolidsCache cache;
        OccluderMap edited = build_occluders(w, p, region, &cache), rebuilt;
        const int reach = occluder_reach(w.tileset), tree = w.tileset.find(SpriteKind::overlay, "tree").front();
        const int col = w.map.width / 2, row = w.map.height / 2, floor = w.map.at(col, row).floor;
        bool planted = false;
        auto seconds = [](auto&& work) {
            const auto t0 = std::chrono::steady_clock::now();
            work();
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        };
        auto edit = [&] {
            planted = !planted;
            const Rect c = set_tile(w, col, row, floor, planted ? std::vector<int>{tree} : std::vector<int>{});
            const Rect around{c.x - reach, c.y - reach, c.w + 2 * reach, c.h + 2 * reach};
            return seconds([&] { update_occluders(edited, w, p, region, around, &cache); });
        };
        auto rebuild = [&] { return seconds([&] { rebuild_occluders(rebuilt, w, p, region, &cache); }); };
        print_ratio("solids_edit_cost", interleaved_costs(edit, rebuild, pairs), "<= 0.05", 3);

        // The same edit at occluder_scale 2: the coarse map and its picks
        // updated over the edit's part, over both made whole from the
        // edited map.
        OccluderMap coarse = coarse_occluders(edited, 2), whole;
        std::vector<std::uint8_t> picks = coarse_picks(edited.surface, coarse, 2), whole_picks;
        auto edit_coarse = [&] {
            planted = !planted;
            const Rect c = set_tile(w, col, row, floor, planted ? std::vector<int>{tree} : std::vector<int>{});
            const Rect around{c.x - reach, c.y - reach, c.w + 2 * reach, c.h + 2 * reach};
            update_occluders(edited, w, p, region, around, &cache);
            return seconds([&] { edit_coarse_occluders(coarse, picks, edited, around, 2); });
        };
        auto coarse_whole = [&] {
            return seconds([&] {
                whole = coarse_occluders(edited, 2);
                whole_picks = coarse_picks(edited.surface, whole, 2);
            });
        };
        print_ratio("solids_edit_cost_scale2", interleaved_costs(edit_coarse, coarse_whole, pairs), nullptr, 3);
    }

    print_solids_frame_ratios(pairs);

    // Beyond the paper: the whole frame with solids, its sprites shaded by
    // the solids' normals, over the same frame unshaded (every light moved).
    {
        auto solids = [](Params& p) { p.occluders = Occluders::solids; };
        auto shaded = [](Params& p) {
            p.occluders = Occluders::solids;
            p.sprite_shading = SpriteShading::solids;
        };
        auto flat_frame = make_screen("default", 1, 32, solids), shaded_frame = make_screen("default", 1, 32, shaded);
        print_ratio("sprite_shading_cost",
                    interleaved([&] { step(*shaded_frame, 32); }, 2, [&] { step(*flat_frame, 32); }, 2, pairs), "<= 1.1",
                    3);
    }
}

}  // namespace isolux::bench
