// The editor's overlays drawn over the view, built on the CPU from core's
// products: the obstacle map (white, as the paper's Figure 6), opacity maps
// (green where a light adds them, red where it subtracts them) and the Δy
// bands Algorithm 1 reads on each sprite (blue, the chosen run cyan), and
// where the 2.5D model and the 3D reference disagree (magenta, cyan).
#pragma once
#include "editor/editor.hpp"

namespace isolux::app {

struct OverlayImage {
    Image image;  // premultiplied RGBA over `rect`
    Rect rect;
};

// Composes the enabled overlays over `region` (world pixels), each at its
// own opacity. Empty when none is enabled.
// `truth` (the 3D reference over the view) feeds the 2.5D-against-3D
// difference overlay when that is on.
OverlayImage build_overlays(const World& world, const FrameState& frame, const Scene& scene, const Overlays& o,
                            Rect region, const LightTexture* truth = nullptr);

}  // namespace isolux::app
