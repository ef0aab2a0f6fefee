// Uses the installed library the way a game would, through its one umbrella
// header: a seeded map on a tileset of its own, and one traced light.
#include <isolux/isolux.hpp>

#include <cstdio>

int main() {
    isolux::Tileset t;
    isolux::Sprite floor;
    floor.name = "floor";
    floor.kind = isolux::SpriteKind::floor;
    floor.image = isolux::Image(16, 8);
    for (std::size_t i = 3; i < floor.image.rgba.size(); i += 4) floor.image.rgba[i] = 255;
    t.tile_width = 16;
    t.tile_height = 8;
    t.sprites.push_back(floor);
    isolux::Scene s;
    s.width = s.height = 4;
    s.lights = {isolux::Light{30, 20}};
    isolux::World w = isolux::make_world(t, s);
    isolux::FrameState st;
    isolux::FrameReport r = isolux::render_frame(st, w, s, isolux::Camera{}, 0);
    std::printf("consumer: %dx%d frame, %d light traced\n", st.final.width, st.final.height, r.lights_traced);
    return r.lights_traced == 1 ? 0 : 1;
}
