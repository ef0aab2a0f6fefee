// The tileset inspector: a sprite with its footprint, the run Algorithm 1
// chose, the Δy lines and the anchor, and the footprint's fields to edit.
#pragma once

namespace isolux::app {

struct App;

struct InspectorState {
    bool open = false;
    int sprite = -1;
    float zoom = 2;
    bool lines = true;  // draw the Δy lines
    bool normals = false;  // the sprite's normal map in place of its colours (sprite shading's source)
};

void inspector_panel(App& app);

}  // namespace isolux::app
