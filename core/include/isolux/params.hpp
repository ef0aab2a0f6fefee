// The paper's parameters: one plain struct, and one table that describes each
// field (its file name, command-line flag, type, range, the paper's symbol, a
// help line and the frame stages it re-runs). Validation, set/get by name,
// preset and scene JSON, the command line, the app's sliders and the frame's
// caches all read the table: adding a parameter is a field here, one row in
// params.cpp's table, and its effect.
//
// A default-constructed Params is the paper's setting (section 3 and Figure 8)
// where the paper gives a value, and the project's documented choice where it
// does not (docs/method.md).
#pragma once
#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "isolux/stage.hpp"

namespace isolux {

// How rays interact with the obstacle map (paper 3.2 and 4).
enum class Mode {
    light,   // the paper's: rays stop at the first obstacle pixel
    shadow,  // the paper's inverted tracing: what lies beyond the first obstacle
    flat,    // no interaction, falloff only (the paper's Figure 10b)
};

// Where sprites meet the ground, for sprites whose manifest gives no footprint.
enum class Footprint {
    automatic,  // Algorithm 1 after taking out baked ground diamonds and baked shadows (footprint.hpp)
    paper,      // Algorithm 1 as the paper writes it
};

// How intensity falls with distance (not in the paper's choice but its function).
enum class FalloffShape {
    chebyshev,  // the paper's: d = max(|dx|, |dy|): square lights
    euclidean,  // d = sqrt(dx^2 + dy^2): round lights
};

// Where a light's distances are measured (not in the paper).
enum class FalloffSpace {
    screen,  // the paper's: d from the screen offset (dx, dy)
    ground,  // on the ground: dy scaled by the tileset's tile width over its height (r), so a
             // round light is a disc of ground, an ellipse r times as wide as tall on screen
};

// How the edge fade falls along a ray, t the share of the way to the border (not in the paper).
enum class FadeCurve {
    linear,  // 1 - t: its slope jumps to 0 at the border (a ring where it meets the unlit ground)
    smooth,  // 1 - 3t^2 + 2t^3: its slope 0 at the border and continuous everywhere
};

// How Algorithm 3 mixes a sprite's colour with the light.
enum class LightMix {
    luminance,  // the paper's: the sprite's luminance times the light (coloured lights paint their hue)
    surface,    // the sprite's own colour times the light (lit sprites keep their hue); soft shadows
};

// How the composite's result reaches the screen (not in the paper).
enum class ToneMap {
    none,           // Algorithm 3's per-channel clamp to [0, 1] (the paper)
    reinhard_knee,  // the added light's luminance rolled into the headroom the texture leaves (composite.hpp)
};

// What a light's rays are stopped by (not in the paper but its own model first).
enum class Occluders {
    footprints,  // the paper's: the obstacle map (where objects meet the ground), then the opacity correction
    solids,      // solids estimated from each sprite's alpha, the light at its height (solid_estimate.hpp)
    shapes,      // the manifest's own shapes (art made from 3D models), the light at its height
};

// What turns a sprite pixel's light with the way its surface faces each
// light (not in the paper: there a lit sprite pixel gets its light flat).
enum class SpriteShading {
    none,       // the paper's: no shading
    solids,     // the normals of the solids estimated from the sprites' alpha (sprite_shading.hpp)
    shapes,     // the manifest's true shapes, or its height maps
    luminance,  // the picture's brightness gradient, as normal-map generators make them
};

// Which pixels rays are traced to.
enum class Rays {
    border,       // every pixel of the area's border (paper 3.2, Algorithm 2)
    every_pixel,  // every pixel of the area: the paper's "4ab rays", the accuracy reference
};

// The defaults live here; the table reads them from Params{}.
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
    double light_height = 32;      // a light's height above the ground, pixels, when it gives none (not in the paper)
    bool rays_over_obstacles = false;  // rays pass over obstacles lower than the ray (height_rays.hpp; not in the paper)
    Occluders occluders = Occluders::footprints;  // what stops the rays (occluder_map.hpp; not in the paper)
    int occluder_scale = 1;         // s: solids and shapes traced over a map s times coarser (occluder_map.hpp)
    Footprint footprint = Footprint::automatic;  // sprites without their own footprint (not in the paper)
    FalloffShape falloff_shape = FalloffShape::chebyshev;
    FalloffSpace falloff_space = FalloffSpace::screen;  // where distances are measured (FalloffSpace)
    bool edge_fade = false;         // intensity falls to 0 at the area's border (not in the paper)
    FadeCurve fade_curve = FadeCurve::linear;  // the edge fade's curve (FadeCurve)
    LightMix light_mix = LightMix::luminance;  // how Algorithm 3 mixes a sprite's colour with the light (LightMix)
    double exposure = 1.0;          // multiplies Algorithm 3's light term (not in the paper; 1 is the paper's)
    ToneMap tone_map = ToneMap::none;  // how the composite reaches the screen (ToneMap; none is the paper's)
    SpriteShading sprite_shading = SpriteShading::none;  // sprites shaded by their surfaces' facing (SpriteShading)
    double shading_strength = 1.0;  // 0: flat light, 1: the full Lambert term (with sprite_shading)

    friend bool operator==(const Params&, const Params&) = default;
};

// Largest light half-extent a or b, pixels: for the preset's area and for a
// light's own.
inline constexpr int max_area = 4096;

enum class ParamType {
    integer,  // an int field
    real,     // a double field
    choice,   // an enum field, named by `choices`
    boolean,  // a bool field
};

// One row of the parameter table. Every value passes through a double: ints,
// enum values and bools are exact in it.
struct ParamInfo {
    const char* name;      // field name in presets and scenes, set_param, sweeps and the app's script
    const char* flag;      // command-line flag: the name with dashes ("--blur-radius")
    const char* old_flag;  // an older flag kept as an alias ("--blur"), or nullptr
    const char* label;     // the app's slider label
    const char* symbol;    // the paper's symbol (UTF-8), or ""
    const char* group;     // the app's section, citing the paper
    ParamType type;
    double min, max;       // accepted range; both ends included unless min_open
    bool min_open;
    double slider_min, slider_max;  // the app's slider span (Ctrl+click types any accepted value)
    bool logarithmic;      // slider scale
    std::array<const char*, 4> choices;  // ParamType::choice: names by enum value (nullptr past the last)
    const char* help;      // one line: what it does, in the paper's words
    StageSet reruns;       // frame stages a change re-runs (empty: it changes only when traces happen)
    double (*get)(const Params&);
    void (*set)(Params&, double);  // the value must already be valid (check_param)
};

// The table, in the order presets, --help and the app list parameters.
std::span<const ParamInfo> param_table();
// The row called `name`, or nullptr.
const ParamInfo* find_param(std::string_view name);
// The parameter's default (its value in Params{}).
double param_default(const ParamInfo& info);
// Number of names in a choice row.
int choice_count(const ParamInfo& info);

// Throws Error "source: field = value is out of range [lo, hi]" (or "is not
// one of ..." for a choice) when `v` is not an accepted value of the row.
void check_param(const ParamInfo& info, double v, std::string_view source);
// Throws Error naming `source` and the field when a value is out of range.
void validate(const Params& p, std::string_view source = "parameters");
// Text for a value ("25", "0.4", "every_pixel", "true") and back; parse
// throws Error naming `source` and the field when malformed or out of range.
std::string format_param(const ParamInfo& info, double v);
double parse_param(const ParamInfo& info, std::string_view text, std::string_view source);
// "[1, 4096]", "(0, 1e+06]", "light, shadow, flat" or "true, false".
std::string param_range_text(const ParamInfo& info);

// The stages that must re-run when the parameters go from `a` to `b`.
StageSet stages_changed(const Params& a, const Params& b);

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
// The parameter's value as text (for CSV columns and labels); "" when unknown.
std::string get_param(const Params& p, std::string_view name);

// Built-in presets: "paper" (the defaults), "fast", "quality", "game".
std::vector<std::string> builtin_preset_names();
// One line on what a built-in preset does (the app's status bar).
std::string builtin_preset_summary(std::string_view name);
Params builtin_preset(std::string_view name);  // throws Error when unknown

}  // namespace isolux
