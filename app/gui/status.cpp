// The Stats panel and the status bar: status.hpp.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "gui/app.hpp"
#include "gui/dialogs.hpp"
#include "editor/file_browser.hpp"
#include "gui/menu_bar.hpp"
#include "gui/status.hpp"
#include "gui/viewport.hpp"
#include "gui/widgets.hpp"
#include "isolux/blur.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

void stats_panel(App& app) {
    if (!app.editor.settings.show_stats) return;
    dock(app, "Stats");
    if (!ImGui::Begin("Stats", &app.editor.settings.show_stats)) return ImGui::End();
    const Stats& s = app.stats;
    ImGui::TextWrapped("%.1f FPS: %.2f ms a frame, lighting %.2f ms of it", s.fps(), s.loop_ms, s.frame_ms);
    help("The rate and the frame's time are one average over the same frames (the whole loop: input, lighting, "
         "panels, drawing); lighting is the pipeline's share of it (the stages below).");
    ImGui::Text("%d lights traced", s.lights_traced);
    ImGui::Text("tracer: %s", s.tracer.empty() ? "none yet" : s.tracer == "gpu" ? "GPU (compute shader)" : "CPU");
    help("Which tracer traced the last traced frame: set under View › Tracer. Automatic takes the GPU's compute shader "
         "unless the GL driver is a software renderer (Mesa's llvmpipe), where the CPU is faster. Both give the same "
         "pixels.");
    const Rect& rb = s.last_rebuilt;
    ImGui::Text("last rebuilt: %d x %d px at (%d, %d)", rb.w, rb.h, rb.x, rb.y);
    help("The world rectangle whose obstacle map was last rebuilt: around the edited tiles after a terrain edit, the "
         "whole region the lights need after a change of Δy, n, the threshold or the map.");
    std::string ran = "ran:";
    for (int k = 0; k < stage_count; ++k)
        if (s.last_ran[k]) ran += std::string(" ") + std::string(to_string(Stage(k)));
    static const char* gpu[4] = {"upload", "sprites(gpu)", "blur(gpu)", "composite(gpu)"};
    for (int k = 0; k < 4; ++k)
        if (s.gpu_ran[k]) ran += std::string(" ") + gpu[k];
    if (ran == "ran:") ran += " nothing (a still frame)";
    ImGui::TextWrapped("%s", ran.c_str());
    static const char* names[Stats::series] = {"sprites (cpu)", "obstacle map", "trace", "opacity correction",
                                               "blur (cpu)", "shift", "composite (cpu)", "upload",
                                               "sprites (gpu)", "blur (gpu)", "composite (gpu)"};
    for (int k = 0; k < Stats::series; ++k) {
        if (k == int(Stage::sprites) || k == int(Stage::blur) || k == int(Stage::composite)) continue;  // on the GPU here
        const auto& v = s.ms[k];
        float latest = v[(s.head + Stats::frames - 1) % Stats::frames];
        float peak = *std::max_element(v.begin(), v.end());
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "%.3f ms (max %.2f)", latest, peak);
        ImGui::PlotLines(names[k], v.data(), Stats::frames, s.head, overlay, 0.0f, std::max(0.1f, peak), ImVec2(170, 26));
    }
    ImGui::End();
}

void status_bar(App& app) {
    const Editor& e = app.editor;
    ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - 26));
    ImGui::SetNextWindowSize(ImVec2(vp->Size.x, 26));
    ImGui::Begin("##status", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus);
    int col = -1, row = -1;
    const bool on_tile = app.ui.viewport.cursor_in_view &&
                         tile_at(e.world.map, e.world.placed, app.ui.viewport.cursor_x, app.ui.viewport.cursor_y, col, row);
    const WorldOffset o = world_offset(e);
    ImGui::Text("world (%.0f, %.0f)  tile %s  |  %.0f FPS  %.2f ms  |  zoom %.2f  |  %s%s", app.ui.viewport.cursor_x + o.x,
                app.ui.viewport.cursor_y + o.y,
                on_tile ? (std::to_string(col + o.col) + ", " + std::to_string(row + o.row)).c_str() : "-",
                app.stats.fps(), app.stats.loop_ms, e.view.zoom, e.dirty ? "unsaved  |  " : "", "");
    ImGui::SameLine();
    if (e.status_error) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", e.status.c_str());
    else ImGui::TextUnformatted(e.status.c_str());
    if (!app.renderer.shader_error.empty()) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "shader: %s", app.renderer.shader_error.c_str());
    }
    ImGui::End();
}

}  // namespace isolux::app
