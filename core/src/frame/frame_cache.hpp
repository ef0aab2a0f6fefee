// The frame's caches (FrameState::cache), private to render_frame's steps.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "isolux/frame.hpp"

namespace isolux {

// What the last frame was built from: private to render_frame, which reads
// it to skip the stages whose inputs did not change.
struct FrameCache {
    // The obstacle map's inputs and the region it covers, and each sprite's
    // Algorithm 1 mask (what an edit's partial rebuild stamps).
    bool has_obstacles = false;
    std::vector<Mask> footprints;
    std::uint64_t sprites_built = 0;  // the World::built_revision footprints and opacity maps were made for
    std::uint64_t world_revision = ~0ull;
    Params obstacle_params;
    Rect obstacle_region;
    SolidsCache solids;  // with occluders solids: each sprite's, estimated once
    NormalsCache normals;  // with sprite_shading: each sprite's normals, made once
    // The last pan of the occluder map (update_occluders, nothing changed):
    // from `pan_from_rect` at revision `pan_from`, to revision `pan_to`. The
    // trace step then updates the coarse map (occluder_scale) in place.
    Rect pan_from_rect;
    std::uint64_t pan_from = 0, pan_to = 0;
    // The last hand edit of the occluder map with solids (update_occluders
    // in the same region), which changed it within `edit_part` alone: from
    // revision `edit_from` to `edit_to`. The trace step then updates the
    // coarse map there alone.
    Rect edit_part;
    std::uint64_t edit_from = 0, edit_to = 0;

    // Each light's traced and corrected pixels, kept while the obstacle map,
    // the tracing parameters and the light's centre, area and clip are the
    // same: an unchanged light is never traced twice.
    struct TracedLight {
        std::int64_t cx = 0, cy = 0;
        int a = 0, b = 0;
        double height = 0;  // read only with rays_over_obstacles
        std::array<std::uint8_t, 3> colour{255, 255, 255};  // what the light added with: a change re-adds its area
        double intensity = 1;
        LightMask mask;
        // What tracing and correcting it took, in ms (0: not timed yet):
        // the next frame traces the costliest first, so that threads finish together.
        double cost_ms = 0;
    };
    std::vector<TracedLight> lights;
    bool lights_corrected = true;  // whether the cached masks had the opacity correction

    // The last trace's inputs.
    bool has_trace = false;
    Params trace_params;
    std::vector<Light> trace_lights;

    // The opacity correction's per-pixel ground lines over the obstacle
    // region, built with the obstacle map (opacity_correction.hpp).
    GroundLines ground;

    // The blurred light texture and its inputs (the blur re-runs after every
    // trace, over the part the trace changed when the rest still holds). Empty
    // with radius 0: the composite reads the traced texture.
    bool has_blur = false;
    Params blur_params;
    LightTexture blurred;
    std::vector<Rect> blur_pending;  // texels traced since the last blur
    std::uint64_t blur_surface_ids = 0;  // the surface_ids_revision the blur stayed within

    // The final image's inputs.
    bool has_final = false;
    Params composite_params;
};

}  // namespace isolux
