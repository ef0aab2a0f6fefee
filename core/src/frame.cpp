// Paper Figure 4: the overall steps, once per frame, each only when needed.
#include "isolux/frame.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <functional>
#include <thread>

#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "isolux/error.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/footprint.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/truth.hpp"
#include "occluders_tree.hpp"
#include "worker_pool.hpp"

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

double trace_work(const Scene& scene, Rect view) {
    const Params& p = scene.params;
    double steps = 0;
    for (const Light& l : scene.lights) {
        if (l.hidden || intersect(light_area(l, p), view).empty()) continue;
        steps += light_trace_work(light_a(l, p), light_b(l, p), p);
    }
    return steps;
}

double render_work(const Scene& scene, Rect view, int frames) {
    const int n = std::max(1, frames);
    const int traces = 1 + (n - 1) / std::max(1, scene.params.trace_every);
    return trace_work(scene, view) * traces + double(view.w) * double(view.h) * view_pixel_steps * n;
}

Rect camera_view(const Camera& c, const World& w) {
    const double x = std::clamp(std::floor(c.x), -1e9, 1e9), y = std::clamp(std::floor(c.y), -1e9, 1e9);
    // No size: the whole map's frame, wherever the camera was (as isolux-cli
    // renders it), the same whatever the edits.
    if (c.width <= 0 || c.height <= 0) return w.frame.empty() ? w.placed.bounds : w.frame;
    return {int(x), int(y), c.width, c.height};
}

namespace {

using Clock = std::chrono::steady_clock;
using TracedLight = FrameCache::TracedLight;

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// Times one stage into the report for as long as it lives.
struct Timer {
    FrameReport& report;
    Stage stage;
    Clock::time_point start = Clock::now();
    ~Timer() {
        report.ran[int(stage)] = true;
        report.ms[int(stage)] += ms_between(start, Clock::now());
    }
};

Rect grow(Rect r, int by) { return {r.x - by, r.y - by, r.w + 2 * by, r.h + 2 * by}; }

Rect bounding(const std::vector<Rect>& parts) {
    Rect b;
    for (const Rect& r : parts) b = bounding(b, r);
    return b;
}

// Records what a stage wrote: its disjoint parts and their bounding box.
void touch(FrameReport& rep, Stage s, std::vector<Rect> parts) {
    std::erase_if(parts, [](const Rect& r) { return r.empty(); });
    rep.touched[int(s)] = bounding(parts);
    rep.touched_parts[int(s)] = std::move(parts);
}

// Unique across every FrameState of the process: a tracer that keeps a copy
// of the obstacle map (the GPU's) never mistakes a new state's map for an
// old one's.
std::uint64_t next_obstacles_revision() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}

bool covers(Rect outer, Rect inner) { return intersect(outer, inner) == inner; }

// Whether a parameter that `stage` reads changed from `before` to `now`.
bool params_changed_for(Stage stage, const Params& before, const Params& now) {
    return !(before == now) && stages_changed(before, now).has(stage);  // equal: the still frame's fast answer
}

int threads_wanted(const FrameOptions& o) {
    return o.threads > 0 ? o.threads : std::max(1, int(std::thread::hardware_concurrency()));
}

// ---------------------------------------------------------------- the steps

// What changed in the world since the caches were built: nothing, edited
// tiles only (`region`), or everything.
struct WorldDelta {
    bool changed = false;
    bool partial = false;  // only `region` changed (set_edits)
    Rect region;
};

WorldDelta world_delta(const FrameCache& c, const World& world) {
    WorldDelta d;
    d.changed = c.world_revision != world.revision;
    if (d.changed && c.has_obstacles) d.partial = changed_since(world, c.world_revision, d.region);
    return d;
}

// The view's sprites (drawn by the GPU in the app).
void draw_view_sprites(FrameState& st, const World& world, Rect view, const WorldDelta& delta, FrameReport& rep) {
    if (!st.options.cpu_sprites) return;
    const bool same_view = st.view == view && st.sprites.width == view.w && st.sprites.height == view.h;
    if (!delta.changed && same_view) return;
    Timer t{rep, Stage::sprites};
    if (!delta.partial || !same_view) {
        st.sprites = render_sprites(world.tileset, world.placed, view);
        touch(rep, Stage::sprites, {view});
        return;
    }
    // An edit: redraw only its rectangle (each pixel is drawn from every
    // sprite over it, so the part equals the whole's).
    const Rect r = intersect(delta.region, view);
    if (r.empty()) return;
    touch(rep, Stage::sprites, {r});
    const Image part = render_sprites(world.tileset, world.placed, r);
    for (int y = 0; y < r.h; ++y)
        std::copy_n(part.at(0, y), std::size_t(r.w) * 4, st.sprites.at(r.x - view.x, r.y + y - view.y));
}

// The light texture's rectangle and every light area that meets it: the
// obstacles their rays can cross.
Rect region_lights_need(const World& world, const Scene& scene, Rect tex_rect) {
    Rect needed = tex_rect;
    for (const Light& l : scene.lights) {
        const Rect area = light_area(l, scene.params);
        if (!intersect(area, tex_rect).empty()) needed = bounding(needed, area);
    }
    return intersect(needed, world.placed.bounds);
}

// What the obstacle map did this frame: nothing, a part (after an edit), or
// all of it.
struct ObstacleChange {
    bool all = false;
    Rect part;  // rebuilt after an edit; lights meeting it are retraced
};

// How far an edit's effect on the obstacle map reaches past the sprites it
// changed: Algorithm 1's arms (a quarter of a sprite's width) and the noise
// filter's window.
int obstacle_reach(const Tileset& ts, const Params& p) {
    int reach = 0;
    for (const Sprite& s : ts.sprites) reach = std::max(reach, s.image.width / 4 + 1);
    return reach + p.noise_window;
}

// The obstacle map's `part` (inside its rectangle) built again: the build
// is exact per region.
void build_obstacle_part(Mask& obstacles, const World& world, const Params& p, Rect part, const std::vector<Mask>& footprints) {
    const Mask built = build_obstacle_map(world.tileset, world.placed, p, part, &footprints);
    for (int y = 0; y < part.h; ++y)
        std::copy_n(&built.bits[std::size_t(y) * part.w], part.w,
                    &obstacles.bits[std::size_t(part.y + y - obstacles.y0) * obstacles.width + (part.x - obstacles.x0)]);
}

// Paper 3.1: the obstacle map and the sprites' opacity maps. Their content
// changes only with the world, Δy, n or the threshold; a larger region is the
// same map over more pixels (the build is exact per region), so it alone does
// not force a retrace. An edit rebuilds only around the edited sprites.
ObstacleChange update_obstacle_map(FrameState& st, const World& world, const Params& p, Rect needed,
                                   const WorldDelta& delta, FrameReport& rep) {
    FrameCache& c = st.cache;
    const bool params_changed = !c.has_obstacles || params_changed_for(Stage::obstacle_map, c.obstacle_params, p);
    const bool changed = delta.changed || params_changed;
    if (!changed && covers(c.obstacle_region, needed)) return {};
    Timer t{rep, Stage::obstacle_map};
    if (delta.partial && !params_changed && covers(c.obstacle_region, needed)) {
        // The build is exact per region: the edited part, rebuilt, equals a
        // full rebuild there. Opacity maps are per sprite: an edit keeps them.
        ObstacleChange ch;
        ch.part = intersect(grow(delta.region, obstacle_reach(world.tileset, p)), c.obstacle_region);
        if (!ch.part.empty()) {
            build_obstacle_part(st.obstacles, world, p, ch.part, c.footprints);
            if (p.rays_over_obstacles)
                st.obstacle_heights = build_obstacle_heights(world.tileset, world.placed, p, st.obstacles);
            if (p.occluders != Occluders::footprints)
                update_occluders(st.occluders, world, p, c.obstacle_region, grow(delta.region, occluder_reach(world.tileset)),
                                 &c.solids);
            repaint_ground_lines(c.ground, world.placed, st.opacity, ch.part);
            st.obstacles_revision = next_obstacles_revision();
        }
        c.world_revision = world.revision;
        rep.rebuilt = ch.part;
        touch(rep, Stage::obstacle_map, {ch.part});
        return ch;
    }
    const Rect old_region = c.obstacle_region;
    c.obstacle_region = obstacle_region_around(needed, world);
    // Per sprite: its Algorithm 1 mask and its opacity map, which depend on
    // the tileset and the parameters only (not on a larger region, nor on edits).
    bool sprites_made = false;
    if (params_changed || c.sprites_built != world.built_revision || world.built_revision == 0 ||
        c.footprints.size() != world.tileset.sprites.size()) {
        c.footprints.clear();
        c.solids.clear();
        st.opacity.clear();
        for (const Sprite& s : world.tileset.sprites) {
            if (s.kind != SpriteKind::overlay) {  // floors are never obstacles
                c.footprints.push_back(Mask{});
                st.opacity.push_back(opacity_map(s.image, sprite_threshold(s, p.opacity_threshold)));
                continue;
            }
            FootprintReport r;
            c.footprints.push_back(tileset_footprint(world.tileset, s, p, &r));
            // Opacity maps of the objects alone: a baked ground diamond or a
            // baked shadow is ground, lit by the light texture, not by the correction.
            st.opacity.push_back(std::move(r.estimate));
        }
        c.sprites_built = world.built_revision;
        sprites_made = true;
    }
    // A pan (the region moved, grown or cut, the world and the parameters
    // the same) keeps what the old region and the new share: only the strips
    // that came in are built. Each map is exact per region, so the result is
    // what a whole build gives.
    const Rect region = c.obstacle_region, kept = intersect(old_region, region);
    const bool pan = !changed && !sprites_made && !kept.empty();
    if (pan && !st.options.obstacle_map && st.obstacles.rect() == old_region) {
        move_grid(st.obstacles.bits, old_region, region);
        st.obstacles.x0 = region.x, st.obstacles.y0 = region.y, st.obstacles.width = region.w, st.obstacles.height = region.h;
        for (const Rect& r : outside(region, kept)) build_obstacle_part(st.obstacles, world, p, r, c.footprints);
    } else {
        st.obstacles = st.options.obstacle_map ? st.options.obstacle_map(world, p, region, c.footprints)
                                               : build_obstacle_map(world.tileset, world.placed, p, region, &c.footprints);
    }
    st.obstacle_heights = p.rays_over_obstacles ? build_obstacle_heights(world.tileset, world.placed, p, st.obstacles)
                                                : ObstacleHeights{};
    // Beyond the paper: solids with height stop the rays (occluders.hpp).
    if (p.occluders == Occluders::footprints) st.occluders = OccluderMap{};
    else if (pan && st.occluders.rect == old_region) update_occluders(st.occluders, world, p, region, Rect{}, &c.solids);
    else rebuild_occluders(st.occluders, world, p, region, &c.solids);
    if (pan && c.ground.exact && c.ground.rect == old_region) pan_ground_lines(c.ground, world.placed, st.opacity, region);
    else c.ground = ground_lines(world.placed, st.opacity, region);
    st.obstacles_revision = next_obstacles_revision();
    c.obstacle_params = p;
    c.world_revision = world.revision;
    c.has_obstacles = true;
    ObstacleChange ch;
    ch.all = changed;
    if (changed) rep.rebuilt = c.obstacle_region;
    touch(rep, Stage::obstacle_map, {c.obstacle_region});
    return ch;
}

// Paper 3.2: rays are traced once every l frames. `must`: nothing traced can
// be reused (obstacles or tracing parameters changed).
struct TraceDecision {
    bool must = false, retrace = false;
};

TraceDecision decide_retrace(const FrameState& st, const Scene& scene, Rect view, long frame,
                             const ObstacleChange& obstacles) {
    const FrameCache& c = st.cache;
    const Params& p = scene.params;
    TraceDecision d;
    d.must = !c.has_trace || obstacles.all || params_changed_for(Stage::trace, c.trace_params, p) ||
             c.lights_corrected != st.options.opacity_correction;
    const bool due = frame % p.trace_every == 0 && (c.trace_lights != scene.lights || !covers(st.traced.rect, view));
    d.retrace = d.must || due || !obstacles.part.empty();  // an edit: the lights it touched, now
    return d;
}

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
// place and clip for dirty_parts, and render_frame drops the cache if the
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
        t.height = p.rays_over_obstacles || p.occluders != Occluders::footprints ? light_height(l, p) : 0;
        t.colour = {l.r, l.g, l.b};
        t.intensity = l.intensity;
        // Against solids a clipped light still walks its whole area's rays
        // (occluders_tree.hpp), so where the trees reach it the light keeps
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
        for (const TracedLight& c : st.cache.lights) to_clear.push_back(c.mask.clip);
    }
    fresh = to_clear.empty() && !(!st.cache.lights.empty() && st.traced.rect == tex_rect && st.traced.channels == channels);
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
        rep.tracer = st.options.tracer(st.obstacles, st.obstacles_revision, solids ? &st.occluders : nullptr, masks,
                                       heights, p, solids && correct);
        traced_elsewhere = !rep.tracer.empty();
        if (traced_elsewhere) rep.ms[int(Stage::trace)] += ms_between(t0, Clock::now());
    }
    if (!traced_elsewhere && n > 0) rep.tracer = "cpu";

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
            if (solids && !traced_elsewhere)  // beyond the paper: solids with height
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
            if (!traced_elsewhere) light_sprite_points(tl.mask, st.occluders, tl.height, p, light_threads);
        } else if (correct && st.cache.ground.exact)
            correct_with_ground_lines(tl.mask, st.cache.ground);
        else if (correct)
            correct_with_opacity_maps(tl.mask, world.placed, st.opacity);
        if (shaped(p)) shape_light(tl.mask, p);  // beyond the paper: round lights, a fade to the border
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
    FrameCache& c = st.cache;
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

// Pieces of the blur's and the composite's rows closer than this are done as
// one, the pixels between them (unchanged, so redone to the same bytes)
// included: each piece of a row starts the hardware's prefetch anew, which
// costs what a few hundred pixels do (isolux-bench's stage/composite_strips:
// the same pixels in full rows and in 960- and 480-pixel strips).
constexpr int join_gap = 256;

// The light texture the composite reads: the blurred one, or the traced one
// when there is no blur.
const LightTexture& shown_light(const FrameState& st, const Params& p) {
    return p.blur_radius > 0 ? st.cache.blurred : st.traced;
}

// Paper 3.2: the blur of the light texture. Redoes only what was traced since
// the last blur, grown by the radius (every texel it reaches), unless the
// texture is new or the radius changed; in bands of rows across threads.
// Returns the world pixels whose blurred light changed, disjoint.
std::vector<Rect> blur_step(FrameState& st, const Params& p, FrameReport& rep) {
    FrameCache& c = st.cache;
    const Rect tex = st.traced.rect;
    std::vector<Rect> changed;
    const bool radius_changed = c.blur_params.blur_radius != p.blur_radius;
    if (c.has_blur && !radius_changed) return changed;
    const bool within = blur_within_surfaces(p);
    const bool whole = radius_changed || !(c.blurred.rect == tex) || (p.blur_radius > 0 && c.blurred.texels.empty()) ||
                       (p.blur_radius > 0 && c.blurred.channels != st.traced.channels) ||
                       c.blur_surface_ids != (within ? st.surface_ids_revision : 0);
    if (whole) {
        changed = {tex};
    } else {
        for (const Rect& r : c.blur_pending) changed.push_back(intersect(grow(r, p.blur_radius), tex));
        changed = disjoint_union(std::move(changed), join_gap);
    }
    if (p.blur_radius > 0 && !changed.empty()) {
        Timer t{rep, Stage::blur};
        if (!(c.blurred.rect == tex) || c.blurred.channels != st.traced.channels || c.blurred.texels.size() != st.traced.texels.size())
            c.blurred = LightTexture(tex, st.traced.channels);
        in_row_bands(changed, threads_wanted(st.options), [&](Rect band) {
            if (within) box_blur_within_into(st.traced, p.blur_radius, st.surface_ids, band, c.blurred);
            else box_blur_into(st.traced, p.blur_radius, band, c.blurred);
        });
        touch(rep, Stage::blur, changed);
    } else if (p.blur_radius == 0) {
        c.blurred = LightTexture{};
        c.blurred.rect = tex;  // what the texture was "blurred" for: itself
    }
    c.has_blur = true;
    c.blur_params = p;
    c.blur_pending = {};
    c.blur_surface_ids = within ? st.surface_ids_revision : 0;
    return changed;
}

// The light texture cut to the view, for a caller that shows it (the paper's
// inverse translation between retraces: the texture stays world-anchored).
void shift_step(FrameState& st, const Params& p, Rect view, const std::vector<Rect>& changed, FrameReport& rep) {
    if (!st.options.view_light_texture || (changed.empty() && st.light.rect == view)) return;
    Timer t{rep, Stage::shift};
    st.light = shift_light_texture(shown_light(st, p), view);
    touch(rep, Stage::shift, {view});
}

// Algorithm 3 on the CPU: the view's sprites mixed with the light under the
// ambient clarity. Redoes only where the light changed (`changed`) when the
// rest of the final frame still holds; in bands of rows across threads.
void composite_step(FrameState& st, const Params& p, Rect view, const WorldDelta& delta,
                    const std::vector<Rect>& changed, FrameReport& rep) {
    FrameCache& c = st.cache;
    const bool whole = !c.has_final || !(st.view == view) || delta.changed ||
                       params_changed_for(Stage::composite, c.composite_params, p) || st.final.width != view.w ||
                       st.final.height != view.h;
    std::vector<Rect> region;  // disjoint, as `changed` is
    if (whole) region = {view};
    else
        for (const Rect& r : changed)
            if (const Rect z = intersect(r, view); !z.empty()) region.push_back(z);
    if (!region.empty()) {
        Timer t{rep, Stage::composite};
        if (st.final.width != view.w || st.final.height != view.h) st.final = Image(view.w, view.h);
        const LightTexture& light = shown_light(st, p);
        in_row_bands(region, threads_wanted(st.options),
                     [&](Rect band) { composite_into(st.sprites, view, light, p, band, st.final); });
        touch(rep, Stage::composite, std::move(region));
    }
    c.composite_params = p;
    c.has_final = true;
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

// Beyond the paper: which surface each pixel of the occluder map's region
// shows, for the blur within surfaces; remade only with the occluders (a
// moving camera keeps them, as it keeps the region), and timed with them.
void surface_ids_step(FrameState& st, const Params& p, FrameReport& rep) {
    if (!blur_within_surfaces(p)) {
        st.surface_ids = SurfaceIds{};
        st.surface_ids_revision = 0;
        return;
    }
    if (st.surface_ids_revision == st.obstacles_revision && !st.surface_ids.id.empty()) return;
    Timer t{rep, Stage::obstacle_map};
    st.surface_ids.rect = st.occluders.surface.rect;
    st.surface_ids.id = st.occluders.surface.instance;
    // The reach serves the CPU blur alone: the app's GPU blur reads the ids.
    if (st.options.cpu_blur_and_composite)
        index_surfaces(st.surface_ids);
    else
        st.surface_ids.reach.clear();
    st.surface_ids_revision = st.obstacles_revision;
}

// Paper 3.2 and Algorithm 2: the lights that need it traced, corrected and
// summed into the light texture, the rest reused. A frame that fails or is
// cancelled keeps nothing half-traced: the next one starts afresh.
void trace_step(FrameState& st, const World& world, const Scene& scene, Rect tex_rect, const TraceDecision& trace,
                const ObstacleChange& obstacles, FrameReport& rep) {
    bool fresh = false;
    const std::vector<Rect> to_clear = prepare_texture(st, tex_rect, texture_channels(scene, st.options), fresh);
    const bool had_lights = !st.cache.lights.empty();
    if (trace.must) st.cache.lights.clear();  // nothing traced is reusable
    LightPlan plan = plan_lights(st.cache, scene, tex_rect, obstacles.part, rep);
    rep.dirty_parts = dirty_parts(st.cache, plan, tex_rect, fresh, trace.must, had_lights);
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

// The scene without its hidden lights (they stay in the scene but light
// nothing); `storage` holds the copy when one is needed.
const Scene& shown_scene(const Scene& scene, Scene& storage) {
    if (std::none_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) { return l.hidden; })) return scene;
    storage.params = scene.params;
    for (const Light& l : scene.lights)
        if (!l.hidden) storage.lights.push_back(l);
    return storage;
}

}  // namespace

Rect obstacle_region_around(Rect needed, const World& world) {
    return needed.empty() ? needed : intersect(grow(needed, 256), world.placed.bounds);
}

Rect frame_region_needed(const World& world, const Scene& scene, const Camera& camera, int margin) {
    Scene storage;
    return region_lights_need(world, shown_scene(scene, storage), grow(camera_view(camera, world), margin));
}

FrameReport render_frame(FrameState& st, const World& world, const Scene& scene_in, const Camera& camera, long frame) {
    Scene storage;
    const Scene& scene = shown_scene(scene_in, storage);
    assert(frame >= 0 && st.options.margin >= 0 && st.options.threads >= 0);
    // An Error here, not a division by zero below. The last trace's
    // parameters were validated then.
    if (!st.cache.has_trace || !(scene.params == st.cache.trace_params)) validate(scene.params, "scene parameters");
    FrameReport rep;
    const Rect view = camera_view(camera, world);
    const Rect tex_rect = grow(view, st.options.margin);
    const WorldDelta delta = world_delta(st.cache, world);

    draw_view_sprites(st, world, view, delta, rep);
    const Rect needed = region_lights_need(world, scene, tex_rect);
    const ObstacleChange obstacles = update_obstacle_map(st, world, scene.params, needed, delta, rep);
    const TraceDecision trace = decide_retrace(st, scene, view, frame, obstacles);
    if (trace.retrace) trace_step(st, world, scene, tex_rect, trace, obstacles, rep);
    surface_ids_step(st, scene.params, rep);
    if (st.options.cpu_blur_and_composite) {
        const std::vector<Rect> changed = blur_step(st, scene.params, rep);
        shift_step(st, scene.params, view, changed, rep);
        composite_step(st, scene.params, view, delta, changed, rep);
    }
    st.view = view;
    return rep;
}

}  // namespace isolux
