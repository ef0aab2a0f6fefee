// isolux-cli's shared arguments: the preset and parameter flags every
// subcommand that lights takes, --light, number lists, and the guard
// against work beyond a few seconds.
#pragma once
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "isolux/params.hpp"
#include "isolux/scene.hpp"

namespace isolux::cli {

// A preset and its overrides on the command line.
struct ParamArgs {
    std::string preset;  // a preset file or a built-in name
    // One per row of the parameter table, set only when given.
    std::vector<std::optional<std::string>> values = std::vector<std::optional<std::string>>(param_table().size());
    std::optional<std::string> area;  // --area A,B: area_a and area_b at once
};

// --preset, then one flag per row of the parameter table: --name-with-dashes
// (and its old name), help from the row, booleans as plain flags.
void add_param_flags(CLI::App& cmd, ParamArgs& pa);

// The preset (the scene's, a file or a built-in), then the overrides.
Params params_from_args(const ParamArgs& a, Params p);

// The note for a parameter set by `flag` (a flag, or a sweep's --param)
// that changes nothing because every one of `lights` gives its own value
// (light_height, area_a, area_b), else "". The caller prints it on stderr.
std::string overridden_by_lights(std::string_view name, std::string_view flag, const std::vector<Light>& lights);
// Prints that note for every parameter flag of `a` the lights override.
void note_overridden_flags(const ParamArgs& a, const std::vector<Light>& lights);

// Refuses work beyond what finishes in seconds, with the estimate and the
// flag that allows it anyway.
void check_work(double steps, bool allow, const std::string& what, double bytes = 0);

// Integers separated by `sep`, and reals separated by commas (finite):
// false, with `out` partial, on anything else.
bool parse_ints(const std::string& s, char sep, std::vector<long long>& out);
bool parse_reals(const std::string& s, std::vector<double>& out);

// --light X,Y[,A,B[,RRGGBB]][,h=H]
Light parse_light(const std::string& text);

}  // namespace isolux::cli
