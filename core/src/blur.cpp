// Paper 3.2: "Once the light texture is in the GPU, a simple box-blur
// algorithm is applied to the same." CPU reference of shaders/blur.frag.
#include "isolux/blur.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <vector>

namespace isolux {

namespace {

bool valid(const LightTexture& tex) {
    return tex.rgb.size() == std::size_t(std::max(0, tex.rect.w)) * std::max(0, tex.rect.h) * 3;
}

// round(v / n) for the window sums v <= 255 n, n odd: floor(v / n + 1/2).
// The exact quotient's fraction is a multiple of 1/n, so after adding 1/2 it
// stays 1/(2n) away from an integer; float's error (< 4e-5 at 256) is below
// that while n < 16000 (radius <= 62), double's for every radius.
template <class Real>
void divide_row(const std::uint32_t* sum, std::size_t count, std::uint32_t n, std::uint8_t* out) {
    const Real inv = Real(1) / Real(n), half = Real(n) * Real(0.5);
    for (std::size_t j = 0; j < count; ++j) out[j] = std::uint8_t(std::int32_t((Real(std::int32_t(sum[j])) + half) * inv));
}

// One row's horizontal window sums over local columns [x0, x0 + w) of a
// texture `width` wide: each the sum of 2r+1 texels, clamped at the edges.
struct RowSums {
    int r, width, x0, w;
    std::vector<std::uint32_t> pad, prefix;

    RowSums(int radius, int tex_width, int col0, int cols)
        : r(radius), width(tex_width), x0(col0), w(cols), pad(std::size_t(cols + 2 * radius) * 3),
          prefix(radius > 3 ? pad.size() + 3 : 0) {}

    void operator()(const std::uint8_t* row, std::uint32_t* out) {
        // The row with its clamped border: pad[i] is texel x0 - r + i.
        const int n = w + 2 * r;
        const int inner0 = std::clamp(r - x0, 0, n), inner1 = std::clamp(width + r - x0, inner0, n);
        for (int i = 0; i < inner0; ++i)
            for (int c = 0; c < 3; ++c) pad[std::size_t(i) * 3 + c] = row[c];
        const std::uint8_t* src = row + std::size_t(x0 - r + inner0) * 3;
        for (std::size_t j = 0, m = std::size_t(inner1 - inner0) * 3; j < m; ++j) pad[std::size_t(inner0) * 3 + j] = src[j];
        for (int i = inner1; i < n; ++i)
            for (int c = 0; c < 3; ++c) pad[std::size_t(i) * 3 + c] = row[std::size_t(width - 1) * 3 + c];
        const std::size_t m = std::size_t(w) * 3;
        if (r <= 3) {  // a few shifted adds, each a vector loop
            std::memcpy(out, pad.data(), m * sizeof(std::uint32_t));
            for (int t = 1; t <= 2 * r; ++t) {
                const std::uint32_t* p = pad.data() + std::size_t(t) * 3;
                for (std::size_t j = 0; j < m; ++j) out[j] += p[j];
            }
            return;
        }
        // Wider windows: differences of running sums (prefix[k + 3] = sum of pad[<= k] per channel).
        prefix[0] = prefix[1] = prefix[2] = 0;
        for (std::size_t k = 0; k < pad.size(); ++k) prefix[k + 3] = prefix[k] + pad[k];
        const std::size_t span = std::size_t(2 * r + 1) * 3;
        for (std::size_t j = 0; j < m; ++j) out[j] = prefix[j + span] - prefix[j];
    }
};

}  // namespace

void box_blur_into(const LightTexture& tex, int radius, Rect region, LightTexture& out) {
    assert(radius >= 0 && valid(tex));
    if (!(out.rect == tex.rect) || !valid(out)) out = LightTexture(tex.rect);
    const Rect z = intersect(region, tex.rect);
    if (z.empty()) return;
    const int w = tex.rect.w, h = tex.rect.h;
    const int x0 = z.x - tex.rect.x, y0 = z.y - tex.rect.y;
    const std::size_t m = std::size_t(z.w) * 3;
    if (radius == 0) {
        for (int y = y0; y < y0 + z.h; ++y)
            std::memcpy(&out.rgb[(std::size_t(y) * w + x0) * 3], &tex.rgb[(std::size_t(y) * w + x0) * 3], m);
        return;
    }
    // Rows are visited top to bottom; the 2r+1 rows of horizontal sums in the
    // window live in a ring (slot of window row i: i mod 2r+1) and their
    // column sums are updated as the window slides: new row in, old row out.
    const int span = 2 * radius + 1;
    const std::uint32_t n = std::uint32_t(span) * std::uint32_t(span);
    RowSums row_sums(radius, w, x0, z.w);
    std::vector<std::uint32_t> ring(std::size_t(span) * m), column(m, 0), incoming(m);
    auto slot = [&](int i) { return &ring[std::size_t(((i % span) + span) % span) * m]; };
    auto texel_row = [&](int i) { return &tex.rgb[std::size_t(std::clamp(i, 0, h - 1)) * w * 3]; };
    for (int i = y0 - radius; i <= y0 + radius; ++i) {
        std::uint32_t* s = slot(i);
        row_sums(texel_row(i), s);
        for (std::size_t j = 0; j < m; ++j) column[j] += s[j];
    }
    for (int y = y0; y < y0 + z.h; ++y) {
        std::uint8_t* dst = &out.rgb[(std::size_t(y) * w + x0) * 3];
        if (n < 16000)
            divide_row<float>(column.data(), m, n, dst);
        else
            divide_row<double>(column.data(), m, n, dst);
        if (y + 1 == y0 + z.h) break;
        std::uint32_t* s = slot(y - radius);  // leaves the window; y + r + 1 takes its slot
        row_sums(texel_row(y + radius + 1), incoming.data());
        for (std::size_t j = 0; j < m; ++j) {
            column[j] += incoming[j] - s[j];
            s[j] = incoming[j];
        }
    }
}

LightTexture box_blur(const LightTexture& tex, int radius) {
    assert(radius >= 0 && valid(tex));
    if (radius <= 0 || tex.rect.empty()) return tex;
    LightTexture out(tex.rect);
    box_blur_into(tex, radius, tex.rect, out);
    return out;
}

LightTexture box_blur_reference(const LightTexture& tex, int radius) {
    assert(radius >= 0 && valid(tex));
    if (radius <= 0 || tex.rect.empty()) return tex;
    const int w = tex.rect.w, h = tex.rect.h;
    const std::uint64_t n = std::uint64_t(2 * radius + 1) * (2 * radius + 1);
    LightTexture out(tex.rect);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                std::uint64_t sum = 0;
                for (int dy = -radius; dy <= radius; ++dy)
                    for (int dx = -radius; dx <= radius; ++dx)
                        sum += tex.rgb[(std::size_t(std::clamp(y + dy, 0, h - 1)) * w + std::clamp(x + dx, 0, w - 1)) * 3 + c];
                out.rgb[(std::size_t(y) * w + x) * 3 + c] = std::uint8_t((sum + n / 2) / n);
            }
    return out;
}

}  // namespace isolux
