// The docked panels: Map, Parameters, Overlays, Lights and the terrain
// Tools, and draw_panels, which lays out and draws every window of a frame.
// Thin: each reads the state and calls the editor's actions (editor/editor.hpp).
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "gui/app.hpp"
#include "gui/overview.hpp"
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

namespace {

// Shows the document's map fields; an edit applies (regenerates, one undo
// step) when the field is left or Enter is pressed. While a field is active
// ImGui edits `ui.map_edit`, which is refreshed from the document otherwise.
void map_panel(App& app) {
    Editor& e = app.editor;
    Ui& ui = app.ui;
    dock(app, "Map");
    if (!ImGui::Begin("Map")) return ImGui::End();
    const MapFields shown = map_fields(e);
    if (!ui.map_editing) ui.map_edit = shown;
    MapFields& m = ui.map_edit;
    bool apply = false, active = false;
    ImGui::InputText("seed", &m.seed);
    active |= ImGui::IsItemActive();
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    help("Any text. The same seed gives the same map, pixel for pixel, on every machine. Enter regenerates.");
    if (!m.endless) {
        int size[2] = {m.width, m.height};
        if (ImGui::InputInt2("size", size)) m.width = size[0], m.height = size[1];
        active |= ImGui::IsItemActive();
        apply |= ImGui::IsItemDeactivatedAfterEdit();
        help("Map size in tiles: each side 1 to 4096, at most 1048576 tiles (1024x1024). Enter regenerates.");
    }
    int layout = int(m.layout);
    if (ImGui::Combo("layout", &layout, "paper\0diamond\0staggered\0")) {
        m.layout = Layout(layout);
        apply = true;
    }
    help("paper: section 3's assembly rule (a parallelogram); diamond and staggered: Tiled's isometric layouts.");
    ui.map_editing = active;
    if (ImGui::Button("Regenerate")) apply = true;
    ImGui::SameLine();
    if (ImGui::Button("Random seed")) {
        static const char* words[] = {"amber", "birch", "cedar", "dune", "ember", "fern", "grove", "heath",
                                      "isle", "juniper", "kelp", "lichen", "moss", "nettle", "oak", "pine"};
        const auto t = std::uint64_t(app.now * 1000) ^ std::uint64_t(e.undo_stack.size() * 7919);
        m.seed = std::string(words[t % 16]) + "-" + std::to_string((t / 16) % 10000);
        apply = true;
    }
    if (ImGui::Checkbox("endless", &m.endless)) apply = true;
    help("No edge: chunks of 32x32 tiles are made around the view as it moves (walk, pan), and saving keeps "
         "the seed, edits and lights, never the tiles.");
    if (apply) {
        if (!m.endless && shown.endless) m.width = Scene{}.width, m.height = Scene{}.height;  // leaving an endless world
        if (!m.endless && !map_size_ok(m.width, m.height))
            set_status(e, std::string("size: ") + map_size_rule(), true);
        else if (!(m == shown) && !e.scene.edits.empty()) {
            ui.dialogs.edits_target = m;  // ask: keep or clear the hand edits?
            ui.dialogs.edits_prompt = true;
        } else if (!(m == shown))
            regenerate(e, m, app.now);
        ui.map_editing = false;
    }
    if (!e.scene.edits.empty() && e.scene.endless) {
        ImGui::Text("%zu hand edits", e.scene.edits.size());
    } else if (!e.scene.edits.empty()) {
        const int outside = edits_outside(e.scene);
        ImGui::Text("%zu hand edits", e.scene.edits.size());
        if (outside > 0) {
            ImGui::SameLine();
            ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "(%d outside the map, kept)", outside);
        }
    }
    ImGui::Text("tileset: %s", shown.tileset.empty() ? "default" : shown.tileset.c_str());
    if (ImGui::Button("Load tileset...")) open_file_popup(app, "load-tileset", shown.tileset);
    ImGui::SameLine();
    if (ImGui::Button("Inspect")) app.ui.inspector.open = true;
    if (e.footprints_unsaved) {
        ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "footprints changed");
        ImGui::SameLine();
        if (ImGui::Button("Save into the manifest")) save_footprints(e);
    }
    ImGui::SameLine();
    if (ImGui::Button("Default tileset") && !e.scene.tileset.empty()) {
        Scene before = e.scene;
        e.scene.tileset.clear();
        if (sync_world(e)) commit_edit(e, before, app.now);
    }
    ImGui::End();
}

// The "(?)" text for a parameter: symbol, help, range and what it re-runs.
std::string param_tooltip(const ParamInfo& info) {
    std::string t = *info.symbol ? std::string(info.symbol) + ": " : "";
    t += std::string(info.help) + "\nRange " + param_range_text(info) + ", default " +
         format_param(info, param_default(info)) + ". ";
    if (info.reruns == StageSet{}) t += "Changes only when rays are traced.";
    else if (info.reruns.has(Stage::obstacle_map)) t += "Rebuilds the obstacle map.";
    else if (info.reruns.has(Stage::trace)) t += "Retraces.";
    else if (info.reruns.has(Stage::blur)) t += "Re-blurs only.";
    else t += "Re-composites only.";
    if (info.type == ParamType::integer || info.type == ParamType::real) t += " Ctrl+click to type any value.";
    return t;
}

void param_widget(App& app, const ParamInfo& info);

// One widget per row of the parameter table, in its order, under a
// collapsible heading per section (each heading once).
// A drag is one undo step; the document is validated by set_params.
void params_panel(App& app) {
    dock(app, "Parameters");
    if (!ImGui::Begin("Parameters")) return ImGui::End();
    ImGui::PushItemWidth(std::min(170.0f, ImGui::GetContentRegionAvail().x * 0.55f));
    // Rows packed a little closer than the style's: every control within one
    // scroll at 1280x720 (tests/app/gui/app_test.sh).
    ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(ImGui::GetStyle().ItemSpacing.x, 2));
    ImGui::PushStyleVar(ImGuiStyleVar_FramePadding, ImVec2(ImGui::GetStyle().FramePadding.x, 1));
    std::vector<std::string_view> groups;
    for (const ParamInfo& info : param_table())
        if (std::find(groups.begin(), groups.end(), info.group) == groups.end()) groups.push_back(info.group);
    for (std::string_view group : groups) {
        if (!ImGui::CollapsingHeader(std::string(group).c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
        for (const ParamInfo& info : param_table())
            if (info.group == group) param_widget(app, info);
    }
    ImGui::PopStyleVar(2);
    ImGui::PopItemWidth();
    record_panel(app, "Parameters");
    ImGui::End();
}

// A parameter's widget, its help and its rectangle for the app's script.
void param_widget(App& app, const ParamInfo& info) {
    Editor& e = app.editor;
    {
        const Scene before = e.scene;
        const double v = info.get(e.scene.params);
        const ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (info.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
        ImGui::PushID(info.name);
        double edited = v;
        bool changed = false;
        switch (info.type) {
            case ParamType::integer: {
                int x = int(v);
                changed = ImGui::SliderInt(info.label, &x, int(info.slider_min), int(info.slider_max), "%d", flags);
                edited = std::clamp(double(x), info.min, info.max);
                break;
            }
            case ParamType::real: {
                float x = float(v);
                changed = ImGui::SliderFloat(info.label, &x, float(info.slider_min), float(info.slider_max), "%.3f", flags);
                edited = std::clamp(double(x), info.min, info.max);
                if (info.min_open && edited <= info.min) edited = v;
                break;
            }
            case ParamType::choice: {
                int x = int(v);
                changed = ImGui::Combo(info.label, &x, info.choices.data(), choice_count(info));
                edited = x;
                break;
            }
            case ParamType::boolean: {
                bool x = v != 0;
                changed = ImGui::Checkbox(info.label, &x);
                edited = x ? 1 : 0;
                break;
            }
        }
        if (changed && edited != v) info.set(e.scene.params, edited);  // live while dragging
        if (info.type == ParamType::integer || info.type == ParamType::real) track_edit(app, before);
        else if (changed) commit_edit(e, before, app.now);
        record_control(app, "Parameters", info.name);
        ImGui::PopID();
        help(param_tooltip(info).c_str());
    }
}

void overlays_panel(App& app) {
    Overlays& o = app.editor.overlays;
    dock(app, "Overlays");
    if (!ImGui::Begin("Overlays")) return ImGui::End();
    auto row = [](const char* name, bool* on, float* opacity, const char* tip) {
        ImGui::Checkbox(name, on);
        help(tip);
        if (opacity) {
            ImGui::SameLine(190);
            ImGui::SetNextItemWidth(100);
            ImGui::SliderFloat((std::string("##") + name).c_str(), opacity, 0.0f, 1.0f, "%.2f");
        }
    };
    row("obstacle map", &o.obstacles, &o.obstacles_opacity, "The obstacle map in white, as the paper's Figure 6.");
    row("opacity maps", &o.opacity_maps, &o.opacity_maps_opacity,
        "Green: sprites standing above a light's centre, added to its light. Red: those below, subtracted.");
    row("delta y bands", &o.delta_y_bands, &o.delta_y_opacity,
        "Blue: the Δy rows Algorithm 1 reads on each sprite; cyan: the run it chose.");
    row("light areas", &o.light_areas, &o.light_areas_opacity, "Each light's (2a+1) x (2b+1) area.");
    row("raw light texture", &o.raw_light, nullptr, "Show the light texture instead of the final frame.");
    row("normals", &o.normals, &o.normals_opacity,
        "Each sprite pixel's normal, as a normal map draws it (red right, green up, blue toward you), from the "
        "sprite shading chosen in Parameters; nothing while sprite shading is none.");
    ImGui::TextDisabled("truth (the sprites' 3D shapes, lights at their height)");
    row("3D light texture", &o.truth_light, nullptr,
        "The light texture of the 3D reference: a pixel is lit when the segment from its surface point to the "
        "light clears every solid. Needs shapes in the tileset.");
    row("2.5D vs 3D", &o.truth_difference, &o.truth_difference_opacity,
        "Magenta: lit by the paper's model but dark in 3D. Cyan: dark in the model but lit in 3D. Recomputed when "
        "the scene changes (slow while dragging a light).");
    row("split view", &o.split_view, nullptr,
        "Left: the paper's lighting. Right: flat lighting (Figure 10), or the 3D reference.");
    if (o.split_view) {
        ImGui::SameLine();
        ImGui::Checkbox("3D on the right", &o.split_with_3d);
        ImGui::SetNextItemWidth(200);
        ImGui::SliderFloat("split", &o.split, 0.0f, 1.0f);
    }
    ImGui::End();
}

void lights_panel(App& app) {
    Editor& e = app.editor;
    dock(app, "Lights");
    if (!ImGui::Begin("Lights")) return ImGui::End();
    ImGui::TextWrapped("Lights tool (L): click to place, drag to move, Shift+click or drag a box to select "
                       "several, right-click or Delete to remove.");
    ImGui::BeginChild("##lights", ImVec2(0, std::min(160.0f, 22.0f * float(e.scene.lights.size()) + 8)), true);
    for (int i = 0; i < int(e.scene.lights.size()); ++i) {
        const Light& l = e.scene.lights[std::size_t(i)];
        char label[160];
        const WorldOffset o = world_offset(e);
        std::snprintf(label, sizeof label, "%s  (%.0f, %.0f)%s%s##%d", light_label(e.scene, i).c_str(), l.x + o.x, l.y + o.y,
                      l.hidden ? "  hidden" : "", l.locked ? "  locked" : "", i);
        if (ImGui::Selectable(label, is_selected(e, i)))
            select_light(e, i, ImGui::GetIO().KeyShift || ImGui::GetIO().KeyCtrl);
    }
    ImGui::EndChild();
    if (!e.selection.empty()) {
        if (ImGui::Button("Duplicate")) duplicate_selection(e, app.now);
        ImGui::SameLine();
        if (ImGui::Button("Copy")) copy_selection(e);
        ImGui::SameLine();
        if (ImGui::Button("Frame")) frame_selection(app);
        ImGui::SameLine();
        if (ImGui::Button("Delete")) delete_selection(e, app.now);
    }
    if (!e.clipboard.empty()) {
        if (e.selection.empty()) ImGui::NewLine();
        ImGui::SameLine();
        if (ImGui::Button("Paste")) paste_lights(e, app.view.x + app.view.w / 2.0, app.view.y + app.view.h / 2.0, app.now);
    }
    if (e.selected >= 0 && e.selected < int(e.scene.lights.size())) {
        ImGui::Separator();
        Light& l = e.scene.lights[std::size_t(e.selected)];
        Scene before = e.scene;
        ImGui::InputText("name", &l.name);
        track_edit(app, before);
        before = e.scene;
        bool flag = l.hidden;
        if (ImGui::Checkbox("hidden", &flag)) {
            l.hidden = flag;
            commit_edit(e, before, app.now);
        }
        help("Hidden lights stay in the scene (and the file) but light nothing, in the app and in isolux-cli.");
        ImGui::SameLine();
        before = e.scene;
        flag = l.locked;
        if (ImGui::Checkbox("locked", &flag)) {
            l.locked = flag;
            commit_edit(e, before, app.now);
        }
        help("Locked lights are not moved by drags nor removed by Delete or right-click.");
        before = e.scene;
        // World pixels (an endless world's, far from its origin, need doubles).
        const WorldOffset o = world_offset(e);
        double pos[2] = {l.x + o.x, l.y + o.y};
        if (ImGui::DragScalarN("position", ImGuiDataType_Double, pos, 2, 1.0f, nullptr, nullptr, "%.1f"))
            l.x = pos[0] - o.x, l.y = pos[1] - o.y;
        track_edit(app, before);
        before = e.scene;
        bool own_area = l.area_a.has_value();
        if (ImGui::Checkbox("own area", &own_area)) {
            if (own_area) l.area_a = e.scene.params.area_a, l.area_b = e.scene.params.area_b;
            else l.area_a.reset(), l.area_b.reset();
            commit_edit(e, before, app.now);
        }
        help("Off: the preset's a and b.");
        if (own_area) {
            before = e.scene;
            int ab[2] = {*l.area_a, *l.area_b};
            if (ImGui::SliderInt2("a, b", ab, 0, 512, "%d", ImGuiSliderFlags_AlwaysClamp))
                l.area_a = ab[0], l.area_b = ab[1];
            track_edit(app, before);
        }
        before = e.scene;
        float col[3] = {l.r / 255.0f, l.g / 255.0f, l.b / 255.0f};
        if (ImGui::ColorEdit3("colour", col)) {
            l.r = std::uint8_t(col[0] * 255 + 0.5f), l.g = std::uint8_t(col[1] * 255 + 0.5f),
            l.b = std::uint8_t(col[2] * 255 + 0.5f);
        }
        track_edit(app, before);
        before = e.scene;
        float intensity = float(l.intensity);
        if (ImGui::SliderFloat("intensity", &intensity, 0.0f, 4.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp))
            l.intensity = intensity;
        track_edit(app, before);
        before = e.scene;
        bool own_height = l.height.has_value();
        if (ImGui::Checkbox("own height", &own_height)) {
            if (own_height) l.height = e.scene.params.light_height;
            else l.height.reset();
            commit_edit(e, before, app.now);
        }
        help("Off: the preset's light height. The height above the ground in pixels: the paper's model ignores "
             "it; the 3D reference (Overlays, truth) uses it.");
        if (own_height) {
            before = e.scene;
            float h = float(*l.height);
            if (ImGui::SliderFloat("height", &h, 0.0f, 256.0f, "%.0f px", ImGuiSliderFlags_AlwaysClamp)) l.height = h;
            track_edit(app, before);
        }
    }
    ImGui::Separator();
    Character& c = e.character;
    if (ImGui::Checkbox("character (WASD)", &c.enabled) && c.enabled) {
        c.x = app.view.x + app.view.w / 2.0;
        c.y = app.view.y + app.view.h / 2.0;
    }
    help("A character carrying a light walks with WASD or the arrow keys: the paper's l-frames shift at work.");
    if (c.enabled) {
        ImGui::SameLine();
        ImGui::Checkbox("follow", &c.follow);
    }
    ImGui::End();
}

// ---------------------------------------------------------------- terrain tools

// A sprite's thumbnail from the renderer's atlas, as a button; `selected`
// draws it framed.
bool sprite_button(App& app, int sprite, bool selected, float size) {
    const Renderer& r = app.renderer;
    if (sprite < 0 || std::size_t(sprite) >= r.atlas_pos.size() || r.atlas_w <= 0) return false;
    const Image& im = app.editor.world.tileset.sprites[std::size_t(sprite)].image;
    const auto& pos = r.atlas_pos[std::size_t(sprite)];
    const ImVec2 uv0(float(pos[0]) / float(r.atlas_w), float(pos[1]) / float(r.atlas_h));
    const ImVec2 uv1(float(pos[0] + im.width) / float(r.atlas_w), float(pos[1] + im.height) / float(r.atlas_h));
    const float k = size / float(std::max(im.width, im.height));
    ImGui::PushID(sprite);
    const ImVec4 bg = selected ? ImVec4(0.95f, 0.8f, 0.3f, 0.6f) : ImVec4(0, 0, 0, 0);
    const bool pressed = ImGui::ImageButton((ImTextureID)(intptr_t)r.atlas, ImVec2(im.width * k, im.height * k), uv0, uv1,
                                            2, bg);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", app.editor.world.tileset.sprites[std::size_t(sprite)].name.c_str());
    ImGui::PopID();
    return pressed;
}

// A row of thumbnails that wraps at the panel's edge.
template <class Body>
void wrapped_row(float item_w, int count, Body body) {
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    for (int i = 0; i < count; ++i) {
        body(i);
        const float next = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + item_w;
        if (i + 1 < count && next < right) ImGui::SameLine();
    }
}

void tools_panel(App& app) {
    Editor& e = app.editor;
    dock(app, "Tools");
    if (!ImGui::Begin("Tools")) return ImGui::End();
    Brush& b = e.brush;
    const auto& tools = tool_table();
    wrapped_row(96, int(tools.size()), [&](int i) {
        const ToolInfo& t = tools[std::size_t(i)];
        const bool on = b.tool == t.tool;
        if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.6f, 0.2f, 0.9f));
        char label[48];
        std::snprintf(label, sizeof label, "%s (%c)", t.label, t.key);
        if (ImGui::Button(label, ImVec2(96, 0))) b.tool = t.tool;
        if (on) ImGui::PopStyleColor();
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", t.help);
    });
    ImGui::Separator();
    const Tileset& ts = e.world.tileset;
    const bool floors = b.tool == Tool::floor || b.tool == Tool::floor_rect || b.tool == Tool::floor_fill;
    const bool overlays = b.tool == Tool::overlay_add;
    if (floors || b.tool == Tool::eyedropper) {
        ImGui::Text("Floor: %s", sprite_name(e, b.floor).c_str());
        std::vector<int> list;
        for (int i = 0; i < int(ts.sprites.size()); ++i)
            if (ts.sprites[std::size_t(i)].kind == SpriteKind::floor) list.push_back(i);
        wrapped_row(44, int(list.size()), [&](int k) {
            if (sprite_button(app, list[std::size_t(k)], b.floor == list[std::size_t(k)], 40)) b.floor = list[std::size_t(k)];
        });
    }
    if (overlays || b.tool == Tool::eyedropper) {
        ImGui::Text("Overlay: %s", b.overlay_tag.empty() ? sprite_name(e, b.overlay).c_str()
                                                         : ("any sprite with tag " + b.overlay_tag).c_str());
        // "Any sprite with tag": natural variation, one pick per tile.
        std::vector<std::string> tags;
        for (const Sprite& sp : ts.sprites)
            if (sp.kind == SpriteKind::overlay)
                for (const std::string& t : sp.tags)
                    if (std::find(tags.begin(), tags.end(), t) == tags.end()) tags.push_back(t);
        wrapped_row(80, int(tags.size()), [&](int k) {
            const std::string label = "any " + tags[std::size_t(k)];
            const bool on = b.overlay_tag == tags[std::size_t(k)];
            if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.6f, 0.2f, 0.9f));
            if (ImGui::Button(label.c_str())) b.overlay_tag = tags[std::size_t(k)];
            if (on) ImGui::PopStyleColor();
        });
        std::vector<int> list;
        for (int i = 0; i < int(ts.sprites.size()); ++i)
            if (ts.sprites[std::size_t(i)].kind == SpriteKind::overlay) list.push_back(i);
        wrapped_row(44, int(list.size()), [&](int k) {
            const int sp = list[std::size_t(k)];
            if (sprite_button(app, sp, b.overlay_tag.empty() && b.overlay == sp, 40)) {
                b.overlay = sp;
                b.overlay_tag.clear();
            }
        });
    }
    if (b.tool == Tool::lights) ImGui::TextWrapped("%s", tool_info(Tool::lights).help);
    else if (!floors && !overlays) ImGui::TextWrapped("%s", tool_info(b.tool).help);
    // What the brush will do under the cursor.
    int col = -1, row = -1;
    if (app.ui.viewport.cursor_in_view && tile_at(e.world.map, e.world.placed, app.ui.viewport.cursor_x, app.ui.viewport.cursor_y, col, row)) {
        ImGui::Separator();
        ImGui::TextWrapped("%s", brush_preview(e, col, row).c_str());
    }
    ImGui::End();
}

}  // namespace

void draw_panels(App& app) {
    Ui& ui = app.ui;
    // The layout follows the window: applied on the first frame, on every
    // resize and on Window > Reset layout.
    if (ui.layout_w != app.window_w || ui.layout_h != app.window_h) {
        ui.layout_w = app.window_w;
        ui.layout_h = app.window_h;
        ui.reset_layout = true;
    }
    ui.layout = panel_layout(app.window_w, app.window_h, int(ImGui::GetFrameHeight()), 26);
    ui.panels.clear();
    ui.controls.clear();
    menu_bar(app);
    map_panel(app);
    params_panel(app);
    overlays_panel(app);
    tools_panel(app);
    lights_panel(app);
    stats_panel(app);
    accuracy_panel(app, app.accuracy);
    inspector_panel(app);
    overview_panel(app);
    help_window(app);
    huge_work_prompt(app);
    status_bar(app);
    light_area_overlay(app);
    viewport_marks(app);
    file_popup(app);
    unsaved_popup(app);
    edits_popup(app);
    recovery_popup(app);
    ui.reset_layout = false;
}

}  // namespace isolux::app
