// The Accuracy panel: a parameter sweep in a background thread, error plotted
// against time, a click applies a point's parameters, and a heat map of the
// current frame's error against the reference.
#pragma once
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "editor/overlays.hpp"
#include "isolux/accuracy.hpp"

namespace isolux::app {

struct App;

struct AccuracyPanel {
    bool open = false;
    std::string axes[4] = {"ray_skip=1,2,4,8", "blur_radius=0,1,2", "trace_every=1,2,4", ""};
    int frames = 6, repeats = 2;
    Reference reference = Reference::three_d;  // what the sweep and the heat map measure against

    // The running sweep: its thread writes these, the UI reads them.
    std::thread worker;
    std::atomic<bool> running{false}, cancel{false};
    std::atomic<int> done{0}, total{0};
    std::mutex mutex;
    std::vector<SweepAxis> result_axes;
    std::vector<SweepPoint> results;
    std::string error;
    // A sweep beyond the work budget waits for "Run anyway": its estimate,
    // 0 when nothing waits.
    double over_budget = 0;

    // The heat map of |final - reference| for the current view.
    bool heatmap = false;
    bool heatmap_stale = true;
    OverlayImage heat;
    ErrorMetrics heat_metrics;

    ~AccuracyPanel();
};

void accuracy_panel(App& app, AccuracyPanel& panel);

// What the panel's buttons do, for the panel and for scripted input.
// false (and panel.error) on a bad axis, or when its work (sweep_work) is
// beyond huge_trace_steps and not `allow_huge` (then panel.over_budget).
bool start_sweep(App& app, AccuracyPanel& panel, bool allow_huge = false);
bool apply_sweep_point(App& app, AccuracyPanel& panel, std::size_t index);  // one undo step
// The "Occluder resolution" button: axes occluder_scale 1, 2, 4 (and
// occluders solids, shapes when the scene uses footprints, on which the
// scale does nothing), against 3d.
void set_occluder_resolution_axes(const App& app, AccuracyPanel& panel);

// The heat map for the app's current view and settings against `reference`
// (CPU, both frames fresh).
OverlayImage error_heatmap(const World& world, const Scene& scene, Rect view, Reference reference,
                           ErrorMetrics* metrics);

}  // namespace isolux::app
