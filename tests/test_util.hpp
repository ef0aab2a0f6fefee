// Helpers shared by the tests: tiny hand-made sprites and the default tileset.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/cpu.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/image.hpp"
#include "isolux/light_trace.hpp"

namespace isolux::test {

// The message of the Error that `f` throws, or "" when it throws none.
template <class F>
std::string error_of(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

#define EXPECT_MENTIONS(msg, text) EXPECT_NE((msg).find(text), std::string::npos) << (msg)

// A folder of this test's own under the temp directory, named after the test
// and the process, removed when it ends. `made`: created empty now; else left
// for the code under test to create (an editor's config folder).
struct TempDir {
    std::filesystem::path path;
    explicit TempDir(bool made = true)
        : path(std::filesystem::temp_directory_path() /
               ("isolux_test_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
        std::filesystem::remove_all(path);
        if (made) std::filesystem::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    // Writes `text` as the file `name` in the folder; returns its path.
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        std::ofstream(path / name, std::ios::binary) << text;
        return path / name;
    }
};

// A sprite from rows of characters: '#' opaque (alpha 255), '+' half (alpha
// 128), anything else transparent.
inline Image sprite_from(const std::vector<std::string>& rows) {
    Image im(int(rows[0].size()), int(rows.size()));
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            std::uint8_t* p = im.at(x, y);
            p[0] = p[1] = p[2] = 200;
            p[3] = rows[y][x] == '#' ? 255 : rows[y][x] == '+' ? 128 : 0;
        }
    return im;
}

// A mask from rows of characters: '#' set.
inline Mask mask_from(const std::vector<std::string>& rows, int x0 = 0, int y0 = 0) {
    Mask m(Rect{x0, y0, int(rows[0].size()), int(rows.size())});
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) m.bits[std::size_t(y) * m.width + x] = rows[y][x] == '#';
    return m;
}

// The set pixels of a mask, as "x,y" strings in raster order, for readable failures.
inline std::vector<std::string> set_pixels(const Mask& m) {
    std::vector<std::string> out;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
            if (m.bits[std::size_t(y) * m.width + x])
                out.push_back(std::to_string(x + m.x0) + "," + std::to_string(y + m.y0));
    return out;
}

// A traced light's pixels as 0/1: lit or not.
inline std::vector<std::uint8_t> lit_of(const LightMask& m) {
    std::vector<std::uint8_t> out(m.value.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = m.value[i] ? 1 : 0;
    return out;
}

inline Tileset default_tileset() { return load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json"); }

// The index of the tileset's sprite named `name` (a test failure and -1
// when there is none).
inline int sprite_index(const Tileset& tileset, const char* name) {
    for (std::size_t i = 0; i < tileset.sprites.size(); ++i)
        if (tileset.sprites[i].name == name) return int(i);
    ADD_FAILURE() << "no sprite " << name;
    return -1;
}

// A seeded side x side map of the default tileset and one light `height` px
// up at the centre of its camera's view, over an area of 200 x 200 with
// `falloff_scale`: the scene of the shading and shaded-reference tests.
struct CentredLight {
    Scene scene;
    World world;
    Rect view;
};
inline CentredLight centred_light(int side, double height, double falloff_scale) {
    Scene s;
    s.width = s.height = side;
    World w = make_world(default_tileset(), s);
    const Rect v = camera_view(s.camera, w);
    Light l{v.x + v.w / 2.0 + 0.5, v.y + v.h / 2.0 + 0.5};
    l.height = height;
    s.lights = {l};
    s.params.area_a = s.params.area_b = 200;
    s.params.falloff_scale = falloff_scale;
    return {s, std::move(w), v};
}
inline Tileset foreign_tileset() {
    return load_tileset(std::string(ISOLUX_TEST_DATA) + "/foreign_tileset/tileset.json");
}

// Texels mostly dark with bright patches and full-white runs: the sums reach
// their maximum and every rounding case appears.
inline LightTexture random_texture(Rect r, std::uint64_t seed) {
    LightTexture t(r);
    Pcg32 rng(seed);
    for (std::size_t i = 0; i < t.texels.size(); ++i) {
        const std::uint32_t k = rng.below(10);
        t.texels[i] = k < 4 ? 0 : k < 6 ? 255 : std::uint8_t(rng.below(256));
    }
    return t;
}

// The kernels' builds to hold to the same bytes (base/cpu.hpp): the
// baseline, and AVX2 when this CPU has it (said once, so a run without it
// is seen).
inline std::vector<bool> both_widths() {
    static const bool has_avx2 = [] {
        set_wide_kernels(true);
        const bool on = wide_kernels();
        if (!on) std::printf("note: this CPU has no AVX2: only the baseline kernels are tested\n");
        return on;
    }();
    return has_avx2 ? std::vector<bool>{false, true} : std::vector<bool>{false};
}

}  // namespace isolux::test
