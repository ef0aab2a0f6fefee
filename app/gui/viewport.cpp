// The viewport's input and marks: viewport.hpp.
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

// Zoom to `zoom` keeping the world point under window pixel (sx, sy) there.
void zoom_at(App& app, double zoom, double sx, double sy) {
    View& v = app.editor.view;
    const double wx = v.x + sx / v.zoom, wy = v.y + sy / v.zoom;
    v.zoom = std::clamp(zoom, min_zoom, max_zoom);
    v.x = wx - sx / v.zoom;
    v.y = wy - sy / v.zoom;
}

// The selected lights and their areas, fitted into the free area.
void frame_selection(App& app) {
    Editor& e = app.editor;
    if (e.selection.empty()) return;
    Rect r;
    for (int i : e.selection) {
        const Rect a = light_area(e.scene.lights[std::size_t(i)], e.scene.params);
        if (r.empty()) {
            r = a;
            continue;
        }
        const int x0 = std::min(r.x, a.x), y0 = std::min(r.y, a.y);
        const int x1 = std::max(r.x + r.w, a.x + a.w), y1 = std::max(r.y + r.h, a.y + a.h);
        r = {x0, y0, x1 - x0, y1 - y0};
    }
    fit_view(e.view, r, app.ui.layout.free);
}

void fit_map(App& app) {
    Editor& e = app.editor;
    if (!e.fit_pending || app.ui.layout.free.empty()) return;
    fit_view(e.view, e.world.placed.bounds, app.ui.layout.free);
    e.fit_pending = false;
}

// The tile under the cursor (and a rectangle stroke's tiles) outlined, and
// the character drawn at its feet.
void viewport_marks(App& app) {
    const Editor& e = app.editor;
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    auto to_screen = [&](double wx, double wy) {
        return ImVec2(float(app.view_x + (wx - app.view.x) * e.view.zoom), float(app.view_y + (wy - app.view.y) * e.view.zoom));
    };
    const Map& m = e.world.map;
    auto outline = [&](int col, int row, ImU32 colour) {
        int cx = 0, cy = 0;
        tile_center(m.layout, m.tile_width, m.tile_height, col, row, cx, cy);
        const double x = cx + e.world.placed.shift_x, y = cy + e.world.placed.shift_y;
        const double hw = m.tile_width / 2.0, hh = m.tile_height / 2.0;
        dl->AddQuad(to_screen(x, y - hh), to_screen(x + hw, y), to_screen(x, y + hh), to_screen(x - hw, y), colour, 2.0f);
    };
    if (e.brush.tool != Tool::lights) {
        int col = -1, row = -1;
        const Stroke& st = e.stroke;
        if (st.active && e.brush.tool == Tool::floor_rect) {
            const int c0 = std::min(st.col0, st.col1), c1 = std::max(st.col0, st.col1);
            const int r0 = std::min(st.row0, st.row1), r1 = std::max(st.row0, st.row1);
            const bool all = long(c1 - c0 + 1) * (r1 - r0 + 1) <= 1024;  // else only its corners
            for (int r = r0; r <= r1; ++r)
                for (int c = c0; c <= c1; ++c)
                    if (all || ((r == r0 || r == r1) && (c == c0 || c == c1))) outline(c, r, IM_COL32(255, 200, 80, 220));
        } else if (app.ui.viewport.cursor_in_view &&
                   tile_at(m, e.world.placed, app.ui.viewport.cursor_x, app.ui.viewport.cursor_y, col, row)) {
            outline(col, row, IM_COL32(255, 230, 120, 230));
            ImGui::SetTooltip("%s", brush_preview(e, col, row).c_str());
        }
    }
    if (app.ui.viewport.box_selecting) {
        dl->AddRect(to_screen(app.ui.viewport.box_x0, app.ui.viewport.box_y0), to_screen(app.ui.viewport.cursor_x, app.ui.viewport.cursor_y),
                    IM_COL32(120, 200, 255, 230), 0, 0, 1.5f);
    }
    const Character& c = e.character;
    if (c.enabled && app.character_tex) {
        const double k = e.view.zoom;
        const ImVec2 p = to_screen(c.x, c.y);
        const ImVec2 p0(float(p.x - app.character_ax * k), float(p.y - app.character_ay * k));
        const ImVec2 p1(float(p0.x + app.character_w * k), float(p0.y + app.character_h * k));
        dl->AddImage((ImTextureID)(intptr_t)app.character_tex, p0, p1);
    }
}

void light_area_overlay(App& app) {
    const Editor& e = app.editor;
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const Scene s = render_scene(e);
    auto to_screen = [&](double wx, double wy) {
        return ImVec2(float(app.view_x + (wx - app.view.x) * e.view.zoom), float(app.view_y + (wy - app.view.y) * e.view.zoom));
    };
    for (int i = 0; i < int(s.lights.size()); ++i) {
        const Light& l = s.lights[i];
        const bool sel = i < int(e.scene.lights.size()) && is_selected(e, i);
        const ImVec2 c = to_screen(l.x, l.y);
        if (e.overlays.light_areas) {
            const Rect a = light_area(l, s.params);
            const int alpha = int(255 * e.overlays.light_areas_opacity);
            const ImU32 line = sel ? IM_COL32(255, 220, 90, alpha) : IM_COL32(200, 200, 255, alpha);
            if (s.params.falloff_shape == FalloffShape::euclidean && s.params.edge_fade) {
                // A round light that fades lights the ellipse its area's box
                // holds (shaped_falloff's t <= 1), not the box's corners.
                constexpr int n = 96;
                ImVec2 pts[n];
                const double cx = a.x + a.w / 2.0, cy = a.y + a.h / 2.0;
                for (int k = 0; k < n; ++k) {
                    const double t = 2 * 3.141592653589793 * k / n;
                    pts[k] = to_screen(cx + a.w / 2.0 * std::cos(t), cy + a.h / 2.0 * std::sin(t));
                }
                dl->AddPolyline(pts, n, line, ImDrawFlags_Closed, 1.0f);
            } else {
                dl->AddRect(to_screen(a.x, a.y), to_screen(a.x + a.w, a.y + a.h), line);
            }
        }
        const ImU32 colour = l.hidden ? IM_COL32(140, 140, 140, 160) : sel ? IM_COL32(255, 220, 90, 255) : IM_COL32(255, 255, 255, 200);
        dl->AddCircle(c, sel ? 7.0f : 5.0f, colour, 16, 2.0f);
        if (l.locked) dl->AddRect(ImVec2(c.x - 3, c.y - 3), ImVec2(c.x + 3, c.y + 3), colour);
        if (!l.name.empty()) dl->AddText(ImVec2(c.x + 9, c.y - 8), colour, l.name.c_str());
    }
    if (e.overlays.split_view) {
        const float x = float(app.view_x + app.view.w * e.overlays.split * e.view.zoom);
        dl->AddLine(ImVec2(x, 0), ImVec2(x, float(app.window_h)), IM_COL32(255, 255, 255, 160), 1.5f);
    }
}

void handle_viewport_input(App& app, double dt) {
    ImGuiIO& io = ImGui::GetIO();
    Editor& e = app.editor;
    Ui& ui = app.ui;
    const double mx = io.MousePos.x, my = io.MousePos.y;
    ui.viewport.cursor_x = app.view.x + (mx - app.view_x) / e.view.zoom;
    ui.viewport.cursor_y = app.view.y + (my - app.view_y) / e.view.zoom;
    ui.viewport.cursor_in_view = !io.WantCaptureMouse && mx >= 0 && my >= 0;

    if (!io.WantCaptureKeyboard) {
        const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
        auto pressed = [](int key) { return ImGui::IsKeyPressed(key, false); };
        if (ctrl && pressed(GLFW_KEY_Z)) {
            if (shift) redo(e, app.now);
            else undo(e, app.now);
        }
        if (ctrl && pressed(GLFW_KEY_Y)) redo(e, app.now);
        if (ctrl && pressed(GLFW_KEY_S)) {
            if (shift) open_file_popup(app, "save-scene", e.scene_path.empty() ? "scene.json" : e.scene_path.string());
            else save_or_save_as(app);
        }
        if (ctrl && pressed(GLFW_KEY_N)) new_scene_action(app);
        if (ctrl && pressed(GLFW_KEY_O)) open_file_popup(app, "open-scene", e.scene_path.string());
        if (ctrl && pressed(GLFW_KEY_Q)) quit_action(app);
        if (ctrl && pressed(GLFW_KEY_C)) copy_selection(e);
        if (ctrl && pressed(GLFW_KEY_V)) paste_lights(e, ui.viewport.cursor_x, ui.viewport.cursor_y, app.now);
        if (ctrl && pressed(GLFW_KEY_D)) duplicate_selection(e, app.now);
        if (ctrl && pressed(GLFW_KEY_A)) select_lights_in(e, {-2000000000, -2000000000, 2147483647, 2147483647}, false);
        if (ctrl && pressed(GLFW_KEY_0)) zoom_at(app, 1.0, app.window_w / 2.0, app.window_h / 2.0);
        if (pressed(GLFW_KEY_ESCAPE)) select_light(e, -1);
        if (pressed(GLFW_KEY_DELETE) && !e.selection.empty()) delete_selection(e, app.now);
        if (pressed(GLFW_KEY_F1)) ui.help_open = !ui.help_open;
        if (pressed(GLFW_KEY_HOME) || (!ctrl && !shift && pressed(GLFW_KEY_F))) e.fit_pending = true;
        if (!ctrl && shift && pressed(GLFW_KEY_F)) frame_selection(app);
        Character& c = e.character;
        if (!ctrl) {
            // Tool hotkeys (letters WASD stay the character's while it walks).
            for (const ToolInfo& t : tool_table())
                if (pressed(GLFW_KEY_A + (t.key - 'A'))) e.brush.tool = t.tool;
            bool* overlay_keys[5] = {&e.overlays.obstacles, &e.overlays.opacity_maps, &e.overlays.delta_y_bands,
                                     &e.overlays.light_areas, &e.overlays.raw_light};
            for (int k = 0; k < 5; ++k)
                if (pressed(GLFW_KEY_1 + k)) *overlay_keys[k] = !*overlay_keys[k];
        }
        if (c.enabled && !ctrl) {
            double dx = 0, dy = 0;
            if (ImGui::IsKeyDown(GLFW_KEY_A) || ImGui::IsKeyDown(GLFW_KEY_LEFT)) dx -= 1;
            if (ImGui::IsKeyDown(GLFW_KEY_D) || ImGui::IsKeyDown(GLFW_KEY_RIGHT)) dx += 1;
            if (ImGui::IsKeyDown(GLFW_KEY_W) || ImGui::IsKeyDown(GLFW_KEY_UP)) dy -= 1;
            if (ImGui::IsKeyDown(GLFW_KEY_S) || ImGui::IsKeyDown(GLFW_KEY_DOWN)) dy += 1;
            // Isometric: half speed vertically. The character keeps to the
            // map and walks around the obstacle map.
            if (dx != 0 || dy != 0) walk_character(e, dx * c.speed * dt, dy * c.speed * dt * 0.5);
            if (c.follow) {
                e.view.x = c.x - app.window_w / 2.0 / e.view.zoom;
                e.view.y = c.y - app.window_h / 2.0 / e.view.zoom;
            }
        }
    }

    if (io.WantCaptureMouse) {
        if (e.stroke.active && !ImGui::IsMouseDown(0)) end_stroke(e, app.now);
        return;
    }
    // Zoom at the cursor, 1/16 to 16.
    if (io.MouseWheel != 0) zoom_at(app, e.view.zoom * std::pow(1.15, io.MouseWheel), mx, my);
    // Pan: middle drag, or Space + left drag.
    const bool space = ImGui::IsKeyDown(GLFW_KEY_SPACE);
    if (ImGui::IsMouseDown(2) || (space && ImGui::IsMouseDown(0))) {
        e.view.x -= io.MouseDelta.x / e.view.zoom;
        e.view.y -= io.MouseDelta.y / e.view.zoom;
        return;
    }
    int col = -1, row = -1;
    const bool on_tile = tile_at(e.world.map, e.world.placed, ui.viewport.cursor_x, ui.viewport.cursor_y, col, row);

    // Terrain tools: a stroke from press to release, one undo step.
    if (e.brush.tool != Tool::lights) {
        if (ImGui::IsMouseClicked(0) && on_tile) begin_stroke(e, col, row);
        if (e.stroke.active && ImGui::IsMouseDown(0) && on_tile) continue_stroke(e, col, row);
        if (e.stroke.active && !ImGui::IsMouseDown(0)) end_stroke(e, app.now);
        return;
    }

    // Lights: click a light to select it (Shift adds), drag to move the
    // selection; on empty ground a click places a light and a drag selects
    // the lights in its box.
    const double pick = 8.0 / e.view.zoom;
    if (ImGui::IsMouseClicked(0)) {
        const int hit = light_at(e, ui.viewport.cursor_x, ui.viewport.cursor_y, pick);
        if (hit >= 0) {
            if (io.KeyShift) select_light(e, hit, true);
            else if (!is_selected(e, hit)) select_light(e, hit);
            if (is_selected(e, hit)) {
                ui.viewport.dragging_light = hit;
                ui.viewport.drag_before = e.scene;
            }
        } else {
            ui.viewport.pressed_empty = true;
            ui.viewport.press_x = mx;
            ui.viewport.press_y = my;
            ui.viewport.box_x0 = ui.viewport.cursor_x;
            ui.viewport.box_y0 = ui.viewport.cursor_y;
        }
    }
    if (ui.viewport.pressed_empty) {
        const bool moved = std::hypot(mx - ui.viewport.press_x, my - ui.viewport.press_y) > 4;
        if (ImGui::IsMouseDown(0)) {
            ui.viewport.box_selecting = ui.viewport.box_selecting || moved;
        } else {
            if (ui.viewport.box_selecting) {
                const double x0 = std::min(ui.viewport.box_x0, ui.viewport.cursor_x), y0 = std::min(ui.viewport.box_y0, ui.viewport.cursor_y);
                const double x1 = std::max(ui.viewport.box_x0, ui.viewport.cursor_x), y1 = std::max(ui.viewport.box_y0, ui.viewport.cursor_y);
                select_lights_in(e, {int(std::floor(x0)), int(std::floor(y0)), int(std::ceil(x1 - x0)) + 1,
                                     int(std::ceil(y1 - y0)) + 1},
                                 io.KeyShift);
            } else if (!io.KeyShift) {
                place_light(e, ui.viewport.box_x0, ui.viewport.box_y0, app.now);
            }
            ui.viewport.pressed_empty = ui.viewport.box_selecting = false;
        }
    }
    if (ui.viewport.dragging_light >= 0) {
        if (ImGui::IsMouseDown(0)) {
            // The selection moves with the light under the cursor, by whole pixels.
            const Light& anchor = e.scene.lights[std::size_t(ui.viewport.dragging_light)];
            const double dx = std::floor(ui.viewport.cursor_x) + 0.5 - anchor.x, dy = std::floor(ui.viewport.cursor_y) + 0.5 - anchor.y;
            if ((dx != 0 || dy != 0) && !anchor.locked) move_selection(e, dx, dy);
        } else {
            commit_edit(e, ui.viewport.drag_before, app.now);  // one undo step per drag
            ui.viewport.dragging_light = -1;
        }
    }
    if (ImGui::IsMouseClicked(1)) {
        const int hit = light_at(e, ui.viewport.cursor_x, ui.viewport.cursor_y, pick);
        if (hit >= 0) remove_light(e, hit, app.now);
    }
}

}  // namespace isolux::app
