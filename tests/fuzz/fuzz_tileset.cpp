// libFuzzer target: tileset manifests, with real images beside them (a 64x48
// sheet and a 16x16 sprite), so rects, anchors and kinds are exercised.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"

namespace fs = std::filesystem;

static fs::path folder() {
    static fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("isolux_fuzz_tileset_" + std::to_string(::getpid()));
        fs::create_directories(d);
        isolux::Image sheet(64, 48), sprite(16, 16);
        for (std::size_t i = 0; i < sheet.rgba.size(); ++i) sheet.rgba[i] = std::uint8_t(i * 7);
        for (std::size_t i = 0; i < sprite.rgba.size(); ++i) sprite.rgba[i] = std::uint8_t(i * 13);
        isolux::save_image(d / "sheet.png", sheet);
        isolux::save_image(d / "tree.png", sprite);
        return d;
    }();
    return dir;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const fs::path manifest = folder() / "tileset.json";
    {
        std::ofstream f(manifest, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        isolux::Tileset t = isolux::load_tileset(manifest);
        isolux::validate(t);
        // A map on what loaded, kept tiny.
        isolux::Map m = isolux::generate_map("fuzz", 3, 3, isolux::Layout::diamond, t);
        isolux::place_sprites(m, t);
    } catch (const isolux::Error&) {
    }
    return 0;
}
