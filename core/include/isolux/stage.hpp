// The stages of one frame (paper Figure 4), in the order they run. Shared by
// the frame driver, which reports which ran, and the parameter table, which
// says which a parameter's change re-runs.
#pragma once
#include <cstdint>
#include <string_view>

namespace isolux {

enum class Stage { sprites, obstacle_map, trace, opacity_correction, blur, shift, composite };
inline constexpr int stage_count = 7;
std::string_view to_string(Stage s);

// A set of stages, as bits by Stage value.
struct StageSet {
    std::uint32_t bits = 0;
    constexpr bool has(Stage s) const { return bits >> int(s) & 1u; }
    constexpr StageSet with(Stage s) const { return {bits | 1u << int(s)}; }
    friend constexpr StageSet operator|(StageSet a, StageSet b) { return {a.bits | b.bits}; }
    friend constexpr bool operator==(StageSet, StageSet) = default;
};

// `first` and every stage after it that depends on its output: a new obstacle
// map means a new trace, a new trace a new blur, and so on. The view's sprites
// depend on no parameter.
constexpr StageSet stages_from(Stage first) {
    StageSet s;
    for (int k = int(first); k < stage_count; ++k)
        if (Stage(k) != Stage::sprites) s = s.with(Stage(k));
    return s;
}

}  // namespace isolux
