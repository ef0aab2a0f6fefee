#include "cli/args.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/scene_file.hpp"

namespace isolux::cli {

void check_work(double steps, bool allow, const std::string& what, double bytes) {
    if (allow) return;
    char buf[64];
    if (steps > huge_trace_steps) {
        std::snprintf(buf, sizeof buf, "%.2g", steps);
        throw Error(what + " would trace about " + std::string(buf) +
                    " ray steps (minutes or more): use a smaller area or view, border rays or fewer frames, or --allow-huge");
    }
    if (bytes > huge_render_bytes) {
        throw Error(what + " would hold " + about_gib(bytes) +
                    " at once (its view's pixels): render part of it with --view X,Y,W,H, or --allow-huge");
    }
}

void add_param_flags(CLI::App& cmd, ParamArgs& pa) {
    cmd.add_option("--preset", pa.preset, "Preset JSON file, or a built-in: paper, fast, quality, game");
    const auto table = param_table();
    for (std::size_t i = 0; i < table.size(); ++i) {
        const ParamInfo& info = table[i];
        std::string names = info.flag;
        if (info.old_flag) names += std::string(",") + info.old_flag;
        std::string help = std::string(*info.symbol ? std::string(info.symbol) + ": " : "") + info.help + " " +
                           param_range_text(info) + ", default " + format_param(info, param_default(info)) + ".";
        if (info.type == ParamType::boolean)
            cmd.add_flag_callback(names, [&pa, i] { pa.values[i] = "true"; }, help);
        else
            cmd.add_option(names, pa.values[i], help);
    }
    cmd.add_option("--area", pa.area, "A,B: --area-a and --area-b at once");
}

Params params_from_args(const ParamArgs& a, Params p) {
    if (!a.preset.empty()) {
        std::vector<std::string> warnings;
        p = preset_named(a.preset, &warnings);
        for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << printable(w) << "\n";
    }
    if (a.area) {
        const std::size_t comma = a.area->find(',');
        if (comma == std::string::npos) throw Error("--area \"" + *a.area + "\": expected A,B (half-extents in pixels)");
        set_param(p, "area_a", a.area->substr(0, comma), "--area");
        set_param(p, "area_b", a.area->substr(comma + 1), "--area");
    }
    const auto table = param_table();
    for (std::size_t i = 0; i < table.size(); ++i)
        if (a.values[i]) set_param(p, table[i].name, *a.values[i], table[i].flag);
    validate(p, "parameters");
    return p;
}

std::string overridden_by_lights(std::string_view name, std::string_view flag, const std::vector<Light>& lights) {
    // The parameters a light may give for itself, and what it gives.
    struct Own {
        const char* name;
        bool (*gives)(const Light&);
        const char* what;
    };
    static const Own own[] = {
        {"light_height", [](const Light& l) { return l.height.has_value(); }, "its own height"},
        {"area_a", [](const Light& l) { return l.area_a.has_value(); }, "its own a (half-width)"},
        {"area_b", [](const Light& l) { return l.area_b.has_value(); }, "its own b (half-height)"},
    };
    for (const Own& o : own)
        if (name == o.name && !lights.empty() && std::all_of(lights.begin(), lights.end(), o.gives))
            return std::string(flag) + " changes nothing: " +
                   (lights.size() == 1 ? std::string("the one light gives ") : "each of the " + std::to_string(lights.size()) + " lights gives ") +
                   o.what;
    return "";
}

void note_overridden_flags(const ParamArgs& a, const std::vector<Light>& lights) {
    const auto table = param_table();
    std::vector<std::pair<std::string, std::string>> set;  // (name, flag as given)
    if (a.area) set.push_back({"area_a", "--area"}), set.push_back({"area_b", "--area"});
    for (std::size_t i = 0; i < table.size(); ++i)
        if (a.values[i]) set.push_back({table[i].name, table[i].flag});
    std::string said;  // --area names both a and b: one line each, unless the same
    for (const auto& [name, flag] : set) {
        const std::string note = overridden_by_lights(name, flag, lights);
        if (!note.empty() && note != said) std::cerr << "isolux-cli: note: " << note << "\n";
        if (!note.empty()) said = note;
    }
}

bool parse_ints(const std::string& s, char sep, std::vector<long long>& out) {
    out.clear();
    std::size_t pos = 0;
    while (true) {
        std::size_t end = s.find(sep, pos);
        std::string part = s.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (part.empty() || part.size() > 20) return false;
        std::size_t used = 0;
        try {
            out.push_back(std::stoll(part, &used));
        } catch (...) {
            return false;
        }
        if (used != part.size()) return false;
        if (end == std::string::npos) return true;
        pos = end + 1;
    }
}

bool parse_reals(const std::string& s, std::vector<double>& out) {
    out.clear();
    std::size_t pos = 0;
    while (true) {
        std::size_t end = s.find(',', pos);
        std::string part = s.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        std::size_t used = 0;
        try {
            out.push_back(std::stod(part, &used));
        } catch (...) {
            return false;
        }
        if (used != part.size() || !std::isfinite(out.back())) return false;
        if (end == std::string::npos) return true;
        pos = end + 1;
    }
}

Light parse_light(const std::string& text) {
    const std::string where = "--light \"" + text + "\"";
    std::vector<std::string> parts;
    std::optional<std::string> height;
    for (std::size_t pos = 0;;) {
        std::size_t end = text.find(',', pos);
        std::string part = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (part.rfind("h=", 0) == 0) height = part.substr(2);
        else parts.push_back(part);
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    if (parts.size() != 2 && parts.size() != 4 && parts.size() != 5)
        throw Error(where + ": expected X,Y or X,Y,A,B or X,Y,A,B,RRGGBB, each optionally with ,h=HEIGHT");
    Light l;
    if (height) {
        Params p;
        set_param(p, "light_height", *height, where + " h");
        l.height = p.light_height;
    }
    std::vector<double> xy;
    if (!parse_reals(parts[0] + "," + parts[1], xy) || std::abs(xy[0]) > 1e15 || std::abs(xy[1]) > 1e15)
        throw Error(where + ": X and Y must be numbers within ±1e15 (an endless world's pixels reach that far)");
    l.x = xy[0];
    l.y = xy[1];
    if (parts.size() >= 4) {
        std::vector<long long> ab;
        if (!parse_ints(parts[2] + "," + parts[3], ',', ab) || ab[0] < 0 || ab[1] < 0 ||
            ab[0] > max_area || ab[1] > max_area)
            throw Error(where + ": A and B must be integers in [0, " + std::to_string(max_area) + "]");
        l.area_a = int(ab[0]);
        l.area_b = int(ab[1]);
    }
    if (parts.size() == 5 && !parse_hex_color(parts[4], l.r, l.g, l.b))
        throw Error(where + ": colour must be RRGGBB hex");
    return l;
}

}  // namespace isolux::cli
