// libFuzzer target: the scene parser, and a save/load round trip of what it accepts.
#include <cstdint>
#include <string_view>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        isolux::Scene s =
            isolux::scene_from_json(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json", nullptr);
        isolux::validate(s.params);
        isolux::Scene back = isolux::scene_from_json(isolux::scene_to_json(s), "roundtrip.json", nullptr);
        if (back.lights.size() != s.lights.size()) __builtin_trap();
    } catch (const isolux::Error&) {
    }
    return 0;
}
