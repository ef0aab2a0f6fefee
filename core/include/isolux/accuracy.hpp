// Accuracy against time: error metrics against a reference (truth.hpp: the
// model's every-pixel rays, the exact 2D line, or the true 3D shapes), and
// parameter sweeps that time every stage.
#pragma once
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "isolux/frame.hpp"
#include "isolux/truth.hpp"

namespace isolux {

struct ErrorMetrics {
    double lit_mismatch = 0;  // share of pixels lit (> 0) in one and not in the other
    double differing = 0;     // share of pixels that differ in any channel
    int max_abs = 0;          // largest channel difference, 0..255
    double rmse = 0;          // root mean square error, in 0..255 units
    double psnr = 0;          // peak 255; +inf when identical
};

// Compares a light texture (or an image) with the reference over the same
// rectangle. RMSE, PSNR and the maximum come from OpenImageIO's
// ImageBufAlgo::compare; the shares are counted here. PSNR alone hides wrong
// shadows (most texels of 255/(1+d) are tiny), so all five are reported.
ErrorMetrics compare_light(const LightTexture& test, const LightTexture& ref);
ErrorMetrics compare_images(const Image& test, const Image& ref);

// The reference's parameters for `p`: everything as `p` but rays every_pixel,
// ray_skip 1, blur_radius 0, trace_every 1.
Params reference_params(Params p);

struct SweepAxis {
    std::string name;                 // a preset parameter name
    std::vector<std::string> values;  // as text, e.g. {"1", "2", "4"}
};

// Parses "NAME=V1,V2,..." and checks every value against `base` (so a bad
// axis fails before any work); throws Error naming `source`.
SweepAxis parse_sweep_axis(std::string_view text, const Params& base, std::string_view source);

// Errors inside the lights' areas on one kind of pixel (the ground, or
// overlay sprites), the model's view light texture against the reference's.
struct AreaErrors {
    double lit_mismatch = 0;  // share of the pixels lit (> 0) in one and not the other
    double rmse = 0;          // 0..255 units
    long pixels = 0;          // pixels counted (per frame, mean)
};

// Splits the comparison of two light textures over `surface.rect` by pixel
// kind, counting only pixels inside one of `areas`.
void compare_in_areas(const LightTexture& model, const LightTexture& ref, const Surface& surface,
                      const std::vector<Rect>& areas, AreaErrors& floor, AreaErrors& sprite, AreaErrors& all);

struct SweepPoint {
    Params params;
    std::vector<std::string> values;    // one per axis, as given
    Reference reference = Reference::every_pixel;
    std::array<double, stage_count> ms{};  // median time per frame of each stage
    double total_ms = 0;                 // every stage
    double lighting_ms = 0;              // the lighting's own stages: all but sprites and composite
                                         // (the same for every setting; on the GPU in the app)
    double lighting_min_ms = 0, lighting_max_ms = 0;  // its spread over the repeats
    double app_cpu_ms = 0;    // what the app runs on the CPU: obstacle map, trace, opacity correction
    double cpu_only_ms = 0;   // what only the CPU renderer runs (the app's GPU does it): blur, shift, composite
    ErrorMetrics light, final;           // means over frames over the whole view (max_abs: the max)
    AreaErrors floor, sprite, area;      // inside the lights' areas: ground, sprites, both
    bool pareto = false;                 // least final RMSE for its lighting time, among its reference's points
};

// The most bytes of reference frames a sweep keeps for the combinations that
// share them; beyond it a reference is made again when asked for.
inline constexpr std::size_t reference_cache_bytes = std::size_t(256) << 20;

struct SweepOptions {
    int frames = 8;       // frames per run; the camera moves along its path
    int repeats = 3;      // runs per combination; times are medians over runs
    double step_x = 24, step_y = 12;  // camera movement per frame, world pixels
    bool carry_light = true;  // a light at the view's centre moves with the camera
    bool opacity_correction = true;  // off: the paper's Figure 6, measured (FrameOptions::opacity_correction)
    // Each combination is measured against each reference (one CSV row each).
    std::vector<Reference> references = {Reference::every_pixel};
    // Called with every point measured so far, each time one is added (not
    // yet marked for the Pareto front): a caller writes its rows as they
    // come, so a sweep stopped or failed midway keeps the work it did.
    std::function<void(const std::vector<SweepPoint>&)> rows_so_far;
};


// Runs every combination of the axes' values over `scene` (its camera as the
// path's start; width 0 means the whole map). Throws Error on an unknown
// parameter or a bad value. `progress(done, total)` is called after each
// combination; `cancel` (optional) stops early, within a frame's trace too,
// and the combinations done so far are returned.
std::vector<SweepPoint> run_sweep(const World& world, const Scene& scene, const std::vector<SweepAxis>& axes,
                                  const SweepOptions& options,
                                  const std::function<void(int, int)>& progress = {},
                                  const std::atomic<bool>* cancel = nullptr);

// A sweep's work at most, in trace_work's steps, before any of it starts: the
// costliest combination's frames (rays and view pixels, as render_work) on
// every run, and each frame's references (reference_work), times the
// combinations and frames; the light the camera carries included. Compared
// with huge_trace_steps by isolux-cli and the app alike.
double sweep_work(const World& world, const Scene& scene, const std::vector<SweepAxis>& axes, const SweepOptions& options);

// Marks the points on the Pareto front of (lighting_ms, final RMSE), one front
// per reference.
void mark_pareto(std::vector<SweepPoint>& points);
// The marked points, fastest first (a chart's line, a report's list).
std::vector<const SweepPoint*> pareto_front(const std::vector<SweepPoint>& points);

// CSV, one row per combination (isolux-cli's sweep draws its SVG chart,
// app/cli/sweep_chart.hpp). `pareto_known` false (a sweep under way): the
// pareto column is left empty.
std::string sweep_csv(const std::vector<SweepAxis>& axes, const std::vector<SweepPoint>& points,
                      bool pareto_known = true);

}  // namespace isolux
