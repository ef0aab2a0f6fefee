// Paper Algorithm 2 as an OpenGL 4.3 compute shader (shaders/trace.comp):
// the same bytes as core's trace_light, held to it by tests/gl_test.cpp. The
// app lets the frame call it through FrameOptions::tracer.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gui/gl.hpp"
#include "isolux/light_trace.hpp"

namespace isolux::app {

struct GpuTracer {
    GLuint program = 0, obstacles = 0, lit = 0, reached = 0, targets = 0, falloff = 0;
    std::uint64_t obstacles_revision = ~0ull;  // what `obstacles` holds
    Rect obstacles_rect;
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

}  // namespace isolux::app
