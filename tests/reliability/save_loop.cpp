// Saves two large scenes (A: 4000 lights, B: 6000) to one path in turn,
// forever or once: the victim kill_save.py kills mid-save.
// Usage: isolux_save_loop PATH [once]
#include <cstdio>
#include <string>

#include "isolux/isolux.hpp"

int main(int argc, char** argv) {
    if (argc < 2) return 2;
    isolux::Scene a, b;
    for (int i = 0; i < 4000; ++i) a.lights.push_back(isolux::Light{double(i), double(i % 977)});
    for (int i = 0; i < 6000; ++i) b.lights.push_back(isolux::Light{double(i) + 0.5, double(i % 613)});
    const bool once = argc > 2 && std::string(argv[2]) == "once";
    for (long n = 0;; ++n) {
        isolux::save_scene(argv[1], n % 2 ? b : a);
        if (once) return 0;
        if (n == 0) std::puts("saving"), std::fflush(stdout);
    }
}
