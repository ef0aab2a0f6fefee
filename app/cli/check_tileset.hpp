// isolux-cli check-tileset: for every overlay sprite, where its obstacle
// lands against its anchor, what the footprint estimate detected, and its
// estimated objects (text, --json, and a --sheet to look at).
#pragma once
#include <string>

#include "cli/args.hpp"

namespace isolux::cli {

struct CheckArgs {
    std::string manifest, sheet;
    bool json = false;
    ParamArgs params;
};

// Prints the report and writes the sheet; throws Error naming the file and
// field at fault.
int run_check_tileset(const CheckArgs& a);

}  // namespace isolux::cli
