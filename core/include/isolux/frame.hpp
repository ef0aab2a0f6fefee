// One frame of the pipeline (paper Figure 4): obstacle map, tracing every l
// frames, opacity correction, blur, the inverse translation in between, and the
// composite. Each stage runs only when its inputs changed; the report says
// which ran and what each cost.
#pragma once
#include <array>
#include <chrono>
#include <string_view>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/scene.hpp"
#include "isolux/world.hpp"

namespace isolux {

enum class Stage { sprites, obstacle_map, trace, opacity_correction, blur, shift, composite };
inline constexpr int stage_count = 7;
std::string_view to_string(Stage s);

struct FrameReport {
    std::array<bool, stage_count> ran{};
    std::array<double, stage_count> ms{};  // wall time per stage, milliseconds
    int lights_traced = 0;       // lights whose rays were traced this frame
    int lights_reused = 0;       // lights whose traced pixels were still valid (not traced again)
    int sprites_corrected = 0;   // sprite instances the opacity correction touched
    bool retraced = false;       // FrameState::traced changed this frame
    Rect dirty;                  // where it changed (what an upload must send); empty when it did not
    bool ran_stage(Stage s) const { return ran[int(s)]; }
};

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
};

// What a frame keeps for the next one. Default-constructed: nothing cached.
struct FrameState {
    FrameOptions options;

    // Obstacle map and per-sprite opacity maps, with what they were built from.
    std::uint64_t world_revision = ~0ull;
    Params obstacle_params;
    Rect obstacle_region;
    Mask obstacles;
    std::vector<Mask> opacity;
    bool has_obstacles = false;

    // Each light's traced and corrected pixels, kept while the obstacle map,
    // the tracing parameters and the light's centre, area and clip are the
    // same: an unchanged light is never traced twice.
    struct TracedLight {
        std::int64_t cx = 0, cy = 0;
        int a = 0, b = 0;
        LightMask mask;
    };
    std::vector<TracedLight> light_cache;
    bool cache_corrected = true;  // whether the cached masks had the opacity correction

    // The last trace, world-anchored: corrected light texture and its blur.
    bool has_trace = false;
    Params trace_params;
    std::vector<Light> trace_lights;
    LightTexture traced, blurred;
    int blurred_radius = -1;

    // The view's sprites, light texture and final image.
    Rect view;
    Image sprites;
    LightTexture light;  // the view's light texture, what the composite reads
    Image final;
    Params composite_params;
    bool has_final = false;
};

// The view a camera shows: its rectangle, or the map's size at the camera's
// position when the camera's width or height is 0.
Rect camera_view(const Camera& camera, const World& world);

// Runs frame number `frame` (0, 1, 2, ...) for the scene's lights and
// parameters seen through `camera`. Retraces on the first frame, whenever a
// tracing parameter or the obstacle map changed, and on frames that are a
// multiple of trace_every when lights moved or the view left the traced
// texture; other frames shift the last texture with the camera.
FrameReport render_frame(FrameState& state, const World& world, const Scene& scene, const Camera& camera, long frame);

}  // namespace isolux
