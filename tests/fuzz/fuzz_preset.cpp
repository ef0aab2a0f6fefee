// libFuzzer target: the preset parser. Any bytes give Params or an Error,
// never a crash, a hang or undefined behaviour.
#include <cstdint>
#include <string_view>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> warnings;
    try {
        isolux::Params p = isolux::preset_from_json(std::string_view(reinterpret_cast<const char*>(data), size),
                                                     "fuzz.json", &warnings);
        isolux::validate(p);  // what loads is always in range
        isolux::preset_from_json(isolux::preset_to_json(p), "roundtrip.json");
    } catch (const isolux::Error&) {
    }
    return 0;
}
