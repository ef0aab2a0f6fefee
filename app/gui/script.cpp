#include "gui/script.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "isolux/error.hpp"

namespace isolux::app {

Script load_script(const std::filesystem::path& path) {
    std::ifstream f(path);
    if (!f) throw Error(path.string() + ": cannot open script");
    Script s;
    std::string text;
    int line = 0;
    while (std::getline(f, text)) {
        ++line;
        if (auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
        std::istringstream in(text);
        ScriptStep step;
        step.line = line;
        if (!(in >> step.op)) continue;
        for (std::string a; in >> a;) step.args.push_back(a);
        // -1: one or more.
        static const std::pair<const char*, int> arity[] = {
            {"wait", 1}, {"click", 2}, {"rclick", 2}, {"drag", 4}, {"key", 1}, {"param", 2},
            {"type", 1}, {"window-shot", 1}, {"inspect", 1}, {"footprint", 2}, {"save-footprints", 0}, {"save-preset", 1}, {"save-scene", 1}, {"load-scene", 1}, {"load-preset", 1}, {"quit", 0},
            {"overlay", 2}, {"sweep", -1}, {"wait-sweep", 0}, {"long-work", 1}, {"apply-point", 1}, {"save-sweep", 1},
            {"tool", 1}, {"brush", 2}, {"view", 3}, {"click-tile", 2}, {"drag-tiles", 4}, {"new", 0}, {"fit", 0},
            {"open-dropped", 1}, {"check-glyphs", 1}, {"dump-panels", 1}, {"export-final", 1}, {"select", 1},
            {"character", -1}, {"show", 1}, {"export-tiled", 1}, {"move-lights", 1}, {"save-stats", 1}};
        bool known = false;
        for (auto [op, n] : arity)
            if (step.op == op) {
                known = true;
                if (n < 0 ? step.args.empty() : step.args.size() != std::size_t(n))
                    throw Error(path.string() + ":" + std::to_string(line) + ": " + step.op + " takes " +
                                (n < 0 ? std::string("one or more") : std::to_string(n)) + " arguments");
            }
        if (!known) throw Error(path.string() + ":" + std::to_string(line) + ": unknown command \"" + step.op + "\"");
        // Numbers are checked here, so a bad one is a message, not a crash mid-run.
        const bool numeric = step.op == "wait" || step.op == "click" || step.op == "rclick" || step.op == "drag" ||
                             step.op == "apply-point" || step.op == "view" || step.op == "click-tile" ||
                             step.op == "drag-tiles" || step.op == "move-lights";
        if (step.op == "character" && step.args.size() != 1 && step.args.size() != 3)
            throw Error(path.string() + ":" + std::to_string(line) + ": character takes on|off [X Y]");
        if (step.op == "view" && step.args.size() == 3) {
            const double z = std::strtod(step.args[2].c_str(), nullptr);
            if (!(z > 0))
                throw Error(path.string() + ":" + std::to_string(line) + ": view: zoom \"" + step.args[2] +
                            "\" must be a number above 0");
        }
        for (std::size_t k = 0; numeric && k < step.args.size(); ++k) {
            const std::string& a = step.args[k];
            char* end = nullptr;
            const double v = std::strtod(a.c_str(), &end);
            const double limit = step.op == "wait" || step.op == "apply-point" ? 1e6 : 1e5;
            if (a.empty() || *end != '\0' || !std::isfinite(v) || v < (step.op == "wait" ? 0 : -limit) || v > limit)
                throw Error(path.string() + ":" + std::to_string(line) + ": " + step.op + ": \"" + a +
                            "\" is not a number in [" + (step.op == "wait" ? "0" : "-" + std::to_string(int(limit))) +
                            ", " + std::to_string(int(limit)) + "]");
        }
        s.steps.push_back(step);
    }
    return s;
}

}  // namespace isolux::app
