// The paper's parameters in one plain struct. A default-constructed Params is
// the paper's setting (section 3 and Figure 8) where the paper gives a value,
// and the project's documented choice where it does not (docs/method.md).
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace isolux {

// How rays interact with the obstacle map (paper 3.2 and 4).
enum class Mode {
    light,   // the paper's: rays stop at the first obstacle pixel
    shadow,  // the paper's inverted tracing: what lies beyond the first obstacle
    flat,    // no interaction, falloff only (the paper's Figure 10b)
};

// Which pixels rays are traced to.
enum class Rays {
    border,       // every pixel of the area's border (paper 3.2, Algorithm 2)
    every_pixel,  // every pixel of the area: the paper's "4ab rays", the accuracy reference
};

struct Params {
    int delta_y = 25;              // Δy: lines read per sprite by Algorithm 1 (paper 3.1: 25 for 128 px)
    int noise_window = 3;          // n: box noise filter window (paper 3.1; value not given)
    int ray_skip = 1;              // k: trace every k-th border ray (paper 3.2)
    int trace_every = 1;           // l: retrace once every l frames (paper 3.2)
    int area_a = 128;              // a: light area half-width, pixels; the area is (2a+1)x(2b+1)
    int area_b = 128;              // b: light area half-height, pixels
    double ambient_clarity = 0.4;  // Algorithm 3's ambientClarity (paper 4: 0.4)
    double opacity_threshold = 0.5;  // alpha above this is opaque (opacity maps, Algorithm 1)
    int blur_radius = 2;           // box blur radius on the light texture, pixels (paper 3.2)
    double falloff_scale = 1.0;    // i = 255 / (1 + max(|dx|,|dy|) / falloff_scale); 1 is the paper's
    Mode mode = Mode::light;
    bool dark_unlit = false;       // Algorithm 3 variant: texFactor *= light (paper 4)
    Rays rays = Rays::border;

    friend bool operator==(const Params&, const Params&) = default;
};

// The accepted range of each parameter, checked by validate() and the files.
struct ParamLimits {
    static constexpr int max_delta_y = 4096;
    static constexpr int max_noise_window = 255;
    static constexpr int max_ray_skip = 1 << 20;
    static constexpr int max_trace_every = 10000;
    static constexpr int max_area = 4096;
    static constexpr int max_blur_radius = 255;
    static constexpr double max_falloff_scale = 1e6;
};

// Throws Error naming `source` and the field when a value is out of range.
void validate(const Params& p, std::string_view source = "parameters");

std::string_view to_string(Mode m);
std::string_view to_string(Rays r);
// Parse a mode or rays name; throw Error naming `source` when unknown.
Mode parse_mode(std::string_view s, std::string_view source);
Rays parse_rays(std::string_view s, std::string_view source);

// Sets the parameter called `name` (a preset field name, e.g. "ray_skip") from
// text; throws Error naming `source` and the field when the name is unknown
// or the value malformed or out of range.
void set_param(Params& p, std::string_view name, std::string_view value, std::string_view source);
std::vector<std::string> param_names();
// The parameter's value as text (for CSV columns and labels).
std::string get_param(const Params& p, std::string_view name);

// Built-in presets: "paper" (the defaults), "fast", "quality".
std::vector<std::string> builtin_preset_names();
Params builtin_preset(std::string_view name);  // throws Error when unknown

}  // namespace isolux
