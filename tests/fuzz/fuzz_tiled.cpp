// libFuzzer target: the TMX reader (load_tiled) on any bytes as a map file,
// beside a small tileset image and an external TSX it may name.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"

namespace fs = std::filesystem;

namespace {
fs::path folder() {
    static const fs::path dir = [] {
        const fs::path d = fs::temp_directory_path() / ("isolux_fuzz_tiled_" + std::to_string(::getpid()));
        fs::create_directories(d);
        isolux::Image im(64, 64);
        for (std::size_t i = 0; i < im.rgba.size(); ++i) im.rgba[i] = std::uint8_t(i * 37 % 251);
        isolux::save_image(d / "tiles.png", im);
        std::ofstream(d / "set.tsx") << R"(<?xml version="1.0"?><tileset name="s" tilewidth="32" tileheight="32" tilecount="4" columns="2"><tileoffset x="0" y="8"/><image source="tiles.png" width="64" height="64"/></tileset>)";
        return d;
    }();
    return dir;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const fs::path map = folder() / "map.tmx";
    {
        std::ofstream f(map, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        isolux::TiledMap t = isolux::load_tiled(map);
        // What it accepted is a world the pipeline can light.
        if (t.world.placed.instances.empty()) __builtin_trap();
        for (const isolux::SpriteInstance& in : t.world.placed.instances)
            if (in.sprite < 0 || std::size_t(in.sprite) >= t.world.tileset.sprites.size()) __builtin_trap();
    } catch (const isolux::Error&) {
    }
    return 0;
}
