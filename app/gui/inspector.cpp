// The tileset inspector: pick an overlay sprite, see what its footprint reads
// (opacity map, Δy lines, the chosen run, the obstacle, the anchor), correct
// it (mode, thresholds, or click to place a run), and save it into the
// manifest. Thin: it reads the world's tileset and calls the editor's actions.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "gui/app.hpp"
#include "common/model_colours.hpp"
#include "gui/inspector.hpp"
#include "gui/widgets.hpp"
#include "isolux/footprint.hpp"
#include "isolux/solid_estimate.hpp"
#include "isolux/sprite_shading.hpp"

namespace isolux::app {

namespace {

// The sprite drawn at `zoom` with what its footprint read over it; a click
// (with the run mode) puts the run's centre there.
void draw_sprite(App& app, int index, const Sprite& s, FootprintSpec& spec, bool& changed) {
    Ui& ui = app.ui;
    const Params& p = app.editor.scene.params;
    FootprintReport r;
    const Mask obstacle = tileset_footprint(app.editor.world.tileset, s, p, &r);
    const float z = ui.inspector.zoom;
    const float w = s.image.width * z, h = s.image.height * z;
    // The sprite in a box of its own that scrolls both ways, so any sprite at
    // any zoom fits the panel and the lines below stay in view.
    const float box_h = std::min(h + ImGui::GetStyle().ScrollbarSize + 2,
                                 std::max(160.0f, ImGui::GetContentRegionAvail().y * 0.65f));
    ImGui::BeginChild("sprite image", ImVec2(0, box_h), false, ImGuiWindowFlags_HorizontalScrollbar);
    const ImVec2 o = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("sprite", ImVec2(w, h));
    const bool hovered = ImGui::IsItemHovered();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(o, ImVec2(o.x + w, o.y + h), IM_COL32(40, 40, 48, 255));
    auto px = [&](int x, int y, ImU32 c) {
        dl->AddRectFilled(ImVec2(o.x + x * z, o.y + y * z), ImVec2(o.x + (x + 1) * z, o.y + (y + 1) * z), c);
    };
    // With "normal map": the sprite's normals as a normal map draws them,
    // made once for the sprite, its source and the parameters.
    static struct {
        int index = -1;
        Params p;
        SpriteShading from = SpriteShading::none;
        std::uint64_t built = 0;
        std::vector<std::uint8_t> rgb;
    } normals;
    const SpriteShading from = p.sprite_shading == SpriteShading::none ? SpriteShading::solids : p.sprite_shading;
    if (ui.inspector.normals && (normals.index != index || !(normals.p == p) || normals.from != from ||
                                 normals.built != app.editor.world.built_revision)) {
        normals.rgb.clear();
        try {
            normals.rgb = normal_map_rgb(sprite_normals(app.editor.world.tileset, s, p, from), NormalConvention::opengl);
        } catch (const Error&) {  // shapes on a sprite without them: its colours, and the reason below
        }
        normals.index = index, normals.p = p, normals.from = from, normals.built = app.editor.world.built_revision;
    }
    const bool show_normals = ui.inspector.normals && !normals.rgb.empty();
    for (int y = 0; y < s.image.height; ++y)
        for (int x = 0; x < s.image.width; ++x) {
            const std::uint8_t* c = s.image.at(x, y);
            if (c[3] == 0) continue;
            if (show_normals) {
                const std::uint8_t* n = &normals.rgb[(std::size_t(y) * s.image.width + x) * 3];
                px(x, y, IM_COL32(n[0], n[1], n[2], 255));
                continue;
            }
            const bool read = r.estimate.get(x, y);
            // What the estimate left out (a baked ground or shadow) is dimmed.
            const int k = read ? 255 : 90;
            px(x, y, IM_COL32(c[0] * k / 255, c[1] * k / 255, c[2] * k / 255, c[3]));
        }
    if (ui.inspector.lines && r.trace.last_line >= r.trace.first_line)
        dl->AddRectFilled(ImVec2(o.x, o.y + r.trace.first_line * z), ImVec2(o.x + w, o.y + (r.trace.last_line + 1) * z),
                          IM_COL32(60, 120, 255, 60));
    for (int y = 0; y < obstacle.height; ++y)
        for (int x = 0; x < obstacle.width; ++x)
            if (obstacle.bits[std::size_t(y) * obstacle.width + x]) px(obstacle.x0 + x, obstacle.y0 + y, IM_COL32(255, 50, 50, 200));
    // The solids estimated from the alpha alone (beyond the paper): each
    // outlined in its model's colour (model_colours.hpp).
    const std::vector<EstimatedObject> objects = estimate_objects(r, obstacle, &spec);
    for (const EstimatedObject& ob : objects) {
        const Mask solid = solid_silhouette({ob}, s.image.width, s.image.height);
        const auto c = app::model_colour(ob.model).rgba;
        for (int y = 0; y < solid.height; ++y)
            for (int x = 0; x < solid.width; ++x)
                if (solid.get(x, y) &&
                    (!solid.get(x - 1, y) || !solid.get(x + 1, y) || !solid.get(x, y - 1) || !solid.get(x, y + 1)))
                    px(x, y, IM_COL32(c[0], c[1], c[2], c[3]));
    }
    // Each object's footprint (a grove has one per tree), outlined in orange.
    for (const EstimatedObject& ob : objects)
        dl->AddRect(ImVec2(o.x + ob.rect.x * z, o.y + ob.rect.y * z),
                    ImVec2(o.x + (ob.rect.x + ob.rect.w) * z, o.y + (ob.rect.y + ob.rect.h) * z), IM_COL32(255, 140, 0, 255));
    if (r.trace.run_length > 0)
        dl->AddRect(ImVec2(o.x + r.trace.run_start * z, o.y + r.trace.chosen_line * z),
                    ImVec2(o.x + (r.trace.run_start + r.trace.run_length) * z, o.y + (r.trace.chosen_line + 1) * z),
                    IM_COL32(0, 255, 255, 255));
    const ImVec2 a(o.x + (s.anchor_x + 0.5f) * z, o.y + (s.anchor_y + 0.5f) * z);
    dl->AddLine(ImVec2(a.x - 8, a.y), ImVec2(a.x + 8, a.y), IM_COL32(0, 255, 255, 255), 2);
    dl->AddLine(ImVec2(a.x, a.y - 8), ImVec2(a.x, a.y + 8), IM_COL32(0, 255, 255, 255), 2);
    if (hovered && ImGui::IsMouseDown(0) && !ImGui::GetIO().KeyShift && spec.mode == FootprintMode::run) {
        // Drag: the run follows the pointer (its centre under it).
        const ImVec2 m = ImGui::GetIO().MousePos;
        const int cx = int((m.x - o.x) / z), cy = int((m.y - o.y) / z);
        spec.run_x = cx - spec.run_length / 2;
        spec.run_y = cy;
        changed = true;
    }
    ImGui::EndChild();
    if (ui.inspector.normals && !show_normals)
        ImGui::TextWrapped("no normal map: sprite_shading shapes needs a shape or a height map on this sprite");
    double cx = 0, cy = 0;
    Rect box;
    if (mask_centre(obstacle, cx, cy, box))
        ImGui::TextWrapped("obstacle centre (%.0f, %.0f), %.0f px from the anchor (%d, %d)%s%s%s", cx, cy,
                    std::hypot(cx - s.anchor_x - 0.5, cy - s.anchor_y - 0.5), s.anchor_x, s.anchor_y,
                    r.baked_ground ? "; baked ground found" : "", r.baked_shadow ? "; baked shadow found" : "",
                    r.whole_base ? "; stands on its whole base" : "");
    else
        ImGui::TextUnformatted("no obstacle: light passes through this sprite");
    for (const EstimatedObject& ob : objects)
        ImGui::TextWrapped("estimated solid: a %s (outlined in %s), %.0f px high, its foot at (%.1f, %.1f)%s",
                           std::string(to_string(ob.model)).c_str(), app::model_colour(ob.model).name,
                           ob.height(), ob.center_x, ob.center_y,
                           spec.object_foot || spec.object_height || spec.object_model ? ", as corrected" : "");
    // The user's choice of model (saved in the manifest's `object` field).
    {
        static constexpr const char* names[] = {"estimated (best fit)", "revolution", "prism", "mound"};
        int current = spec.object_model ? 1 + int(*spec.object_model) : 0;
        if (ImGui::Combo("solid model", &current, names, 4)) {
            if (current == 0) spec.object_model.reset();
            else spec.object_model = ObjectModel(current - 1);
            changed = true;
        }
    }
    // The user's correction of the solid: where it stands and how tall it is.
    bool fix = spec.object_foot.has_value() || spec.object_height > 0;
    if (ImGui::Checkbox("correct the solid", &fix)) {
        if (fix && !objects.empty())
            spec.object_foot = std::pair{int(std::floor(objects[0].center_x)), int(std::floor(objects[0].center_y))},
            spec.object_height = std::min(int(objects[0].height()), s.image.height);  // validate()'s bound
        else if (fix)
            spec.object_foot = std::pair{s.anchor_x, s.anchor_y}, spec.object_height = 0;
        else
            spec.object_foot.reset(), spec.object_height = 0;
        changed = true;
    }
    if (fix) {
        int foot[2] = {spec.object_foot ? spec.object_foot->first : s.anchor_x,
                       spec.object_foot ? spec.object_foot->second : s.anchor_y};
        if (ImGui::InputInt2("foot x, y (sprite pixels)", foot)) {
            spec.object_foot = std::pair{std::clamp(foot[0], 0, s.image.width - 1), std::clamp(foot[1], 0, s.image.height - 1)};
            changed = true;
        }
        int height = spec.object_height;
        if (ImGui::InputInt("height (px, 0: estimated)", &height)) {
            spec.object_height = std::clamp(height, 0, s.image.height);
            changed = true;
        }
        ImGui::TextDisabled("Shift+click on the sprite to put the foot there");
    }
    if (hovered && ImGui::IsMouseClicked(0) && ImGui::GetIO().KeyShift) {
        const ImVec2 m = ImGui::GetIO().MousePos;
        spec.object_foot = std::pair{std::clamp(int((m.x - o.x) / z), 0, s.image.width - 1),
                                     std::clamp(int((m.y - o.y) / z), 0, s.image.height - 1)};
        changed = true;
    }
    (void)index;
}

}  // namespace

void inspector_panel(App& app) {
    Ui& ui = app.ui;
    Editor& e = app.editor;
    if (!ui.inspector.open) return;
    {
        // Opens over the map, inside the window whatever its size.
        const Rect fl = app.ui.layout.floating;
        ImGui::SetNextWindowPos(ImVec2(float(fl.x), float(fl.y)), ImGuiCond_Appearing);
        ImGui::SetNextWindowSize(ImVec2(float(fl.w), float(fl.h)), ImGuiCond_Appearing);
    }
    if (!ImGui::Begin("Tileset inspector", &ui.inspector.open)) return ImGui::End();
    const auto& sprites = e.world.tileset.sprites;
    ImGui::BeginChild("list", ImVec2(150, 0), true);
    for (int i = 0; i < int(sprites.size()); ++i)
        if (sprites[std::size_t(i)].kind == SpriteKind::overlay &&
            ImGui::Selectable(sprites[std::size_t(i)].name.c_str(), ui.inspector.sprite == i))
            ui.inspector.sprite = i;
    ImGui::EndChild();
    ImGui::SameLine();
    ImGui::BeginChild("sprite", ImVec2(0, 0));
    if (ui.inspector.sprite < 0 || ui.inspector.sprite >= int(sprites.size())) {
        ImGui::TextWrapped("Pick a sprite: its obstacle (red), the run Algorithm 1 chose (cyan box), the lines it "
                           "read (blue band), the solid estimated from its alpha (yellow outline) and the anchor (cyan "
                           "cross); what the estimate left out is dimmed.");
    } else {
        const Sprite& s = sprites[std::size_t(ui.inspector.sprite)];
        FootprintSpec spec = s.footprint;
        bool changed = false;
        static const char* modes[] = {"preset's", "auto", "paper", "none", "run", "polygon"};
        int m = spec.mode ? int(*spec.mode) + 1 : 0;
        ImGui::SetNextItemWidth(140);
        if (ImGui::Combo("footprint", &m, modes, 5)) {  // a polygon is set in the manifest
            spec.mode = m == 0 ? std::nullopt : std::optional<FootprintMode>(FootprintMode(m - 1));
            if (spec.mode == FootprintMode::run && spec.run_length < 1) {
                spec.run_length = std::max(4, s.image.width / 8);
                spec.run_x = s.anchor_x - spec.run_length / 2;
                spec.run_y = s.anchor_y;
            }
            changed = true;
        }
        if (spec.mode == FootprintMode::run) {
            int run[3] = {spec.run_x, spec.run_y, spec.run_length};
            if (ImGui::InputInt3("run x, y, length", run)) {
                spec.run_x = run[0], spec.run_y = run[1], spec.run_length = std::max(1, run[2]);
                changed = true;
            }
            ImGui::TextDisabled("drag on the sprite to move the run");
        }
        if (!spec.mode || spec.mode == FootprintMode::automatic) {
            float v[3] = {float(spec.shadow_alpha), float(spec.shadow_luminance), float(spec.ground_tolerance)};
            changed |= ImGui::SliderFloat("shadow alpha", &v[0], 0, 1, "%.2f");
            changed |= ImGui::SliderFloat("shadow luminance", &v[1], 0, 1, "%.2f");
            changed |= ImGui::SliderFloat("ground tolerance", &v[2], 0, 1, "%.2f");
            spec.shadow_alpha = v[0], spec.shadow_luminance = v[1], spec.ground_tolerance = v[2];
        }
        ImGui::Checkbox("Δy lines", &ui.inspector.lines);
        ImGui::SameLine();
        ImGui::Checkbox("normal map", &ui.inspector.normals);
        help("The sprite's normal map (red right, green up, blue toward you) in place of its colours, from the "
             "sprite shading chosen in Parameters, or the estimated solids while it is none; the solid's outline "
             "over it.");
        record_control(app, "Inspector", "normal_map");
        ImGui::SameLine();
        ImGui::SetNextItemWidth(100);
        ImGui::SliderFloat("zoom", &ui.inspector.zoom, 1, 6, "%.0f");
        draw_sprite(app, ui.inspector.sprite, s, spec, changed);
        if (changed) set_sprite_footprint(e, ui.inspector.sprite, spec);
    }
    ImGui::EndChild();
    ImGui::End();
}

}  // namespace isolux::app
