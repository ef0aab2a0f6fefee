// The editor's overlays drawn over the view, built on the CPU from core's
// products: the obstacle map (white, as the paper's Figure 6), opacity maps
// (green where a light adds them, red where it subtracts them) and the Δy
// bands Algorithm 1 reads on each sprite (blue, the chosen run cyan).
#pragma once
#include "gui/editor.hpp"

namespace isolux::app {

struct OverlayImage {
    Image image;  // premultiplied RGBA over `rect`
    Rect rect;
};

// Composes the enabled overlays over `region` (world pixels), each at its
// own opacity. Empty when none is enabled.
OverlayImage build_overlays(const World& world, const FrameState& frame, const Scene& scene, const Overlays& o,
                            Rect region);

}  // namespace isolux::app
