// One frame of the pipeline (paper Figure 4): obstacle map, tracing every l
// frames, opacity correction, blur, the inverse translation in between, and the
// composite. Each stage runs only when its inputs changed; the report says
// which ran and what each cost.
#pragma once
#include <string>
#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "isolux/error.hpp"
#include "isolux/height_rays.hpp"
#include "isolux/image.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/blur.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/sprite_shading.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/scene.hpp"
#include "isolux/stage.hpp"
#include "isolux/world.hpp"

namespace isolux {

struct FrameReport {
    std::array<bool, stage_count> ran{};
    std::array<double, stage_count> ms{};  // wall time per stage, milliseconds
    int lights_traced = 0;       // lights whose rays were traced this frame
    int lights_reused = 0;       // lights whose traced pixels were still valid (not traced again)
    bool retraced = false;       // FrameState::traced changed this frame
    Rect dirty;                  // where it changed (what an upload must send); empty when it did not
    // World pixels whose sprites and obstacle map were rebuilt after an edit
    // (set_edits): only there, and only the lights meeting it were retraced.
    // Empty when no edit arrived; the whole obstacle region on a full rebuild.
    Rect rebuilt;
    // World pixels each stage wrote this frame, by Stage (empty: it did not
    // run): the traced lights' areas, the texture's redone part (trace:
    // clearing and adding lights), the blurred and composited parts.
    std::array<Rect, stage_count> touched{};
    // The same as disjoint rectangles (`touched` is their bounding box): the
    // blur and the composite redo several moved lights' areas, not the box
    // around them. `dirty_parts` likewise for `dirty`.
    std::array<std::vector<Rect>, stage_count> touched_parts{};
    std::vector<Rect> dirty_parts;
    // Which tracer traced this frame's lights: "cpu", or the name a
    // FrameOptions::tracer gave ("gpu" in the app); empty when none was traced.
    std::string_view tracer;
    bool ran_stage(Stage s) const { return ran[int(s)]; }
};

// A tracer other than the CPU's (the app's GPU compute tracer, app/gui/
// gpu_tracer.hpp): fills `masks` (clip, centre, a, b set; value, and reached
// in shadow mode, sized and zero) with exactly trace_light's bytes for these
// obstacles and parameters, or, with occluders solids or shapes (`occluders`
// set, each light at its `heights` entry), trace_light_solids's bytes for
// these occluders, and with `sprite_points` set light_sprite_points's after
// them; and returns its name; or returns "" to leave them to the CPU. Called
// on the frame's own thread, before the opacity correction (or, when the
// tracer did not take it, the sprite pass); `obstacles_revision` changes
// whenever the obstacle map (and with it the occluder map) does.
using LightTracer =
    std::function<std::string_view(const Mask& obstacles, std::uint64_t obstacles_revision, const OccluderMap* occluders,
                                   const std::vector<LightMask*>& masks, const std::vector<double>& heights,
                                   const Params& p, bool sprite_points)>;

struct FrameOptions {
    int margin = 64;                  // light texture = view + margin on each side (the paper's "slightly greater")
    bool opacity_correction = true;   // off only to show the raw light texture (the paper's Figure 6)
    // The app draws sprites, blurs and composites on the GPU: it turns these
    // off and reads FrameState::traced instead.
    bool cpu_sprites = true;
    bool cpu_blur_and_composite = true;
    // Threads that trace lights (and correct them) in parallel; 0: one per
    // core. The output is the same bytes for any count: each light is traced
    // on its own and the saturating sum does not depend on order.
    int threads = 1;
    // FrameState::light, the view's own copy of the blurred texture (the
    // paper's inverse translation): the composite reads the world-anchored
    // blurred texture in place, so only callers that show or save the light
    // layer need the copy.
    bool view_light_texture = true;
    // A grey light texture (LightTexture::channels 1) when every shown light
    // is grey (r = g = b): the same pixels from a third of the bytes added,
    // blurred and composited. Off: always r, g, b (the tests' oracle).
    bool grey_when_lights_are = true;
    // Traces the lights instead of the CPU when set and it accepts them
    // (never for rays_over_obstacles, a CPU-only extension).
    LightTracer tracer;
    // Progress and cancel for long work run on another thread (the app's
    // approved long traces): `done` counts trace_work's steps as the CPU
    // tracer goes (by whole lights with rays_over_obstacles or another
    // tracer). Once `cancel` is set, render_frame stops within a few
    // milliseconds, resets the state (options kept) and throws Cancelled.
    TraceControl control;
    // Builds the obstacle map over a region when it is made whole (not an
    // edit's part): the same bits build_obstacle_map gives, from the world's
    // placed sprites, the parameters and each sprite's Algorithm 1 mask. An
    // endless world's frames copy the blocks earlier windows built
    // (endless.hpp). Empty: build_obstacle_map.
    std::function<Mask(const World&, const Params&, Rect, const std::vector<Mask>& footprints)> obstacle_map;
};

// What the last frame was built from (core/src/frame/frame_cache.hpp):
// private to render_frame, which reads it to skip the stages whose inputs
// did not change.
struct FrameCache;
struct FrameCacheDeleter {
    void operator()(FrameCache* c) const;
};
std::unique_ptr<FrameCache, FrameCacheDeleter> new_frame_cache();


// Beyond the paper: whether the blur stays within surfaces (box_blur_within):
// with occluders solids or shapes, each sprite pixel is lit by the 3D point it
// shows, and averaging it with the ground or another sprite beside it on
// screen mixes in the light of points far from it in depth (docs/beyond.md).
inline bool blur_within_surfaces(const Params& p) {
    return p.occluders != Occluders::footprints && p.mode != Mode::flat && p.blur_radius > 0;
}

// What a frame leaves for the caller, and its caches for the next frame.
// Default-constructed: nothing built yet.
struct FrameState {
    FrameOptions options;

    // Outputs, valid after render_frame (those of stages an option turns off stay empty).
    Mask obstacles;              // the obstacle map over the region lights need (paper 3.1)
    std::uint64_t obstacles_revision = 0;  // a new value, unique in the process, whenever `obstacles` changes
    std::vector<Mask> opacity;   // each tileset sprite's opacity map, by sprite index
    ObstacleHeights obstacle_heights;  // with rays_over_obstacles: the obstacles' estimated heights
    OccluderMap occluders;             // with occluders solids or shapes: spans and surface heights
    // With occluder_scale s > 1: coarse_occluders(occluders, s), what both
    // passes trace over, remade when either changes (coarse_revision: a new
    // value then, as obstacles_revision; coarse_of: the obstacles_revision
    // and the scale it was made for).
    OccluderMap coarse_occluders;
    std::vector<std::uint8_t> coarse_picks;  // coarse_picks(occluders.surface, coarse_occluders, scale)
    std::uint64_t coarse_revision = 0, coarse_of = 0;
    int coarse_scale = 0;
    // With sprite_shading: each pixel's normal and the height of the point it
    // shows, over the obstacle map's region, remade with it
    // (shading_revision: the obstacles_revision it was made for).
    ShadingMap shading;
    std::uint64_t shading_revision = 0;
    // With blur_within_surfaces: which surface each pixel of the occluders'
    // region shows (world pixels, as `occluders`), what the blur stays
    // within, and a new value whenever it changes (0: none). Its reach is
    // filled only with cpu_blur_and_composite (the CPU blur's alone).
    SurfaceIds surface_ids;
    std::uint64_t surface_ids_revision = 0;
    LightTexture traced;         // the last trace: corrected light texture, world-anchored
    Rect view;                   // what the view shows, world pixels
    Image sprites;               // the view's sprites (cpu_sprites)
    LightTexture light;          // the view's blurred light texture, what the composite reads
    Image final;                 // the lit frame (cpu_blur_and_composite)

    // Never null but in a moved-from state.
    std::unique_ptr<FrameCache, FrameCacheDeleter> cache = new_frame_cache();
};

// The Bresenham steps a full trace of the scene's lights that meet `view`
// costs at most (rays x their length): what a render or sweep must do, known
// before it starts. About 1e9 steps take a few seconds on one core.
double trace_work(const Scene& scene, Rect view);

// The work of `frames` frames over `view`, in trace_work's steps: a full trace
// on each of the frames that retrace (every l frames, the first included),
// plus every frame's stages that read each view pixel (sprites, opacity
// correction, blur, shift, composite), a pixel counted as view_pixel_steps.
// What a long --frames or a large view costs, known before it starts.
inline constexpr double view_pixel_steps = 4;
double render_work(const Scene& scene, Rect view, int frames);

// Work beyond this many steps (minutes or more on one core) is refused by
// isolux-cli unless --allow-huge, and asked about by the app before it runs.
constexpr double huge_trace_steps = 4e9;
// The memory a lit render holds a view pixel at its peak: the sprites, the
// obstacle map, the light textures as traced and blurred, the final picture
// and its PNG (isolux-cli's peak resident memory over a 128x128 seeded map's
// 137-megapixel view is 19 bytes a pixel; docs/reliability.md).
inline constexpr double view_pixel_bytes = 20;
double render_memory(Rect view);
// A render whose memory is estimated beyond this (a 1 GiB view: 54
// megapixels, a 128x128 map whole) is refused by isolux-cli unless
// --allow-huge and by the C API unless isolux_world_allow_huge.
constexpr double huge_render_bytes = double(1 << 30);
// "about 1.3 GiB": how the refusals beyond huge_render_bytes say a size
// (isolux-cli's render and export-tiled, the C API alike).
std::string about_gib(double bytes);
// The largest view a render makes (256 megapixels: 1 GiB of RGBA), in
// isolux-cli and in the app's screenshots alike.
constexpr long long max_render_pixels = 1LL << 28;

// The view a camera shows: its rectangle, or the whole map (World::frame:
// the seeded map's bounds, which edits never move) when its width or height
// is 0.
Rect camera_view(const Camera& camera, const World& world);

// The world pixels a frame's obstacle map (and occluder map) must hold: the
// light texture's rectangle (the view grown by `margin`) and every light area
// that meets it, within the map.
Rect frame_region_needed(const World& world, const Scene& scene, const Camera& camera, int margin);
// The region a frame that builds the maps builds them over: what it needs
// and 256 pixels of room around it, within the map, so that a panning camera
// does not rebuild them every frame.
Rect obstacle_region_around(Rect needed, const World& world);

// Runs frame number `frame` (0, 1, 2, ...) for the scene's lights and
// parameters seen through `camera`. Throws Error naming the field when the
// scene's parameters are out of range (validate()). Retraces on the first frame, whenever a
// tracing parameter or the obstacle map changed, and on frames that are a
// multiple of trace_every when lights moved or the view left the traced
// texture; other frames shift the last texture with the camera.
// Throws Cancelled when FrameOptions::control asked.
FrameReport render_frame(FrameState& state, const World& world, const Scene& scene, const Camera& camera, long frame);

}  // namespace isolux
