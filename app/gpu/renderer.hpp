// The GPU side of a frame: sprites drawn from an atlas, the light texture
// uploaded when it was retraced, blur.frag and composite.frag (mirrors of
// core's box_blur and composite), then the view presented with pan, zoom and
// overlays. Needs a current GL 3.3 core context.
#pragma once
#include <array>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/gl.hpp"
#include "isolux/blur.hpp"
#include "isolux/image.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/params.hpp"
#include "isolux/world.hpp"

namespace isolux::app {

struct GpuTarget {
    GLuint fbo = 0, tex = 0;
    int w = 0, h = 0;
    GLenum internal_format = GL_RGBA8;
};

struct GpuProgram {
    GLuint id = 0;
};

// What the composite shows.
struct CompositeOptions {
    bool show_light = false;  // the light texture alone (the "raw light texture" overlay)
    int split = -1;           // >= 0: view column where flat lighting starts (Figure 10)
};

// GPU time of each stage of the last measured frame, milliseconds.
struct GpuTimes {
    double upload = 0, sprites = 0, blur = 0, composite = 0;
};

struct Renderer {
    // Shaders, reloaded from `shader_dir` when a file changes.
    std::filesystem::path shader_dir;
    std::filesystem::file_time_type shader_stamp{};
    GpuProgram sprites, blur, composite, present;
    std::string shader_error;  // the last compile or link error; empty when all compiled

    GLuint vao = 0, instance_vbo = 0;
    GLsizei instance_count = 0;
    GLuint atlas = 0;
    int atlas_w = 0, atlas_h = 0;
    std::vector<std::array<int, 2>> atlas_pos;  // each sprite's top-left in the atlas
    std::uint64_t atlas_built = ~0ull;          // the World::built_revision the atlas holds
    std::uint64_t world_revision = ~0ull;

    GLuint light_tex = 0, flat_tex = 0, overlay_tex = 0;
    Rect light_rect, flat_rect, overlay_rect;
    GpuTarget color, blur_sums, blurred, final;
    bool blur_valid = false;
    Params blur_params;  // what `blurred` was made with
    bool light_dirty = true;
    // With the blur within surfaces (isolux::blur_within_surfaces): which
    // surface each pixel of surface_rect shows (R32I, world pixels), and
    // the FrameState::surface_ids_revision it holds; 0: the plain blur.
    GLuint surface_tex = 0;
    Rect surface_rect;
    std::uint64_t surface_revision = 0;

    // What the last renderer_draw ran: a pass is skipped when its inputs did
    // not change (the view, the world, the light texture, the parameters).
    struct Ran {
        bool sprites = false, blur = false, composite = false;
    } ran;
    Rect sprites_view;
    std::uint64_t sprites_revision = ~0ull;
    bool composite_valid = false;
    Rect composite_view;
    Params composite_params;
    int composite_show = -1, composite_split = -2;

    GLuint queries[3] = {0, 0, 0};  // sprites, blur, composite
    bool query_pending[3] = {false, false, false};
    GpuTimes times;
};

// Compiles the shaders and creates the GL objects. False with `error` set on failure.
bool renderer_init(Renderer& r, std::string& error);
void renderer_shutdown(Renderer& r);

// Recompiles when a shader file changed; a failed compile keeps the last good
// program and sets shader_error. Returns true when something was reloaded.
bool renderer_reload_shaders(Renderer& r, bool force = false);

// Builds the atlas (when the world was rebuilt) and the instance buffer (after
// any change, edits included) for the world's sprites, in draw order.
void renderer_set_world(Renderer& r, const World& world);

// Uploads the world-anchored light texture (after tracing and the opacity
// correction). `dirty` limits the upload to a rectangle when the texture's
// rectangle is unchanged. Returns the upload's CPU time in ms.
double renderer_upload_light(Renderer& r, const LightTexture& tex, Rect dirty);
void renderer_upload_flat_light(Renderer& r, const LightTexture& tex);
// Uploads which surface each pixel shows (FrameState::surface_ids, over the
// occluders' region) when `revision` is new; empty ids (revision 0): the
// plain blur. The blur runs again when they change.
void renderer_upload_surface_ids(Renderer& r, const SurfaceIds& ids, std::uint64_t revision);
// Uploads an RGBA overlay (premultiplied) covering `rect` in world pixels.
void renderer_upload_overlay(Renderer& r, const Image& overlay, Rect rect);

// Draws the view's sprites, blurs the light texture when it changed and
// composites into the `final` target (view-sized, one texel a world pixel).
void renderer_draw(Renderer& r, Rect view, const Params& p, const CompositeOptions& o);

// For tests: replace the sprite pass's output with a CPU image (straight alpha).
void renderer_draw_with_colour(Renderer& r, const Image& colour, Rect view, const Params& p, const CompositeOptions& o);

// Draws `final` onto the window: the view's top-left at window pixel (x, y),
// `zoom` window pixels per world pixel, with the overlay image over it (each
// overlay already blended at its own opacity by build_overlays).
void renderer_present(Renderer& r, int window_w, int window_h, double x, double y, double zoom, Rect view);

// Reads the final target back (top row first, straight alpha).
Image renderer_read_final(Renderer& r);
Image renderer_read_blurred(Renderer& r);
// The window as drawn so far this frame, panels included (top row first, opaque).
Image renderer_read_window(int width, int height);  // the blurred light texture, RGB in rgba, A = 255

}  // namespace isolux::app
