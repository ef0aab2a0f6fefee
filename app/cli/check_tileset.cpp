#include "cli/check_tileset.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/contact_sheet.hpp"
#include "isolux/isolux.hpp"
#include "isolux/footprint.hpp"
#include "isolux/solid_estimate.hpp"
#include "isolux/tileset_file.hpp"

namespace isolux::cli {

using namespace isolux::app;

int run_check_tileset(const CheckArgs& a) {
    if (!a.sheet.empty()) check_image_output(a.sheet);  // before the work, not after it
    const Tileset ts = load_tileset(a.manifest);
    const Params p = params_from_args(a.params, Params{});
    nlohmann::json report = {{"sprites", nlohmann::json::array()}};
    std::vector<SheetSprite> drawn;
    int warnings = 0;
    for (const Sprite& s : ts.sprites) {
        if (s.kind != SpriteKind::overlay) continue;
        FootprintReport fr;
        Mask fp = tileset_footprint(ts, s, p, &fr);
        double cx = 0, cy = 0;
        Rect box;
        const bool any = mask_centre(fp, cx, cy, box);
        nlohmann::json detected = nlohmann::json::array();
        if (fr.baked_ground) detected.push_back("baked_ground");
        if (fr.baked_shadow) detected.push_back("baked_shadow");
        if (fr.whole_base) detected.push_back("whole_base");
        nlohmann::json e = {{"name", s.name}, {"anchor", {s.anchor_x, s.anchor_y}}, {"detected", detected}};
        std::string warning;
        if (any) {
            const double d = std::hypot(cx - (s.anchor_x + 0.5), cy - (s.anchor_y + 0.5));
            e["obstacle_center"] = {std::round(cx * 10) / 10, std::round(cy * 10) / 10};
            e["obstacle_rect"] = {box.x, box.y, box.w, box.h};
            e["distance"] = std::round(d * 10) / 10;
            if (d > ts.tile_width / 4.0)
                warning = "the obstacle's centre is " + std::to_string(int(std::lround(d))) +
                          " px from the anchor, over a quarter of the tile width (" + std::to_string(ts.tile_width / 4) +
                          "): check the footprint";
        } else {
            e["obstacle_center"] = nullptr;
            e["obstacle_rect"] = nullptr;
            e["distance"] = nullptr;
            if (s.footprint.mode != FootprintMode::none) warning = "no obstacle: light passes through this sprite";
        }
        // Beyond the paper: each object's solid, estimated from the alpha alone,
        // and how much of the manifest's shape it shares, where there is one.
        const std::vector<EstimatedObject> objects = estimate_objects(fr, fp, &s.footprint);
        e["objects"] = nlohmann::json::array();
        for (const EstimatedObject& o : objects) {
            nlohmann::json j = {{"center", {std::round(o.center_x * 10) / 10, std::round(o.center_y * 10) / 10}},
                                {"rect", {o.rect.x, o.rect.y, o.rect.w, o.rect.h}},
                                {"height", o.height()},
                                {"model", std::string(to_string(o.model))}};
            // A prism under a pitched roof: the ridge's ground axis and the eaves' height.
            if (o.ridge_axis >= 0) j["roof"] = {{"ridge", o.ridge_axis == 0 ? "x" : "y"}, {"eaves", o.eaves}};
            e["objects"].push_back(std::move(j));
        }
        e["solid_overlap"] = s.shape.empty() ? nlohmann::json(nullptr)
                                             : nlohmann::json(std::round(volume_overlap(objects, s.anchor_x, s.anchor_y,
                                                                                        s.shape) * 1000) / 1000);
        e["warning"] = warning.empty() ? nlohmann::json(nullptr) : nlohmann::json(warning);
        warnings += !warning.empty();
        report["sprites"].push_back(e);
        drawn.push_back({&s, std::move(fp), objects});
    }
    if (a.json) {
        std::cout << report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    } else {
        std::cout << "sprite                obstacle centre     anchor        distance  detected\n";
        for (const auto& e : report["sprites"]) {
            char line[256];
            const auto& c = e["obstacle_center"];
            std::snprintf(line, sizeof line, "%-20s  %-18s  %-12s  %-8s  %s", e["name"].get<std::string>().c_str(),
                          c.is_null() ? "none" : (std::to_string(int(c[0].get<double>())) + ", " + std::to_string(int(c[1].get<double>()))).c_str(),
                          (std::to_string(e["anchor"][0].get<int>()) + ", " + std::to_string(e["anchor"][1].get<int>())).c_str(),
                          e["distance"].is_null() ? "-" : std::to_string(int(std::lround(e["distance"].get<double>()))).c_str(),
                          e["detected"].dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
            std::cout << line << "\n";
            if (!e["warning"].is_null()) std::cout << "  warning: " << e["warning"].get<std::string>() << "\n";
        }
        std::cout << warnings << " warning" << (warnings == 1 ? "" : "s") << "\n";
    }
    if (!a.sheet.empty()) {
        save_image(a.sheet, contact_sheet(drawn));
        if (!a.json) std::cout << "wrote " << a.sheet << "\n";
    }
    return 0;
}

}  // namespace isolux::cli
