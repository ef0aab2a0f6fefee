// Shared by the editor's tests.
#pragma once
#include <filesystem>

#include "editor/editor.hpp"

namespace isolux::test {

// A 10x10 document with three lights, its config in `config`.
inline app::Editor three_light_editor(const std::filesystem::path& config) {
    Scene s;
    s.width = s.height = 10;
    s.lights = {Light{100.5, 100.5}, Light{300.5, 120.5}, Light{600.5, 400.5}};
    return app::make_editor(s, config);
}

}  // namespace isolux::test
