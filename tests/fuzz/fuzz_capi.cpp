// libFuzzer target: the C API (isolux.h) driven by any bytes as a caller
// would misuse it. Each input is a program of calls on one small seeded
// world: lights added, moved, hidden and removed by ids that exist or not,
// parameters and presets by good and bad names and values, tile edits in and
// out of the map, renders of good and bad views with buffers of the right
// and the wrong size, and the world freed at the end. Whatever it does, a
// call answers a status, the world stays usable, and nothing crashes.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "isolux.h"
#include "isolux/image_file.hpp"
#include "isolux/isolux.hpp"

namespace {

// A small tileset of its own (a floor and two overlays), so an input costs
// its calls and not the default tileset's loading.
const std::string& tileset_manifest() {
    static const std::string path = [] {
        namespace fs = std::filesystem;
        const fs::path d = fs::temp_directory_path() / ("isolux_fuzz_capi_" + std::to_string(::getpid()));
        fs::create_directories(d);
        auto image = [&](const char* name, int w, int h, int opaque_from) {
            isolux::Image im(w, h);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    std::uint8_t* p = im.at(x, y);
                    p[0] = std::uint8_t(40 + x * 3), p[1] = std::uint8_t(90 + y), p[2] = 60;
                    p[3] = y >= opaque_from && std::abs(x - w / 2) < (y - opaque_from) / 2 + 2 ? 255 : 0;
                }
            isolux::save_image(d / name, im);
        };
        image("grass.png", 64, 32, 0);
        image("tree.png", 24, 40, 4);
        image("rock.png", 20, 14, 2);
        std::ofstream(d / "tileset.json") << R"({"tile": {"width": 64, "height": 32}, "sprites": [
            {"name": "grass", "image": "grass.png", "kind": "floor", "tags": ["grass"]},
            {"name": "water", "image": "grass.png", "kind": "floor", "tags": ["water"]},
            {"name": "tree", "image": "tree.png", "kind": "overlay", "tags": ["tree"]},
            {"name": "rock", "image": "rock.png", "kind": "overlay", "tags": ["rock"],
             "shape": [{"kind": "box", "min": [-4, -4, 0], "max": [4, 4, 10]}]}]})";
        return (d / "tileset.json").string();
    }();
    return path;
}

// Texts a caller may pass: real names and values, and wrong ones.
const char* const param_names[] = {"ray_skip", "trace_every", "area_a", "area_b", "ambient_clarity", "rays",
                                   "occluders", "delta_y", "noise_window", "light_height", "blur_radius", "falloff_scale",
                                   "no_such", "", "RAY_SKIP"};
const char* const param_values[] = {"0",    "1",     "2",    "-1",  "64",     "300",         "1e9",   "nan",
                                    "true", "false", "solids", "shapes", "every_pixel", "border", "x", ""};
const char* const sprite_names[] = {"grass", "water", "tree", "rock", "oak", "no_such", "", "../grass"};
const char* const presets[] = {"paper", "fast", "quality", "game", "nowhere.json", "", "./paper"};

template <std::size_t N>
const char* pick(FuzzedDataProvider& in, const char* const (&list)[N]) {
    return list[in.ConsumeIntegralInRange<std::size_t>(0, N - 1)];
}

// A coordinate: ordinary mostly, sometimes far, infinite or not a number.
double coordinate(FuzzedDataProvider& in) {
    switch (in.ConsumeIntegralInRange(0, 7)) {
    case 0: return std::numeric_limits<double>::quiet_NaN();
    case 1: return std::numeric_limits<double>::infinity();
    case 2: return in.ConsumeFloatingPoint<double>();
    default: return in.ConsumeIntegralInRange(-600, 1400);
    }
}

// An id that exists, or one that does not.
int light_id(FuzzedDataProvider& in, const std::vector<int>& ids) {
    if (!ids.empty() && in.ConsumeBool()) return ids[in.ConsumeIntegralInRange<std::size_t>(0, ids.size() - 1)];
    return in.ConsumeIntegral<int>();
}

isolux_light light_from(FuzzedDataProvider& in) {
    isolux_light l;
    isolux_light_init(&l, coordinate(in), coordinate(in));
    l.area_a = in.ConsumeIntegralInRange(-5, 200);
    l.area_b = in.ConsumeIntegralInRange(-5, 200);
    l.r = in.ConsumeIntegral<std::uint8_t>();
    l.intensity = in.ConsumeBool() ? coordinate(in) : 1.0;
    l.height = in.ConsumeBool() ? coordinate(in) : -1.0;
    return l;
}

void render(FuzzedDataProvider& in, isolux_world* w) {
    isolux_rect view{in.ConsumeIntegralInRange(-300, 900), in.ConsumeIntegralInRange(-300, 600),
                     in.ConsumeIntegralInRange(-2, 160), in.ConsumeIntegralInRange(-2, 120)};
    if (in.ConsumeIntegralInRange(0, 15) == 0) view.width = in.ConsumeIntegral<int>();  // anything at all
    const std::size_t bytes = view.width > 0 && view.height > 0 && view.width <= 160 && view.height <= 120
                                  ? std::size_t(view.width) * std::size_t(view.height) * 4
                                  : 64;
    std::vector<std::uint8_t> rgba(bytes), light(bytes);
    const std::size_t told = in.ConsumeBool() ? bytes : in.ConsumeIntegralInRange<std::size_t>(0, bytes);
    isolux_world_render(w, view, in.ConsumeIntegralInRange(-1, 40), in.ConsumeBool() ? rgba.data() : nullptr, told,
                        in.ConsumeBool() ? light.data() : nullptr, told);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    isolux_world* w = nullptr;
    const int side = in.ConsumeIntegralInRange(-1, 6);
    if (isolux_world_open_seeded("fuzz", side, 4, in.ConsumeBool() ? "staggered" : nullptr, tileset_manifest().c_str(),
                                 &w) != ISOLUX_OK)
        return 0;
    std::vector<int> ids;
    char buf[64];
    for (int step = 0; step < 24 && in.remaining_bytes() > 0; ++step) {
        switch (in.ConsumeIntegralInRange(0, 15)) {
        case 0: {
            const isolux_light l = light_from(in);
            int id = -1;
            if (isolux_world_add_light(w, &l, &id) == ISOLUX_OK) ids.push_back(id);
            break;
        }
        case 1: isolux_world_move_light(w, light_id(in, ids), coordinate(in), coordinate(in)); break;
        case 2: isolux_world_remove_light(w, light_id(in, ids)); break;
        case 3: isolux_world_set_light_hidden(w, light_id(in, ids), in.ConsumeIntegralInRange(-1, 2)); break;
        case 4: {
            const isolux_light l = light_from(in);
            isolux_world_set_light(w, light_id(in, ids), &l);
            break;
        }
        case 5: {
            isolux_light l;
            if (isolux_world_get_light(w, light_id(in, ids), &l) == ISOLUX_OK && in.ConsumeBool())
                isolux_world_set_light(w, light_id(in, ids), &l);  // what get returned, given back
            break;
        }
        case 6: isolux_world_set_param(w, pick(in, param_names), pick(in, param_values)); break;
        case 7: isolux_world_get_param(w, pick(in, param_names), buf, in.ConsumeIntegralInRange<std::size_t>(0, sizeof buf)); break;
        case 8: isolux_world_load_preset(w, pick(in, presets)); break;
        case 9: {
            const char* overlays[4] = {pick(in, sprite_names), pick(in, sprite_names), pick(in, sprite_names),
                                       pick(in, sprite_names)};
            isolux_world_set_tile(w, in.ConsumeIntegralInRange(-3, 9), in.ConsumeIntegralInRange(-3, 9),
                                  in.ConsumeBool() ? pick(in, sprite_names) : nullptr, overlays,
                                  in.ConsumeIntegralInRange(-1, 4));
            break;
        }
        case 10: isolux_world_clear_edits(w); break;
        case 11: render(in, w); break;
        case 12: isolux_world_allow_huge(w, in.ConsumeIntegralInRange(-1, 2)); break;
        case 13: isolux_world_set_threads(w, in.ConsumeIntegralInRange(-1, 3)); break;
        case 14: {
            int got[8], count = -1;
            isolux_world_lights(w, in.ConsumeBool() ? got : nullptr, in.ConsumeIntegralInRange(-1, 8), &count);
            break;
        }
        default: {
            isolux_rect r;
            int cols = 0, rows = 0;
            isolux_world_bounds(w, &r);
            isolux_world_default_view(w, &r);
            isolux_world_tiles(w, &cols, &rows);
            isolux_world_cancel(w);  // on an idle world: forgotten by the next call
            break;
        }
        }
    }
    // Still a world: a small frame renders after whatever came before.
    isolux_world_set_param(w, "occluders", "footprints");
    isolux_world_allow_huge(w, 0);
    std::vector<std::uint8_t> rgba(32 * 32 * 4);
    const isolux_status last = isolux_world_render(w, isolux_rect{0, 0, 32, 32}, 100, rgba.data(), rgba.size(), nullptr, 0);
    if (last != ISOLUX_OK && last != ISOLUX_ERROR_TOO_MUCH_WORK) __builtin_trap();
    isolux_world_free(w);
    return 0;
}
