// The light texture (paper 3.2): what the traced rays draw, one texel per
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

// A texel is r, g, b, or (channels 1, "grey") one byte standing for all
// three: a frame whose lights are all grey (r = g = b, white among them) adds,
// blurs and reads a third of the bytes for the same pixels.
struct LightTexture {
    Rect rect;                          // world pixels
    int channels = 3;                   // 3: r, g, b; 1: grey
    std::vector<std::uint8_t> texels;   // rect.w * rect.h * channels, row by row

    LightTexture() = default;
    explicit LightTexture(Rect r, int channel_count = 3)
        : rect(r), channels(channel_count), texels(std::size_t(r.w) * r.h * std::size_t(channel_count), 0) {}
    const std::uint8_t* at(int wx, int wy) const {
        return &texels[(std::size_t(wy - rect.y) * rect.w + (wx - rect.x)) * std::size_t(channels)];
    }
    // Channel c (0 r, 1 g, 2 b) of the texel at world (wx, wy), in either layout.
    std::uint8_t value(int wx, int wy, int c) const { return at(wx, wy)[channels == 3 ? c : 0]; }
};

// Whether a light's texels are grey: every channel the same.
inline bool grey_light(const Light& l) { return l.r == l.g && l.g == l.b; }

// Whether a texture's layout holds: 1 or 3 channels, and its texels sized to its rectangle.
inline bool well_formed(const LightTexture& tex) {
    return (tex.channels == 1 || tex.channels == 3) &&
           tex.texels.size() == std::size_t(tex.rect.w > 0 ? tex.rect.w : 0) * std::size_t(tex.rect.h > 0 ? tex.rect.h : 0) *
                                    std::size_t(tex.channels);
}

// The texture with three channels (a grey one's value copied into each).
LightTexture rgb_texture(const LightTexture& tex);

// Adds one light's pixels to the texture (a grey texture takes grey lights
// only): Mode::light and Mode::flat add the
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
// read from `traced` (a world-anchored texture of an earlier frame), in its
// channels. Texels outside `traced` are 0 (unlit).
LightTexture shift_light_texture(const LightTexture& traced, Rect view);

// The texture as an opaque RGBA image (for export and display).
Image light_texture_image(const LightTexture& tex);

// The (2a+1) x (2b+1) area of a light (its own a, b or the preset's), world pixels.
Rect light_area(const Light& light, const Params& p);
int light_a(const Light& light, const Params& p);
int light_b(const Light& light, const Params& p);

}  // namespace isolux
