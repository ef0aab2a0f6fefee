// Paper Figure 4: the overall steps, once per frame, each only when needed.
#include "isolux/frame.hpp"

#include <algorithm>
#include <cstdio>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <thread>

#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "isolux/error.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/footprint.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/truth.hpp"
#include "frame/frame_steps.hpp"
#include "base/worker_pool.hpp"

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

double render_memory(Rect view) { return double(view.w) * double(view.h) * view_pixel_bytes; }

std::string about_gib(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "about %.1f GiB", bytes / double(1 << 30));
    return text;
}

Rect camera_view(const Camera& c, const World& w) {
    const double x = std::clamp(std::floor(c.x), -1e9, 1e9), y = std::clamp(std::floor(c.y), -1e9, 1e9);
    // No size: the whole map's frame, wherever the camera was (as isolux-cli
    // renders it), the same whatever the edits.
    if (c.width <= 0 || c.height <= 0) return w.frame.empty() ? w.placed.bounds : w.frame;
    return {int(x), int(y), c.width, c.height};
}

using namespace frame_steps;

// Unique across every FrameState of the process: a tracer that keeps a copy
// of the obstacle map (the GPU's) never mistakes a new state's map for an
// old one's.
std::uint64_t frame_steps::next_obstacles_revision() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}

namespace {

bool covers(Rect outer, Rect inner) { return intersect(outer, inner) == inner; }

// Whether a parameter that `stage` reads changed from `before` to `now`.
bool params_changed_for(Stage stage, const Params& before, const Params& now) {
    return !(before == now) && stages_changed(before, now).has(stage);  // equal: the still frame's fast answer
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
    FrameCache& c = *st.cache;
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
            const Rect occluders_part = grow(delta.region, occluder_reach(world.tileset));
            if (p.occluders != Occluders::footprints)
                update_occluders(st.occluders, world, p, c.obstacle_region, occluders_part, &c.solids);
            repaint_ground_lines(c.ground, world.placed, st.opacity, ch.part);
            // (The manifest's shapes may reach anywhere: an edit remakes them whole.)
            const bool local = p.occluders == Occluders::solids;
            c.edit_from = local ? st.obstacles_revision : 0;
            c.edit_part = intersect(occluders_part, c.obstacle_region);
            st.obstacles_revision = next_obstacles_revision();
            c.edit_to = local ? st.obstacles_revision : 0;
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
        c.normals.clear();
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
    // Beyond the paper: solids with height stop the rays (occluder_map.hpp).
    const bool occluders_panned = p.occluders != Occluders::footprints && pan && st.occluders.rect == old_region;
    if (p.occluders == Occluders::footprints) st.occluders = OccluderMap{};
    else if (occluders_panned) update_occluders(st.occluders, world, p, region, Rect{}, &c.solids);
    else rebuild_occluders(st.occluders, world, p, region, &c.solids);
    if (pan && c.ground.exact && c.ground.rect == old_region) pan_ground_lines(c.ground, world.placed, st.opacity, region);
    else c.ground = ground_lines(world.placed, st.opacity, region);
    c.pan_from = occluders_panned ? st.obstacles_revision : 0;
    c.pan_from_rect = old_region;
    st.obstacles_revision = next_obstacles_revision();
    c.pan_to = occluders_panned ? st.obstacles_revision : 0;
    c.edit_from = c.edit_to = 0;
    c.obstacle_params = p;
    c.world_revision = world.revision;
    c.has_obstacles = true;
    ObstacleChange ch;
    ch.all = changed;
    if (changed) rep.rebuilt = c.obstacle_region;
    touch(rep, Stage::obstacle_map, {c.obstacle_region});
    return ch;
}

TraceDecision decide_retrace(const FrameState& st, const Scene& scene, Rect view, long frame,
                             const ObstacleChange& obstacles) {
    const FrameCache& c = *st.cache;
    const Params& p = scene.params;
    TraceDecision d;
    d.must = !c.has_trace || obstacles.all || params_changed_for(Stage::trace, c.trace_params, p) ||
             c.lights_corrected != st.options.opacity_correction;
    const bool due = frame % p.trace_every == 0 && (c.trace_lights != scene.lights || !covers(st.traced.rect, view));
    d.retrace = d.must || due || !obstacles.part.empty();  // an edit: the lights it touched, now
    return d;
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
    return p.blur_radius > 0 ? st.cache->blurred : st.traced;
}

// Paper 3.2: the blur of the light texture. Redoes only what was traced since
// the last blur, grown by the radius (every texel it reaches), unless the
// texture is new or the radius changed; in bands of rows across threads.
// Returns the world pixels whose blurred light changed, disjoint.
std::vector<Rect> blur_step(FrameState& st, const Params& p, FrameReport& rep) {
    FrameCache& c = *st.cache;
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
    if (!st.options.view_light_texture) {
        // Dropped, not left stale: a later frame that wants it again then
        // finds no copy of this view and makes one.
        st.light = LightTexture{};
        return;
    }
    if (changed.empty() && st.light.rect == view) return;
    Timer t{rep, Stage::shift};
    st.light = shift_light_texture(shown_light(st, p), view);
    touch(rep, Stage::shift, {view});
}

// Algorithm 3 on the CPU: the view's sprites mixed with the light under the
// ambient clarity. Redoes only where the light changed (`changed`) when the
// rest of the final frame still holds; in bands of rows across threads.
void composite_step(FrameState& st, const Params& p, Rect view, const WorldDelta& delta,
                    const std::vector<Rect>& changed, FrameReport& rep) {
    FrameCache& c = *st.cache;
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

// Beyond the paper: the normals and points sprite shading reads, over the
// obstacle map's region, timed with the trace that reads it (which a change
// of either re-runs). The map is exact per region (each pixel is the topmost
// overlay over it), so as the obstacle map it keeps what it can: after an
// edit only the obstacle map's rebuilt part is remade, after a pan only the
// strips that came in; a change of source, parameters or world remakes it.
void copy_shading_part(ShadingMap& into, const ShadingMap& part) {
    for (int y = 0; y < part.rect.h; ++y) {
        const std::size_t from = std::size_t(y) * part.rect.w,
                          to = std::size_t(part.rect.y + y - into.rect.y) * into.rect.w + std::size_t(part.rect.x - into.rect.x);
        std::copy_n(&part.normal[from], part.rect.w, &into.normal[to]);
        std::copy_n(&part.height[from], part.rect.w, &into.height[to]);
    }
}

void shading_step(FrameState& st, const World& world, const Params& p, const ObstacleChange& obstacles, FrameReport& rep) {
    FrameCache& c = *st.cache;
    if (p.sprite_shading == SpriteShading::none) {
        st.shading = ShadingMap{};
        st.shading_revision = 0;
        return;
    }
    const Rect region = c.obstacle_region, old = st.shading.rect;
    const bool kept_source = c.normals.from == p.sprite_shading && !st.shading.empty();
    if (kept_source && st.shading_revision == st.obstacles_revision && old == region) return;
    Timer t{rep, Stage::trace};
    const Rect kept = intersect(old, region);
    if (kept_source && !obstacles.all && !obstacles.part.empty() && old == region) {
        copy_shading_part(st.shading, build_shading_map(world, p, obstacles.part, c.normals, &c.solids));
    } else if (kept_source && !obstacles.all && obstacles.part.empty() && !kept.empty() && old != region) {
        move_grid(st.shading.normal, old, region);
        move_grid(st.shading.height, old, region);
        st.shading.rect = region;
        for (const Rect& r : outside(region, kept)) copy_shading_part(st.shading, build_shading_map(world, p, r, c.normals, &c.solids));
    } else {
        st.shading = build_shading_map(world, p, region, c.normals, &c.solids);
    }
    st.shading_revision = st.obstacles_revision;
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

void FrameCacheDeleter::operator()(FrameCache* c) const { delete c; }
std::unique_ptr<FrameCache, FrameCacheDeleter> new_frame_cache() {
    return std::unique_ptr<FrameCache, FrameCacheDeleter>(new FrameCache);
}

FrameReport render_frame(FrameState& st, const World& world, const Scene& scene_in, const Camera& camera, long frame) {
    Scene storage;
    const Scene& scene = shown_scene(scene_in, storage);
    assert(frame >= 0 && st.options.margin >= 0 && st.options.threads >= 0);
    // An Error here, not a division by zero below. The last trace's
    // parameters were validated then.
    if (!st.cache->has_trace || !(scene.params == st.cache->trace_params)) validate(scene.params, "scene parameters");
    FrameReport rep;
    const Rect view = camera_view(camera, world);
    const Rect tex_rect = grow(view, st.options.margin);
    const WorldDelta delta = world_delta(*st.cache, world);

    draw_view_sprites(st, world, view, delta, rep);
    const Rect needed = region_lights_need(world, scene, tex_rect);
    const ObstacleChange obstacles = update_obstacle_map(st, world, scene.params, needed, delta, rep);
    shading_step(st, world, scene.params, obstacles, rep);
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
