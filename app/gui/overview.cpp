// The Overview window: overview.hpp.
#include "gui/overview.hpp"

#include <imgui.h>

#include "gui/app.hpp"
#include "gui/widgets.hpp"

namespace isolux::app {

void overview_panel(App& app) {
    const Editor& e = app.editor;
    if (!e.scene.endless) return;
    const Rect free = app.ui.layout.free;
    constexpr float side = 200;
    const ImGuiCond cond = app.ui.reset_layout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(ImVec2(float(free.x + free.w) - side - 24, float(free.y) + 8), cond);
    ImGui::SetNextWindowSize(ImVec2(side + 16, side + 86), cond);
    if (!ImGui::Begin("Overview")) return ImGui::End();
    constexpr int radius = 4;
    const Overview o = endless_overview(e, radius);
    ImGui::Text("tile (%lld, %lld)", (long long)o.col, (long long)o.row);
    ImGui::Text("chunk (%lld, %lld) of %dx%d tiles", (long long)o.cx, (long long)o.cy, chunk_tiles, chunk_tiles);
    help("Chunks around the view, one square each (the view's in the middle, outlined): filled where the window "
         "around the view holds them, with a dot for hand edits (orange) and lights (yellow). Chunks are made as "
         "the view moves; saving keeps the seed, edits and lights, never the chunks.");
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const int n = 2 * radius + 1;
    const float cell = side / float(n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const OverviewChunk& c = o.chunks[std::size_t(j * n + i)];
            const ImVec2 a(p.x + i * cell, p.y + j * cell), b(a.x + cell - 1, a.y + cell - 1);
            dl->AddRectFilled(a, b, c.in_window ? IM_COL32(70, 110, 80, 255) : IM_COL32(40, 40, 48, 255));
            if (c.edits > 0) dl->AddCircleFilled(ImVec2(a.x + cell * 0.3f, a.y + cell * 0.5f), 3, IM_COL32(255, 160, 60, 255));
            if (c.lights > 0) dl->AddCircleFilled(ImVec2(a.x + cell * 0.7f, a.y + cell * 0.5f), 3, IM_COL32(255, 230, 90, 255));
            if (i == radius && j == radius) dl->AddRect(a, b, IM_COL32(255, 255, 255, 255), 0, 0, 2);
        }
    ImGui::Dummy(ImVec2(side, side));
    ImGui::Text("%llu windows made", (unsigned long long)e.endless.windows_built);
    ImGui::End();
}

}  // namespace isolux::app
