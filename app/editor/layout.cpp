#include "editor/layout.hpp"

#include <algorithm>

namespace isolux::app {

PanelLayout panel_layout(int w, int h, int top, int bottom) {
    constexpr int gap = 10;
    PanelLayout out;
    // Two columns at the edges, as wide as the window allows while leaving
    // the map at least half of it.
    const int col = std::clamp(w / 4, 200, 340);
    const int y0 = top + gap, avail = std::max(240, h - top - bottom - 2 * gap);
    // One table: each column's panels top to bottom, with their share of the
    // height and its bounds; share 0 takes what the others leave.
    struct Slot {
        const char* name;
        double share;
        int min, max;
    };
    // Parameters takes what is left, at least about half the column: its
    // every control within one scroll at 1280x720 (tests/app/gui/app_test.sh).
    static const Slot left[] = {{"Map", 0.20, 130, 210}, {"Parameters", 0, 0, 0}, {"Overlays", 0.25, 140, 250}};
    static const Slot right[] = {{"Tools", 0.42, 200, 340}, {"Lights", 0.30, 150, 300}, {"Stats", 0, 0, 0}};
    auto stack = [&](const Slot (&slots)[3], int x) {
        int fixed = 0;
        for (const Slot& s : slots)
            if (s.share > 0) fixed += std::clamp(int(avail * s.share), s.min, s.max) + gap;
        int y = y0;
        for (const Slot& s : slots) {
            const int ph = s.share > 0 ? std::clamp(int(avail * s.share), s.min, s.max) : std::max(60, avail - fixed);
            out.panels.push_back({s.name, {x, y, col, ph}});
            y += ph + gap;
        }
    };
    stack(left, gap);
    stack(right, w - gap - col);
    out.free = {col + 2 * gap, top, std::max(1, w - 2 * col - 4 * gap), std::max(1, h - top - bottom)};
    const int fw = std::min(560, out.free.w), fh = std::min(640, avail);
    out.floating = {out.free.x + (out.free.w - fw) / 2, y0, fw, fh};
    return out;
}

Rect panel_rect(const PanelLayout& layout, const std::string& name) {
    for (const PanelRect& p : layout.panels)
        if (p.name == name) return p.rect;
    return {};
}

}  // namespace isolux::app
