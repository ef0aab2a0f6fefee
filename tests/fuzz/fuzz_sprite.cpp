// libFuzzer target: sprite loading (any bytes as an image file), then the
// opacity map and Algorithm 1 on whatever decodes.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("isolux_fuzz_sprite_" + std::to_string(::getpid()) + ".png");
    {
        std::ofstream f(path, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        isolux::Image im = isolux::load_image(path);
        if (std::size_t(im.width) * im.height > (1u << 22)) return 0;
        isolux::Mask op = isolux::opacity_map(im, 0.5);
        isolux::sprite_obstacle(op, 25);
    } catch (const isolux::Error&) {
    }
    return 0;
}
