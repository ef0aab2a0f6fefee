// Paper Algorithm 2 as an OpenGL 4.3 compute shader (shaders/trace.comp):
// the same bytes as core's trace_light, held to it by tests/app/gpu/gl_test.cpp; and
// both passes against solids with height (shaders/trace_solids.comp,
// sprite_points.comp, start_layers.comp), the same bytes as core's
// trace_light_solids and light_sprite_points. The app lets the frame call them
// through FrameOptions::tracer.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/gl.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/occluder_map.hpp"

namespace isolux::app {

// The ray targets of each light extent (a, b) a GPU tracer keeps: a run
// (first, count) of offsets from the centre each, for these rays.
struct RayRuns {
    using Key = std::array<int, 2>;
    std::map<Key, std::array<GLint, 2>> run;
    std::vector<GLint> targets;  // x, y pairs
    Rays rays = Rays::border;
    int skip = -1;
};

struct GpuTracer {
    GLuint program = 0, obstacles = 0, lit = 0, reached = 0, targets = 0, falloff = 0;
    std::uint64_t obstacles_revision = ~0ull;  // what `obstacles` holds
    Rect obstacles_rect;
    GLuint solids_program = 0, spans = 0, overflow = 0;
    std::uint64_t spans_revision = ~0ull;  // what `spans` holds
    GLuint points_program = 0, shown_start = 0, shown = 0;  // the sprite pass
    std::uint64_t shown_revision = ~0ull;  // what `shown_start` and `shown` hold
    GLuint start_program = 0, surface_height = 0, surface_sprite = 0;  // each light's layer started (start_layers.comp)
    std::uint64_t surface_revision = ~0ull;  // what `surface_height` and `surface_sprite` hold
    Rect surface_rect;
    // A frame's lights against solids, traced together: their records, rays
    // and falloff, and one layer each of `layers` (layers_w x layers_h x
    // layer_count) for their masks.
    GLuint lights = 0, ray_targets = 0, layers = 0;
    RayRuns rays;  // what ray_targets holds
    int layers_w = 0, layers_h = 0, layer_count = 0;
    GLint max_layers = 0;  // GL_MAX_ARRAY_TEXTURE_LAYERS
    bool get_sub_image = false;  // glGetTextureSubImage (GL 4.5): a batch reads back its own layers alone
    Rect spans_rect;
    GLint max_storage = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
    int lit_w = 0, lit_h = 0;
    GLint max_texture = 0;
    std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
};

// Needs a current GL context with compute shaders (4.3, or
// ARB_compute_shader). False, with the reason, when there are none.
bool gpu_tracer_init(GpuTracer& t, std::string& error);
void gpu_tracer_free(GpuTracer& t);

// Whether the context is a software rasteriser (Mesa's llvmpipe, softpipe,
// swrast): there the CPU tracer is faster, and the automatic choice takes it.
bool gpu_tracer_is_software(const GpuTracer& t);

// Traces every mask (clip, centre and a, b set; value, and reached in shadow
// mode, sized) with `p`'s mode, rays and falloff. Returns false, leaving
// them, for what it does not do: rays over obstacles, centres beyond int
// range, or textures larger than the GPU allows.
bool gpu_trace(GpuTracer& t, const Mask& obstacles, std::uint64_t obstacles_revision,
               const std::vector<LightMask*>& masks, const Params& p);

// Traces the ground pass against solids with height (occluders solids or
// shapes; light and shadow modes) into every mask, each light at its
// `heights` entry: trace_light_solids's bytes, `occluders_revision` changing
// whenever the occluder map does; with `sprite_points`, the sprite pass
// after it too (light_sprite_points's bytes, its pixels no ray reaches
// included). All the lights go in one dispatch a pass (in
// batches of at most max_layers lights and 64 MiB of masks) and come back
// in one read-back a batch. False, leaving the masks to the CPU, for what it
// does not do: centres beyond int range, an occluder map larger than a
// storage buffer, or a ray with more live shades than the shader holds.
bool gpu_trace_solids(GpuTracer& t, const OccluderMap& occluders, std::uint64_t occluders_revision,
                      const std::vector<LightMask*>& masks, const std::vector<double>& heights, const Params& p,
                      bool sprite_points);

// What FrameOptions::tracer calls: gpu_trace_solids with occluders,
// gpu_trace without; "gpu" when it traced them, "" to leave them to the CPU.
std::string_view gpu_trace_frame(GpuTracer& t, const Mask& obstacles, std::uint64_t obstacles_revision,
                                 const OccluderMap* occluders, const std::vector<LightMask*>& masks,
                                 const std::vector<double>& heights, const Params& p, bool sprite_points);

}  // namespace isolux::app
