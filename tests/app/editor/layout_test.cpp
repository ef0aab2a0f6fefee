// The panel layout (layout.hpp): docked panels inside the window, apart.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <unistd.h>

#include "editor/layout.hpp"
#include "isolux/image.hpp"

using namespace isolux;
using namespace isolux::app;
namespace fs = std::filesystem;

namespace {
bool inside(Rect outer, Rect inner) { return intersect(outer, inner) == inner; }
}  // namespace

TEST(Layout, everyDockedPanelLiesInsideTheWindowWithoutOverlap) {
    for (auto [w, h] : {std::pair{1280, 720}, {1366, 768}, {1600, 900}, {1920, 1080}, {2560, 1440}}) {
        const PanelLayout l = panel_layout(w, h, 21, 26);
        ASSERT_EQ(l.panels.size(), 6u);
        const Rect screen{0, 21, w, h - 21 - 26};
        for (const PanelRect& p : l.panels) EXPECT_TRUE(inside(screen, p.rect)) << p.name << " at " << w << "x" << h;
        for (std::size_t i = 0; i < l.panels.size(); ++i)
            for (std::size_t j = i + 1; j < l.panels.size(); ++j)
                EXPECT_TRUE(intersect(l.panels[i].rect, l.panels[j].rect).empty())
                    << l.panels[i].name << " overlaps " << l.panels[j].name << " at " << w << "x" << h;
        EXPECT_TRUE(inside(screen, l.floating)) << w << "x" << h;
        // The map keeps the middle, at least 40 % of the width.
        EXPECT_GE(l.free.w, w * 2 / 5) << w;
        for (const PanelRect& p : l.panels) EXPECT_TRUE(intersect(p.rect, l.free).empty()) << p.name;
    }
}
