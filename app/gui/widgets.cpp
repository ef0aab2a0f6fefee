// Small widgets every panel and dialog shares: widgets.hpp.
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

// The "(?)" marker beside each parameter: the paper's symbol, meaning, range.
void help(const char* text) {
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
        ImGui::TextUnformatted(text);
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

// Wraps a widget that edits the document live: the first change snapshots
// the document, the end of the drag commits one undo step.
void track_edit(App& app, const Scene& before_widget) {
    Ui& ui = app.ui;
    if (ImGui::IsItemActivated() && !ui.editing) {
        ui.editing = true;
        ui.edit_before = before_widget;
    }
    if (ImGui::IsItemDeactivated() && ui.editing) {
        ui.editing = false;
        if (ImGui::IsItemDeactivatedAfterEdit()) commit_edit(app.editor, ui.edit_before, app.now);
    }
}

// Places a docked panel: always on the frames the layout is (re)applied,
// otherwise where the user left it.
void dock(App& app, const char* name) {
    const Rect r = panel_rect(app.ui.layout, name);
    if (r.empty()) return;
    const ImGuiCond cond = app.ui.reset_layout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(ImVec2(float(r.x), float(r.y)), cond);
    ImGui::SetNextWindowSize(ImVec2(float(r.w), float(r.h)), cond);
}

void record_control(App& app, const char* panel, const char* name) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    app.ui.controls.push_back({panel, name, a.x, a.y, b.x - a.x, b.y - a.y});
}

void record_panel(App& app, const char* name) {
    const ImVec2 p = ImGui::GetWindowPos(), sz = ImGui::GetWindowSize();
    app.ui.panels.push_back({name, p.x, p.y, sz.x, sz.y, ImGui::GetScrollY(), ImGui::GetScrollMaxY()});
}

}  // namespace isolux::app
