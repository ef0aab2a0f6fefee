// The light texture (paper 3.2): what the traced rays draw, one RGB texel per
// world pixel over a rectangle slightly larger than the view.
#pragma once
#include <cstdint>
#include <limits>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/params.hpp"
#include "isolux/scene.hpp"

namespace isolux {

struct LightTexture {
    Rect rect;                       // world pixels
    std::vector<std::uint8_t> rgb;   // rect.w * rect.h * 3

    LightTexture() = default;
    explicit LightTexture(Rect r) : rect(r), rgb(std::size_t(r.w) * r.h * 3, 0) {}
    const std::uint8_t* at(int wx, int wy) const {
        return &rgb[(std::size_t(wy - rect.y) * rect.w + (wx - rect.x)) * 3];
    }
};

// Adds one light's pixels to the texture: Mode::light and Mode::flat add the
// lit pixels, Mode::shadow the reached-but-unlit ones, each with
// falloff(d) * intensity * colour / 255 per channel, rounded. Sums saturate at
// 255 per channel; since every contribution is >= 0 the result is
// min(255, total), whatever the order lights are added in. A white light of
// intensity 1 adds exactly the paper's 255 / (1 + d) to all three channels.
// Only rows [row_begin, row_end) of the texture are touched (world y), so
// threads may add into separate bands of one texture; and only `within`
// when given (world pixels), so a frame re-adds just where lights changed.
void accumulate_light(LightTexture& tex, const LightMask& mask, const Light& light, const Params& p,
                      int row_begin = std::numeric_limits<int>::min(), int row_end = std::numeric_limits<int>::max(),
                      const Rect* within = nullptr);

// The paper's inverse translation between retraces: the texture of `view`
// read from `traced` (a world-anchored texture of an earlier frame). Texels
// outside `traced` are 0 (unlit).
LightTexture shift_light_texture(const LightTexture& traced, Rect view);

// The texture as an opaque RGBA image (for export and display).
Image light_texture_image(const LightTexture& tex);

// The (2a+1) x (2b+1) area of a light (its own a, b or the preset's), world pixels.
Rect light_area(const Light& light, const Params& p);
int light_a(const Light& light, const Params& p);
int light_b(const Light& light, const Params& p);

}  // namespace isolux
