#include "gui/accuracy_panel.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gui/app.hpp"
#include "isolux/composite.hpp"
#include "isolux/error.hpp"

namespace isolux::app {

AccuracyPanel::~AccuracyPanel() {
    cancel = true;
    if (worker.joinable()) worker.join();
}

OverlayImage error_heatmap(const World& world, const Scene& scene, Rect view, Reference reference,
                           ErrorMetrics* metrics) {
    const Camera cam{double(view.x), double(view.y), view.w, view.h};
    FrameState test;
    render_frame(test, world, scene, cam, 0);
    const Params rp = reference_params(scene.params);
    Scene rs = scene;
    rs.params = rp;
    struct {
        Image final;
    } ref{composite(render_sprites(world.tileset, world.placed, view), view,
                    reference_texture(world, rs, view, reference), rp)};
    if (metrics) *metrics = compare_images(test.final, ref.final);
    OverlayImage out;
    out.rect = view;
    out.image = Image(view.w, view.h);
    for (std::size_t i = 0; i < std::size_t(view.w) * view.h; ++i) {
        int d = 0;
        for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(test.final.rgba[i * 4 + k]) - int(ref.final.rgba[i * 4 + k])));
        if (d == 0) continue;
        // Yellow to red as the error grows; 16/255 and above saturate.
        const float t = std::min(1.0f, d / 16.0f), a = 0.35f + 0.6f * t;
        std::uint8_t* p = &out.image.rgba[i * 4];
        p[0] = std::uint8_t(255 * a);
        p[1] = std::uint8_t(255 * (1 - t) * a);
        p[2] = 0;
        p[3] = std::uint8_t(255 * a);
    }
    return out;
}

namespace {
std::string label_of(const std::vector<SweepAxis>& axes, const SweepPoint& p);
}  // namespace

bool start_sweep(App& app, AccuracyPanel& panel, bool allow_huge) {
    std::vector<SweepAxis> axes;
    try {
        for (const std::string& text : panel.axes)
            if (!text.empty()) axes.push_back(parse_sweep_axis(text, app.editor.scene.params, "sweep"));
    } catch (const Error& e) {
        panel.error = e.what();
        return false;
    }
    if (panel.worker.joinable()) panel.worker.join();
    panel.error.clear();
    panel.over_budget = 0;
    panel.running = true;
    panel.cancel = false;
    panel.done = 0;
    panel.total = 1;
    // The sweep owns copies: the user may regenerate or edit while it runs.
    auto world = std::make_shared<World>(app.editor.world);
    Scene scene = render_scene(app.editor);
    scene.camera = {double(app.view.x), double(app.view.y), std::min(app.view.w, 960), std::min(app.view.h, 640)};
    SweepOptions opt;
    opt.frames = panel.frames;
    opt.repeats = panel.repeats;
    opt.references = {panel.reference};
    // The CLI's budget: beyond it, "Run anyway" (isolux-cli's --allow-huge).
    const double steps = sweep_work(app.editor.world, scene, axes, opt);
    if (steps > huge_trace_steps && !allow_huge) {
        char text[200];
        std::snprintf(text, sizeof text, "this sweep would trace about %.2g ray steps (minutes or more)", steps);
        panel.error = text;
        panel.over_budget = steps;
        panel.running = false;
        return false;
    }
    panel.worker = std::thread([&panel, world, scene, axes, opt] {
        std::vector<SweepPoint> points;
        std::string error;
        try {
            points = run_sweep(*world, scene, axes, opt, [&](int d, int t) {
                panel.done = d;
                panel.total = t;
            }, &panel.cancel);
        } catch (const std::exception& e) {
            error = e.what();
        }
        std::lock_guard<std::mutex> lock(panel.mutex);
        panel.result_axes = axes;
        panel.results = std::move(points);
        panel.error = error;
        panel.running = false;
    });
    return true;
}

void set_occluder_resolution_axes(const App& app, AccuracyPanel& panel) {
    const bool footprints = app.editor.scene.params.occluders == Occluders::footprints;
    panel.axes[0] = "occluder_scale=1,2,4";
    panel.axes[1] = footprints ? "occluders=solids,shapes" : "";
    panel.axes[2] = panel.axes[3] = "";
    panel.reference = Reference::three_d;
    panel.heatmap_stale = true;
}

bool apply_sweep_point(App& app, AccuracyPanel& panel, std::size_t index) {
    if (index >= panel.results.size()) return false;
    const SweepPoint& point = panel.results[index];
    Params p = app.editor.scene.params;
    for (std::size_t i = 0; i < panel.result_axes.size(); ++i)
        set_param(p, panel.result_axes[i].name, point.values[i], "sweep");
    set_params(app.editor, p, app.now);
    set_status(app.editor, "applied " + label_of(panel.result_axes, point));
    return true;
}

namespace {

std::string label_of(const std::vector<SweepAxis>& axes, const SweepPoint& p) {
    std::string s;
    for (std::size_t i = 0; i < axes.size() && i < p.values.size(); ++i)
        s += (i ? " " : "") + axes[i].name + "=" + p.values[i];
    return s;
}

}  // namespace

void accuracy_panel(App& app, AccuracyPanel& panel) {
    if (!panel.open) return;
    {
        // Opens over the map, inside the window whatever its size.
        const Rect fl = app.ui.layout.floating;
        ImGui::SetNextWindowPos(ImVec2(float(fl.x), float(fl.y)), ImGuiCond_Appearing);
        ImGui::SetNextWindowSize(ImVec2(float(fl.w), float(fl.h)), ImGuiCond_Appearing);
    }
    if (!ImGui::Begin("Accuracy", &panel.open)) return ImGui::End();
    ImGui::TextWrapped("Time and error of parameter combinations against a reference, over the current view "
                       "with the camera moving. 3d: the sprites' true shapes, lights at their height; every_pixel: "
                       "the model's own 4ab rays; exact_line: each pixel's own Bresenham line.");
    {
        static const char* names[] = {"every_pixel", "exact_line", "3d", "3d_facing", "3d_shaded"};
        int r = int(panel.reference);
        ImGui::SetNextItemWidth(160);
        if (ImGui::Combo("reference", &r, names, 5)) {
            panel.reference = Reference(r);
            panel.heatmap_stale = true;
        }
    }
    for (int i = 0; i < 4; ++i) {
        ImGui::SetNextItemWidth(300);
        ImGui::InputText(("axis " + std::to_string(i + 1)).c_str(), &panel.axes[i]);
    }
    // What the occluders' resolution costs and saves: the knob swept
    // against the 3D truth, with the occluders it acts on.
    if (ImGui::Button("Occluder resolution")) set_occluder_resolution_axes(app, panel);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Sets the axes to occluder_scale 1, 2 and 4 (with solids and shapes when the scene uses "
                          "footprints) against 3d: each point's error beside its time.");
    ImGui::SetNextItemWidth(120);
    ImGui::SliderInt("frames", &panel.frames, 1, 30);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120);
    ImGui::SliderInt("repeats", &panel.repeats, 1, 7);
    if (!panel.running && panel.over_budget > 0) {
        // It runs on its own thread with progress and Cancel, but for minutes: ask first.
        if (ImGui::Button("Run anyway")) start_sweep(app, panel, true);
        ImGui::SameLine();
        if (ImGui::Button("Not now")) panel.over_budget = 0, panel.error.clear();
    } else if (!panel.running) {
        if (ImGui::Button("Run sweep")) start_sweep(app, panel);
    } else {
        if (ImGui::Button("Cancel")) panel.cancel = true;
        ImGui::SameLine();
        const float f = panel.total > 0 ? float(panel.done) / float(panel.total) : 0.0f;
        ImGui::ProgressBar(f, ImVec2(-1, 0), (std::to_string(panel.done) + "/" + std::to_string(panel.total)).c_str());
    }
    std::unique_lock<std::mutex> lock(panel.mutex);
    if (!panel.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", panel.error.c_str());

    // Error (final RMSE) against lighting time; orange: the Pareto front.
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 260);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("plot", size);
    const bool hovered_plot = ImGui::IsItemHovered();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(p0, ImVec2(p0.x + size.x, p0.y + size.y), IM_COL32(25, 27, 32, 255));
    const auto& pts = panel.results;
    if (!pts.empty()) {
        double tmin = 1e300, tmax = 0, emax = 0;
        for (const SweepPoint& p : pts) {
            tmin = std::min(tmin, p.lighting_ms);
            tmax = std::max(tmax, p.lighting_ms);
            emax = std::max(emax, p.final.rmse);
        }
        tmin = std::max(tmin, 1e-4);
        emax = std::max(emax * 1.1, 1e-6);
        auto fx = [&](double t) {
            const double u = tmax > tmin ? (std::log(std::max(t, 1e-4)) - std::log(tmin)) / (std::log(tmax) - std::log(tmin)) : 0.5;
            return p0.x + 30 + float(u) * (size.x - 50);
        };
        auto fy = [&](double e) { return p0.y + size.y - 20 - float(e / emax) * (size.y - 35); };
        const std::vector<const SweepPoint*> front = pareto_front(pts);  // one reference per sweep here
        for (std::size_t i = 1; i < front.size(); ++i)
            dl->AddLine(ImVec2(fx(front[i - 1]->lighting_ms), fy(front[i - 1]->final.rmse)),
                        ImVec2(fx(front[i]->lighting_ms), fy(front[i]->final.rmse)), IM_COL32(224, 112, 32, 255), 1.5f);
        const ImVec2 m = ImGui::GetIO().MousePos;
        const SweepPoint* nearest = nullptr;
        float best = 64.0f;
        for (const SweepPoint& p : pts) {
            const ImVec2 c(fx(p.lighting_ms), fy(p.final.rmse));
            dl->AddCircleFilled(c, p.pareto ? 5.0f : 3.5f, p.pareto ? IM_COL32(224, 112, 32, 255) : IM_COL32(90, 140, 220, 255));
            const float d = (c.x - m.x) * (c.x - m.x) + (c.y - m.y) * (c.y - m.y);
            if (hovered_plot && d < best) best = d, nearest = &p;
        }
        dl->AddText(ImVec2(p0.x + 4, p0.y + 2), IM_COL32(200, 200, 200, 255), "final RMSE");
        dl->AddText(ImVec2(p0.x + size.x - 190, p0.y + size.y - 16), IM_COL32(200, 200, 200, 255),
                    "lighting ms / frame (log)");
        if (nearest) {
            ImGui::BeginTooltip();
            ImGui::Text("%s", label_of(panel.result_axes, *nearest).c_str());
            ImGui::Text("%.3f ms lighting, %.3f ms in all", nearest->lighting_ms, nearest->total_ms);
            ImGui::Text("final: RMSE %.3f, PSNR %.1f dB, max %d, lit mismatch %.2f%%", nearest->final.rmse,
                        nearest->final.psnr, nearest->final.max_abs, nearest->light.lit_mismatch * 100);
            ImGui::Text("in the lights' areas, lit mismatch: ground %.1f%%, sprites %.1f%%",
                        nearest->floor.lit_mismatch * 100, nearest->sprite.lit_mismatch * 100);
            ImGui::Text("CPU in the app %.3f ms; CPU renderer only (blur, shift, composite) %.3f ms",
                        nearest->app_cpu_ms, nearest->cpu_only_ms);
            ImGui::TextDisabled("click to apply these parameters");
            ImGui::EndTooltip();
            if (ImGui::IsMouseClicked(0)) apply_sweep_point(app, panel, std::size_t(nearest - pts.data()));
        }
    } else {
        dl->AddText(ImVec2(p0.x + 10, p0.y + 10), IM_COL32(150, 150, 150, 255), "run a sweep to see error against time");
    }
    ImGui::Separator();
    if (ImGui::Checkbox("error heat map", &panel.heatmap)) panel.heatmap_stale = true;
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("The current frame's per-pixel error against the reference, yellow to red (16/255 and more).");
    if (panel.heatmap) {
        ImGui::SameLine();
        if (ImGui::Button("Recompute")) panel.heatmap_stale = true;
        ImGui::Text("RMSE %.3f  max %d  differing %.2f%%", panel.heat_metrics.rmse, panel.heat_metrics.max_abs,
                    panel.heat_metrics.differing * 100);
    }
    ImGui::End();
}

}  // namespace isolux::app
