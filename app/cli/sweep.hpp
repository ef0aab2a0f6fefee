// isolux-cli sweep: accuracy against time, every combination of the
// parameters given, as a CSV (and an SVG chart) with its Pareto front.
#pragma once
#include <string>
#include <vector>

namespace isolux::cli {

struct SweepArgs {
    std::string scene, out, chart;
    std::vector<std::string> params;
    int frames = 8, repeats = 3;
    std::string step = "24,12";
    std::string references = "every_pixel";
    bool no_carry = false;
    bool allow_huge = false;
    bool no_opacity_correction = false;
};

// Writes the CSV row by row as it is measured; throws Error naming the file
// and field at fault.
int run_sweep_command(const SweepArgs& a);

}  // namespace isolux::cli
