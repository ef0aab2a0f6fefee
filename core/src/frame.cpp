// Paper Figure 4: the overall steps, once per frame, each only when needed.
#include "isolux/frame.hpp"

#include <algorithm>
#include <cmath>
#include <atomic>
#include <barrier>
#include <cstring>
#include <thread>

#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/opacity_map.hpp"

namespace isolux {

std::string_view to_string(Stage s) {
    switch (s) {
        case Stage::sprites: return "sprites";
        case Stage::obstacle_map: return "obstacle_map";
        case Stage::trace: return "trace";
        case Stage::opacity_correction: return "opacity_correction";
        case Stage::blur: return "blur";
        case Stage::shift: return "shift";
        case Stage::composite: return "composite";
    }
    return "?";
}

Rect camera_view(const Camera& c, const World& w) {
    const double x = std::clamp(std::floor(c.x), -1e9, 1e9), y = std::clamp(std::floor(c.y), -1e9, 1e9);
    const int width = c.width > 0 ? c.width : w.placed.bounds.w;
    const int height = c.height > 0 ? c.height : w.placed.bounds.h;
    return {int(x), int(y), width, height};
}

namespace {

using Clock = std::chrono::steady_clock;

struct Timer {
    FrameReport& report;
    Stage stage;
    Clock::time_point start = Clock::now();
    ~Timer() {
        report.ran[int(stage)] = true;
        report.ms[int(stage)] += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    }
};

Rect grow(Rect r, int by) { return {r.x - by, r.y - by, r.w + 2 * by, r.h + 2 * by}; }

bool covers(Rect outer, Rect inner) { return intersect(outer, inner) == inner; }

Rect bounding(Rect a, Rect b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    const int x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
    const int x1 = std::max(a.x + a.w, b.x + b.w), y1 = std::max(a.y + a.h, b.y + b.h);
    return {x0, y0, x1 - x0, y1 - y0};
}

bool same_obstacle_params(const Params& a, const Params& b) {
    return a.delta_y == b.delta_y && a.noise_window == b.noise_window && a.opacity_threshold == b.opacity_threshold;
}

bool same_trace_params(const Params& a, const Params& b) {
    return a.area_a == b.area_a && a.area_b == b.area_b && a.ray_skip == b.ray_skip && a.rays == b.rays &&
           a.mode == b.mode && a.falloff_scale == b.falloff_scale;
}

bool same_composite_params(const Params& a, const Params& b) {
    return a.ambient_clarity == b.ambient_clarity && a.dark_unlit == b.dark_unlit && a.mode == b.mode;
}

}  // namespace

FrameReport render_frame(FrameState& st, const World& world, const Scene& scene, const Camera& camera, long frame) {
    FrameReport rep;
    const Params& p = scene.params;
    const Rect view = camera_view(camera, world);
    const bool world_changed = st.world_revision != world.revision;

    // The view's sprites (drawn by the GPU in the app).
    if (st.options.cpu_sprites && (world_changed || !(st.view == view) || st.sprites.width != view.w)) {
        Timer t{rep, Stage::sprites};
        st.sprites = render_sprites(world.tileset, world.placed, view);
    }

    // Which lights could light the texture, and the obstacles their rays cross.
    const Rect tex_rect = grow(view, st.options.margin);
    Rect needed = tex_rect;
    for (const Light& l : scene.lights) {
        const Rect area = light_area(l, p);
        if (!intersect(area, tex_rect).empty()) needed = bounding(needed, area);
    }
    needed = intersect(needed, world.placed.bounds);

    // The obstacle map's content changes only with the world, Δy, n or the
    // threshold; a larger region is the same map over more pixels (the build
    // is exact per region), so it alone does not force a retrace.
    const bool obstacles_changed = world_changed || !st.has_obstacles || !same_obstacle_params(st.obstacle_params, p);
    if (obstacles_changed || !covers(st.obstacle_region, needed)) {
        Timer t{rep, Stage::obstacle_map};
        // Some room around what is needed, so a panning camera does not
        // rebuild every frame; never more than the map.
        st.obstacle_region = needed.empty() ? needed : intersect(grow(needed, 256), world.placed.bounds);
        st.obstacles = build_obstacle_map(world.tileset, world.placed, p, st.obstacle_region);
        st.opacity.clear();
        for (const Sprite& s : world.tileset.sprites)
            st.opacity.push_back(opacity_map(s.image, sprite_threshold(s, p.opacity_threshold)));
        st.obstacle_params = p;
        st.world_revision = world.revision;
        st.has_obstacles = true;
    }

    const bool must = !st.has_trace || obstacles_changed || !same_trace_params(st.trace_params, p) ||
                      st.cache_corrected != st.options.opacity_correction;
    const bool due = frame % p.trace_every == 0 &&
                     (st.trace_lights != scene.lights || !covers(st.traced.rect, view));
    const bool retrace = must || due;
    if (retrace) {
        // Reuse the texture: only the rectangles lights drew into last time
        // hold anything to clear (in the bands below, in parallel).
        std::vector<Rect> to_clear;
        if (!(st.traced.rect == tex_rect) || st.traced.rgb.size() != std::size_t(tex_rect.w) * tex_rect.h * 3) {
            st.traced = LightTexture(tex_rect);
        } else {
            for (const FrameState::TracedLight& c : st.light_cache) to_clear.push_back(c.mask.clip);
        }
        const bool had_lights = !st.light_cache.empty();
        const bool new_texture = to_clear.empty() && !(had_lights && st.traced.rect == tex_rect);
        if (must) st.light_cache.clear();  // obstacles or tracing parameters changed: nothing is reusable
        // The lights whose area meets the texture; the others have nothing to trace.
        std::vector<const Light*> lights;
        for (const Light& l : scene.lights)
            if (!intersect(light_area(l, p), tex_rect).empty()) lights.push_back(&l);
        std::vector<FrameState::TracedLight> traced(lights.size());
        std::vector<std::size_t> todo;
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const Light& l = *lights[i];
            FrameState::TracedLight& t = traced[i];
            t.cx = std::int64_t(std::floor(l.x));
            t.cy = std::int64_t(std::floor(l.y));
            t.a = light_a(l, p);
            t.b = light_b(l, p);
            const Rect clip = intersect(light_area(l, p), tex_rect);
            auto same = [&](const FrameState::TracedLight& c) {
                return c.cx == t.cx && c.cy == t.cy && c.a == t.a && c.b == t.b && c.mask.clip == clip;
            };
            // Lights mostly keep their place in the list: look there first.
            const FrameState::TracedLight* hit = nullptr;
            if (i < st.light_cache.size() && same(st.light_cache[i])) hit = &st.light_cache[i];
            for (std::size_t j = 0; !hit && j < st.light_cache.size(); ++j)
                if (same(st.light_cache[j])) hit = &st.light_cache[j];
            if (hit) {
                t.mask = hit->mask;
                ++rep.lights_reused;
            } else {
                t.mask.clip = clip;
                todo.push_back(i);
            }
        }
        const int threads_wanted = st.options.threads > 0 ? st.options.threads
                                                          : std::max(1, int(std::thread::hardware_concurrency()));
        // One pass per light: trace, then the opacity correction. Workers take
        // the next light as they finish one (lights differ in cost).
        const bool correct = st.options.opacity_correction && p.mode != Mode::flat;
        std::vector<double> trace_ms(todo.size(), 0), correct_ms(todo.size(), 0);
        std::vector<int> touched(todo.size(), 0);
        std::atomic<std::size_t> next{0};
        auto worker = [&] {
            for (std::size_t k; (k = next++) < todo.size();) {
                FrameState::TracedLight& tl = traced[todo[k]];
                const auto t0 = Clock::now();
                const Rect area{int(tl.cx) - tl.a, int(tl.cy) - tl.b, 2 * tl.a + 1, 2 * tl.b + 1};
                tl.mask = trace_light(st.obstacles, tl.cx, tl.cy, tl.a, tl.b, p, tl.mask.clip,
                                      area_is_clear(st.obstacles, area));
                const auto t1 = Clock::now();
                if (correct) touched[k] = correct_with_opacity_maps(tl.mask, world.placed, st.opacity);
                trace_ms[k] = std::chrono::duration<double, std::milli>(t1 - t0).count();
                correct_ms[k] = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
            }
        };
        // Then the lights are drawn into the light texture (part of
        // tracing): workers take bands of rows. The saturating sum is the
        // same in any order, so the bytes do not depend on the split. One set
        // of threads does both, meeting at a barrier in between.
        // More bands than threads, taken as threads come free: lights are not
        // spread evenly over the rows.
        const int bands = std::max(1, std::min(threads_wanted * 8, tex_rect.h / 32));
        std::atomic<int> next_band{0};
        auto band = [&](int k) {
            const int y0 = tex_rect.y + int(std::int64_t(tex_rect.h) * k / bands);
            const int y1 = tex_rect.y + int(std::int64_t(tex_rect.h) * (k + 1) / bands);
            for (const Rect& c : to_clear) {
                const Rect z = intersect(intersect(c, tex_rect), Rect{tex_rect.x, y0, tex_rect.w, y1 - y0});
                for (int y = z.y; y < z.y + z.h; ++y)
                    std::memset(&st.traced.rgb[(std::size_t(y - tex_rect.y) * tex_rect.w + (z.x - tex_rect.x)) * 3], 0,
                                std::size_t(z.w) * 3);
            }
            for (std::size_t i = 0; i < lights.size(); ++i)
                accumulate_light(st.traced, traced[i].mask, *lights[i], p, y0, y1);
        };
        // Threads only when there is enough work to pay for starting them.
        long work = 0;
        for (std::size_t k : todo) work += long(traced[k].mask.clip.w) * traced[k].mask.clip.h * 2;
        for (const FrameState::TracedLight& t : traced) work += long(t.mask.clip.w) * t.mask.clip.h;
        const int pool_size =
            work < 200000 ? 1 : std::max(1, std::min(threads_wanted, std::max(int(todo.size()), bands)));
        const auto t0 = Clock::now();
        Clock::time_point t_traced;
        std::barrier sync(pool_size, [&]() noexcept { t_traced = Clock::now(); });
        auto run = [&] {
            worker();
            sync.arrive_and_wait();
            for (int k; (k = next_band++) < bands;) band(k);
        };
        std::vector<std::thread> pool;
        for (int id = 1; id < pool_size; ++id) pool.emplace_back(run);
        run();
        for (std::thread& th : pool) th.join();
        const auto t_done = Clock::now();
        if (!todo.empty()) {
            // Wall time, split between the two stages in proportion to their work.
            const double wall = std::chrono::duration<double, std::milli>(t_traced - t0).count();
            double tr = 0, co = 0;
            for (std::size_t k = 0; k < todo.size(); ++k) tr += trace_ms[k], co += correct_ms[k];
            const double share = tr + co > 0 ? tr / (tr + co) : 1.0;
            rep.ms[int(Stage::trace)] += wall * share;
            if (correct) {
                rep.ran[int(Stage::opacity_correction)] = true;
                rep.ms[int(Stage::opacity_correction)] += wall * (1 - share);
            }
            rep.lights_traced = int(todo.size());
            for (int n : touched) rep.sprites_corrected += n;
        }
        rep.ran[int(Stage::trace)] = true;
        rep.ms[int(Stage::trace)] += std::chrono::duration<double, std::milli>(t_done - t_traced).count();
        // What changed: the areas of lights traced now and of lights gone or
        // moved since (all of it when the texture itself is new).
        Rect dirty;
        if (!had_lights && lights.empty()) dirty = Rect{};
        else if (new_texture || must) dirty = tex_rect;
        else {
            for (std::size_t k : todo) dirty = bounding(dirty, intersect(traced[k].mask.clip, tex_rect));
            for (const FrameState::TracedLight& old : st.light_cache) {
                bool kept = false;
                for (const FrameState::TracedLight& now : traced)
                    kept = kept || (now.cx == old.cx && now.cy == old.cy && now.a == old.a && now.b == old.b);
                if (!kept) dirty = bounding(dirty, intersect(old.mask.clip, tex_rect));
            }
            if (st.trace_lights.size() == scene.lights.size() && todo.empty() && dirty.empty()) {
                // Only colours or intensities changed: the lights' own areas.
                for (const FrameState::TracedLight& now : traced) dirty = bounding(dirty, intersect(now.mask.clip, tex_rect));
            }
        }
        rep.dirty = dirty;
        st.light_cache = std::move(traced);
        st.cache_corrected = st.options.opacity_correction;
        st.has_trace = true;
        st.trace_params = p;
        st.trace_lights = scene.lights;
        st.blurred_radius = -1;
        // No light now and none before: the texture stayed empty, nothing to
        // upload or blur again.
        rep.retraced = !dirty.empty();
        if (!rep.retraced) {
            rep.ran[int(Stage::trace)] = false;
            rep.ms[int(Stage::trace)] = 0;
            if (!(st.blurred.rect == st.traced.rect)) st.blurred = st.traced;  // all zero
            st.blurred_radius = p.blur_radius;
        }
    }
    if (!st.options.cpu_blur_and_composite) {
        st.view = view;
        return rep;
    }

    bool light_changed = false;
    if (st.blurred_radius != p.blur_radius) {
        if (p.blur_radius > 0) {
            Timer t{rep, Stage::blur};
            st.blurred = box_blur(st.traced, p.blur_radius);
        } else {
            st.blurred = st.traced;
        }
        st.blurred_radius = p.blur_radius;
        light_changed = true;
    }
    if (light_changed || !(st.light.rect == view)) {
        // Between retraces this is the paper's inverse translation: the
        // world-anchored texture read at the moved view.
        Timer t{rep, Stage::shift};
        st.light = shift_light_texture(st.blurred, view);
        light_changed = true;
    }

    if (light_changed || !st.has_final || !(st.view == view) || world_changed ||
        !same_composite_params(st.composite_params, p)) {
        Timer t{rep, Stage::composite};
        st.final = composite(st.sprites, view, st.light, p);
        st.composite_params = p;
        st.has_final = true;
    }
    st.view = view;
    return rep;
}

}  // namespace isolux
