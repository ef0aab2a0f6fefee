// The editor's lights: place, move, remove, select, copy and paste (editor.hpp).
#include "editor/editor.hpp"

#include <algorithm>
#include <cmath>

#include "isolux/edits.hpp"
#include "isolux/error.hpp"

namespace isolux::app {

void place_light(Editor& e, double x, double y, double now) {
    Scene before = e.scene;
    Light l;
    l.x = std::floor(x) + 0.5;
    l.y = std::floor(y) + 0.5;
    e.scene.lights.push_back(l);
    select_light(e, int(e.scene.lights.size()) - 1);
    commit_edit(e, before, now);
    if (e.frame.obstacles.get(int(std::floor(x)), int(std::floor(y))))
        set_status(e, "light " + std::to_string(e.selected + 1) +
                          " sits on an obstacle pixel: it lights nothing (Algorithm 2 tests the centre first)",
                    true);
    else
        set_status(e, "placed light " + std::to_string(e.selected + 1));
}

void remove_light(Editor& e, int index, double now) {
    if (index < 0 || index >= int(e.scene.lights.size())) return;
    if (e.scene.lights[std::size_t(index)].locked) {
        set_status(e, light_label(e.scene, index) + " is locked: unlock it in the Lights panel to remove it", true);
        return;
    }
    Scene before = e.scene;
    const std::string label = light_label(e.scene, index);
    e.scene.lights.erase(e.scene.lights.begin() + index);
    std::vector<int> kept;
    for (int i : e.selection)
        if (i != index) kept.push_back(i > index ? i - 1 : i);
    e.selection = kept;
    if (e.selected == index) e.selected = -1;
    else if (e.selected > index) --e.selected;
    commit_edit(e, before, now);
    set_status(e, "removed " + label);
}

void move_light(Editor& e, int index, double x, double y) {
    if (index < 0 || index >= int(e.scene.lights.size()) || e.scene.lights[std::size_t(index)].locked) return;
    e.scene.lights[index].x = std::floor(x) + 0.5;
    e.scene.lights[index].y = std::floor(y) + 0.5;
}

int light_at(const Editor& e, double x, double y, double radius) {
    int best = -1;
    double best_d = radius;
    for (int i = 0; i < int(e.scene.lights.size()); ++i) {
        const double d = std::hypot(e.scene.lights[i].x - x, e.scene.lights[i].y - y);
        if (d <= best_d) {
            best_d = d;
            best = i;
        }
    }
    return best;
}

std::string light_label(const Scene& s, int i) {
    if (i < 0 || i >= int(s.lights.size())) return "no light";
    const Light& l = s.lights[std::size_t(i)];
    return l.name.empty() ? "light " + std::to_string(i + 1) : l.name;
}

bool is_selected(const Editor& e, int i) { return std::binary_search(e.selection.begin(), e.selection.end(), i); }

void select_light(Editor& e, int i, bool add) {
    if (i < 0 || i >= int(e.scene.lights.size())) {
        if (!add) e.selection.clear(), e.selected = -1;
        return;
    }
    if (!add) {
        e.selection = {i};
        e.selected = i;
        return;
    }
    auto it = std::lower_bound(e.selection.begin(), e.selection.end(), i);
    if (it != e.selection.end() && *it == i) {
        e.selection.erase(it);
        if (e.selected == i) e.selected = e.selection.empty() ? -1 : e.selection.back();
    } else {
        e.selection.insert(it, i);
        e.selected = i;
    }
}

void select_lights_in(Editor& e, Rect r, bool add) {
    if (!add) e.selection.clear();
    for (int i = 0; i < int(e.scene.lights.size()); ++i) {
        const Light& l = e.scene.lights[std::size_t(i)];
        if (l.x >= r.x && l.y >= r.y && l.x < r.x + r.w && l.y < r.y + r.h && !is_selected(e, i)) {
            e.selection.insert(std::lower_bound(e.selection.begin(), e.selection.end(), i), i);
        }
    }
    e.selected = e.selection.empty() ? -1 : e.selection.back();
}

void move_selection(Editor& e, double dx, double dy) {
    for (int i : e.selection) {
        Light& l = e.scene.lights[std::size_t(i)];
        if (l.locked) continue;
        l.x += dx;
        l.y += dy;
    }
}

void delete_selection(Editor& e, double now) {
    Scene before = e.scene;
    int removed = 0, locked = 0;
    for (auto it = e.selection.rbegin(); it != e.selection.rend(); ++it) {
        if (e.scene.lights[std::size_t(*it)].locked) {
            ++locked;
            continue;
        }
        e.scene.lights.erase(e.scene.lights.begin() + *it);
        ++removed;
    }
    e.selection.clear();
    e.selected = -1;
    commit_edit(e, before, now);
    set_status(e, "removed " + std::to_string(removed) + " light" + (removed == 1 ? "" : "s") +
                      (locked ? " (" + std::to_string(locked) + " locked kept)" : ""),
               locked > 0);
}

void copy_selection(Editor& e) {
    e.clipboard.clear();
    for (int i : e.selection) e.clipboard.push_back(e.scene.lights[std::size_t(i)]);
    set_status(e, "copied " + std::to_string(e.clipboard.size()) + " light" + (e.clipboard.size() == 1 ? "" : "s"));
}

namespace {
// Adds `lights` to the scene, selected, as one undo step.
void add_lights(Editor& e, const std::vector<Light>& lights, double dx, double dy, double now, const char* what) {
    if (lights.empty()) return;
    Scene before = e.scene;
    e.selection.clear();
    for (Light l : lights) {
        l.x = std::floor(l.x + dx) + 0.5;
        l.y = std::floor(l.y + dy) + 0.5;
        l.locked = false;
        e.scene.lights.push_back(l);
        e.selection.push_back(int(e.scene.lights.size()) - 1);
    }
    e.selected = e.selection.back();
    commit_edit(e, before, now);
    set_status(e, std::string(what) + " " + std::to_string(lights.size()) + " light" + (lights.size() == 1 ? "" : "s"));
}
}  // namespace

void duplicate_selection(Editor& e, double now) {
    std::vector<Light> copies;
    for (int i : e.selection) copies.push_back(e.scene.lights[std::size_t(i)]);
    add_lights(e, copies, 16, 16, now, "duplicated");
}

void paste_lights(Editor& e, double x, double y, double now) {
    if (e.clipboard.empty()) return;
    double cx = 0, cy = 0;
    for (const Light& l : e.clipboard) cx += l.x, cy += l.y;
    cx /= double(e.clipboard.size());
    cy /= double(e.clipboard.size());
    add_lights(e, e.clipboard, x - cx, y - cy, now, "pasted");
}

}  // namespace isolux::app
