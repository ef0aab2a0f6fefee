// Paper 3.2 and Algorithm 2 in the frame: which lights to trace, each
// traced and corrected, all summed into the light texture, and the trace
// kept for the frames that reuse it (frame_steps.hpp).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>

#include "frame/frame_steps.hpp"
#include "isolux/error.hpp"
#include "isolux/height_rays.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/sprite_shading.hpp"
#include "solids/solids_pass_tree.hpp"
#include "base/worker_pool.hpp"

namespace isolux::frame_steps {

namespace {

// The lights whose area meets the texture, each with its cached trace when
// one is still valid; `todo` lists those to trace now.
struct LightPlan {
    std::vector<const Light*> lights;
    std::vector<TracedLight> traced;  // by index in `lights`
    std::vector<std::size_t> todo;  // in the scene's order (trace_and_accumulate orders them by cost)
    std::vector<std::size_t> recoloured;  // reused masks whose colour or intensity changed
};

// A reused light's mask is moved out of the cache (copying 32 masks of 66 KB
// was most of a frame where one light moved): the cache keeps each light's
// place and clip for dirty_parts, and trace_step drops the cache if the
// frame does not finish.
LightPlan plan_lights(FrameCache& c, const Scene& scene, Rect tex_rect, Rect edited, FrameReport& rep) {
    const Params& p = scene.params;
    LightPlan plan;
    for (const Light& l : scene.lights)
        if (!intersect(light_area(l, p), tex_rect).empty()) plan.lights.push_back(&l);
    plan.traced.resize(plan.lights.size());
    std::vector<char> taken(c.lights.size(), 0);  // a mask moves out once (two lights may share a place)
    for (std::size_t i = 0; i < plan.lights.size(); ++i) {
        const Light& l = *plan.lights[i];
        TracedLight& t = plan.traced[i];
        t.cx = std::int64_t(std::floor(l.x));
        t.cy = std::int64_t(std::floor(l.y));
        t.a = light_a(l, p);
        t.b = light_b(l, p);
        t.height = p.rays_over_obstacles || p.occluders != Occluders::footprints || p.sprite_shading != SpriteShading::none
                       ? light_height(l, p)
                       : 0;
        t.colour = {l.r, l.g, l.b};
        t.intensity = l.intensity;
        // Against solids a clipped light still walks its whole area's rays
        // (solids_pass_tree.hpp), so where the trees reach it the light keeps
        // its whole area: a camera that moves then reuses it.
        const bool whole = p.occluders != Occluders::footprints && occluder_tree_extent(t.a, t.b, p);
        const Rect clip = whole ? light_area(l, p) : intersect(light_area(l, p), tex_rect);
        auto same = [&](const TracedLight& old) {
            return old.cx == t.cx && old.cy == t.cy && old.a == t.a && old.b == t.b && old.height == t.height &&
                   old.mask.clip == clip && intersect(old.mask.clip, edited).empty();
        };
        // Lights mostly keep their place in the list: look there first.
        std::size_t hit = c.lights.size();
        if (i < c.lights.size() && !taken[i] && same(c.lights[i])) hit = i;
        for (std::size_t j = 0; hit == c.lights.size() && j < c.lights.size(); ++j)
            if (!taken[j] && same(c.lights[j])) hit = j;
        if (hit < c.lights.size()) {
            taken[hit] = 1;
            const TracedLight& old = c.lights[hit];
            t.mask = std::move(c.lights[hit].mask);  // (its clip, a plain copy, stays behind for dirty_parts)
            ++rep.lights_reused;
            if (old.colour != t.colour || old.intensity != t.intensity)
                plan.recoloured.push_back(i);
            t.cost_ms = old.cost_ms;
        } else {
            t.mask.clip = clip;
            if (i < c.lights.size()) t.cost_ms = c.lights[i].cost_ms;  // most likely this light, moved
            plan.todo.push_back(i);
        }
    }
    // The lights to trace take the vectors of cached masks no light reuses:
    // their capacity, so that retracing allocates nothing and touches no
    // fresh page.
    std::size_t spare = 0;
    for (std::size_t i : plan.todo) {
        while (spare < c.lights.size() && taken[spare]) ++spare;
        if (spare == c.lights.size()) break;
        plan.traced[i].mask.value = std::move(c.lights[spare].mask.value);
        plan.traced[i].mask.reached = std::move(c.lights[spare].mask.reached);
        taken[spare++] = 1;
    }
    return plan;
}

// The light texture's channels for these lights: grey (1) when every one is
// grey and the options allow it, else r, g, b (3).
int texture_channels(const Scene& scene, const FrameOptions& options) {
    const bool grey = options.grey_when_lights_are &&
                      std::all_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) { return grey_light(l); });
    return grey ? 1 : 3;
}

// Reuses the light texture when it has the right rectangle and channels:
// only the areas lights drew into last time hold anything, and they are
// cleared in trace_and_accumulate. Returns those areas; `fresh` says the
// texture is new (every light is added again).
std::vector<Rect> prepare_texture(FrameState& st, Rect tex_rect, int channels, bool& fresh) {
    std::vector<Rect> to_clear;
    if (!(st.traced.rect == tex_rect) || st.traced.channels != channels ||
        st.traced.texels.size() != std::size_t(tex_rect.w) * tex_rect.h * std::size_t(channels)) {
        st.traced = LightTexture(tex_rect, channels);
    } else {
        for (const TracedLight& c : st.cache->lights) to_clear.push_back(c.mask.clip);
    }
    fresh = to_clear.empty() && !(!st.cache->lights.empty() && st.traced.rect == tex_rect && st.traced.channels == channels);
    return to_clear;
}

// Algorithm 2 for every light in plan.todo, the opacity correction on each,
// then every light drawn into the texture. One set of threads does both
// phases, meeting at a barrier in between: workers take the next light as
// they finish one (lights differ in cost), then bands of rows (lights are not
// spread evenly over the rows). The saturating sum is the same in any order,
// so the bytes do not depend on the thread count.
void trace_and_accumulate(FrameState& st, const World& world, const Params& p, LightPlan& plan,
                          const std::vector<Rect>& to_clear, Rect tex_rect, const Rect* redo, FrameReport& rep) {
    const int threads = threads_wanted(st.options);
    // Beyond the paper: solids with height stop the rays, and sprite pixels are
    // lit by the points they show, in place of the opacity correction.
    const bool solids = p.occluders != Occluders::footprints && p.mode != Mode::flat;
    const bool correct = st.options.opacity_correction && p.mode != Mode::flat;
    const bool over = p.rays_over_obstacles && p.mode != Mode::shadow && !solids;
    const std::size_t n = plan.todo.size();
    std::vector<double> trace_ms(n, 0), correct_ms(n, 0);
    // Beyond the paper: the occluders' resolution (occluder_map.hpp); the
    // coarse map is made here, once per obstacle map and scale.
    const int scale = solids ? p.occluder_scale : 1;
    if (scale > 1 && (st.coarse_of != st.obstacles_revision || st.coarse_scale != scale)) {
        const auto t0 = Clock::now();
        // After a pan of the map it was made from: updated in place (the
        // blocks the two regions share kept); after an edit, the edit's
        // blocks made again; else made whole.
        const FrameCache& c = *st.cache;
        const bool same_scale = st.coarse_scale == scale;
        if (same_scale && c.pan_to == st.obstacles_revision && c.pan_from == st.coarse_of && c.pan_from != 0)
            pan_coarse_occluders(st.coarse_occluders, st.coarse_picks, st.occluders, c.pan_from_rect, scale);
        else if (same_scale && c.edit_to == st.obstacles_revision && c.edit_from == st.coarse_of && c.edit_from != 0)
            edit_coarse_occluders(st.coarse_occluders, st.coarse_picks, st.occluders, c.edit_part, scale);
        else {
            st.coarse_occluders = coarse_occluders(st.occluders, scale);
            st.coarse_picks = coarse_picks(st.occluders.surface, st.coarse_occluders, scale);
        }
        st.coarse_of = st.obstacles_revision;
        st.coarse_scale = scale;
        st.coarse_revision = next_obstacles_revision();
        rep.ms[int(Stage::obstacle_map)] += ms_between(t0, Clock::now());
    }
    // The order threads take the lights in: the costliest first, so that a
    // cheap one last leaves the least time with one thread idle. A light's
    // cost is what it took last frame (lights move little between frames);
    // lights not timed yet come first, the largest first.
    std::vector<std::size_t> order = plan.todo;
    auto pixels = [&](std::size_t i) { return std::int64_t(plan.traced[i].mask.clip.w) * plan.traced[i].mask.clip.h; };
    auto cost = [&](std::size_t i) { return plan.traced[i].cost_ms > 0 ? plan.traced[i].cost_ms : HUGE_VAL; };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return cost(a) != cost(b) ? cost(a) > cost(b) : pixels(a) > pixels(b);
    });

    // Another tracer (the app's GPU) first, on this thread, when one is set.
    bool traced_elsewhere = false;
    if (st.options.tracer && !over && n > 0) {
        const auto t0 = Clock::now();
        std::vector<LightMask*> masks;
        std::vector<double> heights;
        for (std::size_t k : plan.todo) {
            TracedLight& tl = plan.traced[k];
            start_mask(tl.mask, tl.cx, tl.cy, tl.a, tl.b, p, tl.mask.clip, p.mode == Mode::shadow);
            masks.push_back(&tl.mask);
            heights.push_back(tl.height);
        }
        if (scale == 1) {
            rep.tracer = st.options.tracer(st.obstacles, st.obstacles_revision, solids ? &st.occluders : nullptr,
                                           masks, heights, p, solids && correct);
        } else {
            // The coarse lights over the coarse map, then each fine mask from its coarse one.
            const Params cp = coarse_params(p);
            std::vector<LightMask> coarse(masks.size());
            std::vector<LightMask*> coarse_masks;
            for (std::size_t i = 0; i < masks.size(); ++i) {
                start_coarse_mask(coarse[i], *masks[i], scale, cp);
                coarse_masks.push_back(&coarse[i]);
                heights[i] = std::max(heights[i], 0.0) / scale;
            }
            // (The revision names the coarse map: a tracer keeping a copy of it
            // sees a new one when the scale changes.)
            rep.tracer = st.options.tracer(st.obstacles, st.coarse_revision, &st.coarse_occluders, coarse_masks,
                                           heights, cp, correct);
            if (!rep.tracer.empty())
                for (std::size_t i = 0; i < masks.size(); ++i)
                    upsample_mask(*masks[i], coarse[i], scale, p, &st.occluders.surface, &st.coarse_picks);
        }
        traced_elsewhere = !rep.tracer.empty();
        if (traced_elsewhere) rep.ms[int(Stage::trace)] += ms_between(t0, Clock::now());
    }
    if (!traced_elsewhere && n > 0) rep.tracer = "cpu";

    const double dy_scale = falloff_dy_scale(p, world.tileset.tile_width, world.tileset.tile_height);
    const bool shade = shades_sprites(p);
    const TraceControl& control = st.options.control;
    const TraceControl* ctl = control.cancel || control.done ? &control : nullptr;
    // One light, its passes against solids walked on `light_threads` threads.
    auto trace_one = [&](std::size_t k, int light_threads) {
        TracedLight& tl = plan.traced[order[k]];
        const auto t0 = Clock::now();
        const Rect area{int(tl.cx) - tl.a, int(tl.cy) - tl.b, 2 * tl.a + 1, 2 * tl.b + 1};
        if (!over && !solids && !traced_elsewhere) {
            trace_light_into(tl.mask, st.obstacles, tl.cx, tl.cy, tl.a, tl.b, p, tl.mask.clip,
                             area_is_clear(st.obstacles, area), ctl);
        } else {
            if (solids && !traced_elsewhere && scale > 1) {  // beyond the paper: both passes over the coarse map
                start_mask(tl.mask, tl.cx, tl.cy, tl.a, tl.b, p, tl.mask.clip, p.mode == Mode::shadow);
                trace_solids_at_scale(tl.mask, st.coarse_occluders, scale, tl.height, p, correct, light_threads,
                                      &st.occluders.surface, &st.coarse_picks);
            } else if (solids && !traced_elsewhere)  // beyond the paper: solids with height
                tl.mask = trace_light_solids(st.occluders, tl.cx, tl.cy, tl.a, tl.b, tl.height, p, tl.mask.clip,
                                             light_threads);
            else if (over)  // beyond the paper: rays over low obstacles
                tl.mask = trace_light_over(st.obstacles, st.obstacle_heights, tl.cx, tl.cy, tl.a, tl.b, tl.height,
                                           p, tl.mask.clip);
            control.add(std::int64_t(light_trace_work(tl.a, tl.b, p)));  // progress by whole lights here
        }
        const auto t1 = Clock::now();
        // With solids the sprite pass (unless another tracer took it with
        // its rays); else the ground lines when every sprite's ground fits
        // them, the reference otherwise.
        if (correct && solids) {
            if (!traced_elsewhere && scale == 1) light_sprite_points(tl.mask, st.occluders, tl.height, p, light_threads);
        } else if (correct && st.cache->ground.exact)
            correct_with_ground_lines(tl.mask, st.cache->ground);
        else if (correct)
            correct_with_opacity_maps(tl.mask, world.placed, st.opacity);
        // Beyond the paper: round lights, distances on the ground, a fade to the border.
        tl.mask.dy_scale = dy_scale;
        if (shaped(p)) shape_light(tl.mask, p);
        // Beyond the paper: sprite pixels turned from the light get less of it.
        if (shade) shade_sprites(tl.mask, st.shading, tl.height, p);
        trace_ms[k] = ms_between(t0, t1);
        correct_ms[k] = ms_between(t1, Clock::now());
        tl.cost_ms = trace_ms[k] + correct_ms[k];
    };
    // Fewer lights against solids than threads: each light's rays spread
    // over all of them, one light after another, rather than threads idle
    // beside a light that takes long.
    const bool split_lights = solids && !traced_elsewhere && n > 0 && int(n) < threads;
    std::atomic<std::size_t> next_light{0};
    auto trace_lights = [&] {
        if (split_lights) return;
        for (std::size_t k; (k = next_light++) < n;) {
            if (control.cancelled()) break;
            trace_one(k, 1);
        }
    };
    const int bands = std::max(1, std::min(threads * 8, tex_rect.h / 32));
    std::atomic<int> next_band{0};
    // Only where lights changed (`redo`), when the rest of the texture still
    // holds the sum of unchanged lights; everything they covered otherwise.
    // (Each texel once: lights' areas overlap.)
    const std::vector<Rect> clear = redo ? std::vector<Rect>{*redo} : disjoint_union(to_clear);
    const std::size_t texel = std::size_t(st.traced.channels);
    auto accumulate_band = [&](int k) {
        const int y0 = tex_rect.y + int(std::int64_t(tex_rect.h) * k / bands);
        const int y1 = tex_rect.y + int(std::int64_t(tex_rect.h) * (k + 1) / bands);
        for (const Rect& c : clear) {
            const Rect z = intersect(intersect(c, tex_rect), Rect{tex_rect.x, y0, tex_rect.w, y1 - y0});
            for (int y = z.y; y < z.y + z.h; ++y)
                std::memset(&st.traced.texels[(std::size_t(y - tex_rect.y) * tex_rect.w + (z.x - tex_rect.x)) * texel], 0,
                            std::size_t(z.w) * texel);
        }
        for (std::size_t i = 0; i < plan.lights.size(); ++i)
            accumulate_light(st.traced, plan.traced[i].mask, *plan.lights[i], p, y0, y1, redo);
    };

    // Threads only when there is enough work to pay for starting them.
    long work = 0;
    for (std::size_t k : plan.todo) work += long(plan.traced[k].mask.clip.w) * plan.traced[k].mask.clip.h * 2;
    for (const TracedLight& t : plan.traced) {
        const Rect c = redo ? intersect(t.mask.clip, *redo) : t.mask.clip;
        work += long(c.w) * c.h;
    }
    const int pool_size = work < 200000 ? 1 : std::max(1, std::min(threads, std::max(int(n), bands)));
    const auto t0 = Clock::now();
    for (std::size_t k = 0; split_lights && k < n && !control.cancelled(); ++k) trace_one(k, threads);
    Clock::time_point t_traced;
    const std::function<void()> traced_all = [&] { t_traced = Clock::now(); };
    PhaseBarrier sync(pool_size, traced_all);
    auto run = [&] {
        trace_lights();
        sync.arrive_and_wait();
        if (control.cancelled()) return;  // the masks are incomplete: render_frame throws them away
        for (int k; (k = next_band++) < bands;) accumulate_band(k);
    };
    run_on_threads(pool_size, run);
    const auto t_done = Clock::now();

    if (n > 0) {
        // Wall time, split between the two stages in proportion to their work.
        const double wall = ms_between(t0, t_traced);
        double tr = 0, co = 0;
        for (std::size_t k = 0; k < n; ++k) tr += trace_ms[k], co += correct_ms[k];
        const double share = tr + co > 0 ? tr / (tr + co) : 1.0;
        rep.ms[int(Stage::trace)] += wall * share;
        if (correct) {
            rep.ran[int(Stage::opacity_correction)] = true;
            rep.ms[int(Stage::opacity_correction)] += wall * (1 - share);
        }
        rep.lights_traced = int(n);
        std::vector<Rect> traced;
        for (std::size_t k : plan.todo) traced.push_back(plan.traced[k].mask.clip);
        traced = disjoint_union(std::move(traced));
        if (correct) touch(rep, Stage::opacity_correction, traced);
        touch(rep, Stage::trace, std::move(traced));
    }
    rep.ran[int(Stage::trace)] = true;
    rep.ms[int(Stage::trace)] += ms_between(t_traced, t_done);
}

// What changed in the texture, as disjoint rectangles: the areas of lights
// traced now, of lights gone or moved since, and of lights whose colour or
// intensity changed (all of it when the texture itself is new). Known before
// tracing: its bounding box is also where the accumulation is redone.
std::vector<Rect> dirty_parts(const FrameCache& c, const LightPlan& plan, Rect tex_rect, bool fresh, bool must,
                              bool had_lights) {
    if (!had_lights && plan.lights.empty()) return {};
    if (fresh || must) return {tex_rect};
    std::vector<Rect> dirty;
    for (std::size_t k : plan.todo) dirty.push_back(intersect(plan.traced[k].mask.clip, tex_rect));
    for (std::size_t k : plan.recoloured) dirty.push_back(intersect(plan.traced[k].mask.clip, tex_rect));
    for (const TracedLight& old : c.lights) {
        bool kept = false;
        for (const TracedLight& now : plan.traced)
            kept = kept || (now.cx == old.cx && now.cy == old.cy && now.a == old.a && now.b == old.b &&
                            now.mask.clip == old.mask.clip);
        if (!kept) dirty.push_back(intersect(old.mask.clip, tex_rect));
    }
    return disjoint_union(std::move(dirty));
}

// Keeps this trace for the next frames, and invalidates the blur.
void keep_trace(FrameState& st, const Scene& scene, LightPlan& plan, FrameReport& rep) {
    FrameCache& c = *st.cache;
    c.lights = std::move(plan.traced);
    c.lights_corrected = st.options.opacity_correction;
    c.has_trace = true;
    c.trace_params = scene.params;
    c.trace_lights = scene.lights;
    c.has_blur = false;
    // Frames traced but not yet blurred (the app blurs on the GPU) pile up
    // parts: past a few hundred, their box stands for them.
    c.blur_pending.insert(c.blur_pending.end(), rep.dirty_parts.begin(), rep.dirty_parts.end());
    if (c.blur_pending.size() > 256) c.blur_pending = {bounding(c.blur_pending)};
    rep.retraced = !rep.dirty.empty();
    std::vector<Rect> traced = rep.touched_parts[int(Stage::trace)];
    traced.insert(traced.end(), rep.dirty_parts.begin(), rep.dirty_parts.end());
    touch(rep, Stage::trace, disjoint_union(std::move(traced)));
    if (!rep.retraced) {
        // No light now and none before: the texture stayed empty, nothing to
        // upload or blur again.
        rep.ran[int(Stage::trace)] = false;
        rep.ms[int(Stage::trace)] = 0;
        c.has_blur = false;  // the blur follows: cheap when nothing is pending
    }
}

// Whether a kept texture is redone only where lights changed (`dirty`): when
// that is less work than clearing and adding every light again.
bool redo_only_dirty(bool fresh, const TraceDecision& trace, const std::vector<Rect>& to_clear, const LightPlan& plan,
                     Rect dirty) {
    if (fresh || trace.must || to_clear.empty()) return false;
    auto area = [](Rect r) { return double(r.w) * r.h; };
    double whole = 0, part = area(dirty);
    for (const Rect& c : to_clear) whole += area(c);
    for (const TracedLight& t : plan.traced) whole += area(t.mask.clip), part += area(intersect(t.mask.clip, dirty));
    return part < whole;
}

}  // namespace

// Paper 3.2 and Algorithm 2: the lights that need it traced, corrected and
// summed into the light texture, the rest reused. A frame that fails or is
// cancelled keeps nothing half-traced: the next one starts afresh.
void trace_step(FrameState& st, const World& world, const Scene& scene, Rect tex_rect, const TraceDecision& trace,
                const ObstacleChange& obstacles, FrameReport& rep) {
    bool fresh = false;
    const std::vector<Rect> to_clear = prepare_texture(st, tex_rect, texture_channels(scene, st.options), fresh);
    const bool had_lights = !st.cache->lights.empty();
    if (trace.must) st.cache->lights.clear();  // nothing traced is reusable
    LightPlan plan = plan_lights(*st.cache, scene, tex_rect, obstacles.part, rep);
    rep.dirty_parts = dirty_parts(*st.cache, plan, tex_rect, fresh, trace.must, had_lights);
    rep.dirty = bounding(rep.dirty_parts);
    const bool partial = redo_only_dirty(fresh, trace, to_clear, plan, rep.dirty);
    try {
        trace_and_accumulate(st, world, scene.params, plan, to_clear, tex_rect, partial ? &rep.dirty : nullptr, rep);
    } catch (...) {
        st = FrameState{st.options};  // the cache gave its masks to the plan
        throw;
    }
    if (st.options.control.cancelled()) {
        st = FrameState{st.options};
        throw Cancelled();
    }
    keep_trace(st, scene, plan, rep);
}

}  // namespace isolux::frame_steps
