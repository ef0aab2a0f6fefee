// The app's frame: core's pipeline with the chosen tracer (CPU, or the GPU's
// compute shader), the 3D reference for the truth overlays, the budget on
// tracing work and approved long work on a worker thread, and the Stats
// panel's figures. main.cpp's loop calls render_app_frame once a frame.
#pragma once
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "isolux/frame.hpp"
#include "isolux/light_texture.hpp"

namespace isolux::app {

struct App;

// Work beyond huge_trace_steps waits for the user's word (the CLI's
// --allow-huge): the frame is not traced until then.
struct HugeWork {
    bool asking = false;
    double steps = 0;
    bool approved = false;
    Params approved_params;
    std::size_t approved_lights = 0;
    bool declined = false;  // "Not now" or Cancel: these parameters stay untraced, unasked, until they change
    Params declined_params;
    // How a script answers the prompt (script command long-work): undo
    // the change (the default), trace it, or trace it and press Cancel
    // once the work is under way.
    std::string script_answer = "undo";
};
// Approved long work runs on a worker thread with the CPU tracer, whose
// rays check for Cancel every 64 rays, while the window shows only its
// progress (long_work_prompt): the worker reads the document, so nothing
// else may edit it meanwhile.
struct LongTrace {
    std::thread worker;
    std::atomic<bool> cancel{false}, finished{false};
    std::atomic<std::int64_t> done{0};  // trace_work's steps so far
    double total = 0;                   // trace_work's estimate for the frame
    double started = 0;                 // App::now when it began
    double seconds = 0;                 // how long the worker took, once finished
    FrameReport report;                 // once finished, not cancelled
    bool cancelled = false;
    std::string error;
    bool running() const { return worker.joinable() && !finished.load(); }
};

// The 3D reference over the view, for the truth overlays and the 2.5D | 3D
// split: recomputed only when what it shows changed.
struct TruthCache {
    bool valid = false;
    Params params;
    std::vector<Light> lights;
    Rect view;
    std::uint64_t revision = 0;
    LightTexture texture;
};

// Whether the GPU tracer traces (the setting, --tracer, and the driver).
bool gpu_tracer_chosen(const App& app);

// One frame of the pipeline: core traces, the renderer does the rest.
// `screenshot_mode`: the frame is the scene's camera, as isolux-cli's.
FrameReport render_app_frame(App& app, bool screenshot_mode);

// One frame's figures for the Stats panel: the stages that ran, their
// times, the frame's own time (`frame_ms`) and the loop's rate (`dt`).
void push_stats(App& app, const FrameReport& rep, double frame_ms, double dt);

// Stops a long trace the window is closing on (its work is thrown away).
void stop_long_trace(App& app);

}  // namespace isolux::app
