// The app's frame: core's pipeline with the chosen tracer (CPU, or the GPU's
// compute shader), the 3D reference for the truth overlays, the budget on
// tracing work and approved long work on a worker thread, and the Stats
// panel's figures. main.cpp's loop calls render_app_frame once a frame.
#pragma once
#include "gui/app.hpp"

namespace isolux::app {

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
