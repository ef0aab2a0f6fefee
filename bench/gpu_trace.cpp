#include "gpu_trace.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "gpu/gpu_tracer.hpp"
#include "gui/window.hpp"
#include "ratio.hpp"
#include "scenes.hpp"
#include "whole_frame.hpp"

namespace isolux::bench {

void print_gpu_figures() {
    std::string error;
    GLFWwindow* window = app::open_window(64, 64, false, error);
    app::GpuTracer tracer;
    if (!window || !app::gpu_tracer_init(tracer, error)) {
        std::printf("gpu_trace_identical unavailable: %s (run under xvfb-run, as the GL tests are)\n", error.c_str());
        return;
    }
    // Every benchmark scene and area, k = 1 and k = 4, light and shadow modes.
    bool identical = true;
    int compared = 0;
    std::uint64_t revision = 0;
    for (const char* name : {"empty", "default", "forest", "corridors"}) {
        const TraceScene& s = trace_scene(name);
        ++revision;
        for (int a : {64, 128, 256})
            for (int k : {1, 4})
                for (Mode mode : {Mode::light, Mode::shadow}) {
                    Params p;
                    p.ray_skip = k;
                    p.mode = mode;
                    const Rect area{s.cx - a, s.cy - a, 2 * a + 1, 2 * a + 1};
                    const LightMask want = trace_light(s.obstacles, s.cx, s.cy, a, a, p, area);
                    LightMask got;
                    got.clip = area, got.cx = s.cx, got.cy = s.cy, got.a = a, got.b = a;
                    got.value.assign(want.value.size(), 0);
                    got.reached.assign(want.reached.size(), 0);
                    std::vector<LightMask*> masks{&got};
                    identical = identical && app::gpu_trace(tracer, s.obstacles, revision, masks, p) &&
                                got.value == want.value && got.reached == want.reached;
                    ++compared;
                }
    }
    // Against solids with height: estimated and the manifest's shapes, on the default map.
    const World& w = world("default", 24);
    int against_solids = 0;
    for (Occluders kind : {Occluders::solids, Occluders::shapes}) {
        Params base;
        base.occluders = kind;
        const OccluderMap occ = build_occluders(w, base, w.placed.bounds);
        ++revision;
        const std::int64_t cx = w.placed.bounds.x + w.placed.bounds.w / 2, cy = w.placed.bounds.y + w.placed.bounds.h / 2;
        for (int a : {64, 128})
            for (int k : {1, 4})
                for (Mode mode : {Mode::light, Mode::shadow}) {
                    Params p = base;
                    p.ray_skip = k;
                    p.mode = mode;
                    const Rect area{int(cx) - a, int(cy) - a, 2 * a + 1, 2 * a + 1};
                    LightMask want = trace_light_solids(occ, cx, cy, a, a, 32, p, area);
                    light_sprite_points(want, occ, 32, p);
                    LightMask got;
                    start_mask(got, cx, cy, a, a, p, area, mode == Mode::shadow);
                    std::vector<LightMask*> masks{&got};
                    identical = identical && app::gpu_trace_solids(tracer, occ, revision, masks, {32.0}, p, true) &&
                                got.value == want.value && got.reached == want.reached;
                    ++against_solids;
                }
    }
    std::printf("gpu_trace_identical %d (%d traces: 4 scenes, 3 areas, k = 1 and 4, light and shadow; and %d against "
                "solids and shapes (both passes), 2 areas, k = 1 and 4, light and shadow; on %s)\n",
                identical ? 1 : 0, compared, against_solids, tracer.renderer.c_str());
    // One 257^2 light on the default map, the GPU (upload, dispatch, read back) over the CPU.
    const TraceScene& s = trace_scene("default");
    Params p;
    const Rect area{s.cx - 128, s.cy - 128, 257, 257};
    LightMask m;
    m.clip = area, m.cx = s.cx, m.cy = s.cy, m.a = m.b = 128;
    m.value.assign(std::size_t(257) * 257, 0);
    std::vector<LightMask*> masks{&m};
    LightMask cpu;
    print_ratio("gpu_trace_over_cpu", interleaved([&] { app::gpu_trace(tracer, s.obstacles, revision, masks, p); }, 5,
                                                  [&] { cpu = trace_light(s.obstacles, s.cx, s.cy, 128, 128, p, area); },
                                                  5, 7),
                nullptr, 2);
    // The app's frame against solids on the GPU path: what it leaves the calling thread.
    bool same = false;
    std::vector<double> ms = solids_frame_thread_ms(
        [&](const Mask& obstacles, std::uint64_t rev, const OccluderMap* occ, const std::vector<LightMask*>& m,
            const std::vector<double>& heights, const Params& q, bool sprite_points) {
            return app::gpu_trace_frame(tracer, obstacles, rev, occ, m, heights, q, sprite_points);
        },
        11, same);
    std::sort(ms.begin(), ms.end());
    std::printf("solids_gpu_cpu_ms %.2f (median of %zu frames of 32 moving lights against solids on the GPU path, "
                "the calling thread's CPU clock, spread %.2f-%.2f; target < 1); its light texture the CPU's: %d\n",
                ms[ms.size() / 2], ms.size(), ms.front(), ms.back(), same ? 1 : 0);
    app::gpu_tracer_free(tracer);
    glfwDestroyWindow(window);
}

}  // namespace isolux::bench
