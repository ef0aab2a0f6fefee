// The colour each estimated solid's model is outlined in, on check-tileset's
// contact sheet and in the editor's tileset inspector alike.
#pragma once
#include <array>
#include <cstdint>

#include "isolux/tileset.hpp"

namespace isolux::app {

struct ModelColour {
    std::array<std::uint8_t, 4> rgba;
    const char* name;  // as the inspector and the docs say it
};

// Revolution keeps the yellow the solid's outline always had.
inline ModelColour model_colour(ObjectModel m) {
    switch (m) {
        case ObjectModel::revolution: return {{255, 220, 0, 255}, "yellow"};
        case ObjectModel::prism: return {{255, 80, 255, 255}, "magenta"};
        case ObjectModel::mound: return {{80, 255, 120, 255}, "green"};
    }
    return {{255, 220, 0, 255}, "yellow"};
}

}  // namespace isolux::app
