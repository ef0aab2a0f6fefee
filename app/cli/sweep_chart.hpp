// isolux-cli sweep --chart: error against time as an SVG chart, with a
// table of every point beside it.
#pragma once
#include <string>
#include <vector>

#include "isolux/accuracy.hpp"

namespace isolux::cli {

// The chart of a sweep's points: lighting time (median, min to max) against
// the final frame's RMSE, each reference's Pareto front as a line.
std::string sweep_svg(const std::vector<SweepAxis>& axes, const std::vector<SweepPoint>& points,
                      const std::string& title);

}  // namespace isolux::cli
