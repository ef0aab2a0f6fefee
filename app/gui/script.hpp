// Scripted input for tests and demos: one command a frame, fed to ImGui's IO
// as a user's mouse and keys would be, or to the editor's actions.
//   wait N | click X Y | rclick X Y | drag X0 Y0 X1 Y1 | key [ctrl+]NAME
//   (a letter, delete, home, enter, tab) | type TEXT (characters into the focused field) |
//   window-shot PATH (the whole window, panels included, as PNG) |
//   inspect SPRITE (the tileset inspector on it) | footprint SPRITE JSON (as the manifest
//   spells it, no spaces) | save-footprints |
//   param NAME VALUE (a slider moved: one undo step) | save-preset PATH |
//   save-scene PATH | load-scene PATH | load-preset PATH | quit |
//   overlay NAME on|off (obstacles, opacity_maps, delta_y_bands, light_areas, normals,
//   raw_light, split_view, split_with_3d, truth_light, truth_difference, heatmap,
//   inspector_normals: the tileset inspector's normal map) | sweep NAME=V1,V2... [...] (the Accuracy
//   panel's sweep) | sweep-resolution (its Occluder resolution button, then the sweep) | wait-sweep | apply-point K | save-sweep PATH (its CSV) |
//   tool NAME (lights, floor, rectangle, fill, place, remove, eraser, eyedropper) |
//   brush floor|overlay SPRITE | brush tag TAG | view X Y ZOOM (the camera) |
//   click-tile COL ROW | drag-tiles C0 R0 C1 R1 (a stroke from tile to tile) |
//   new | fit | open-dropped PATH (as if dropped on the window) |
//   check-glyphs TEXT (exit 3 unless the font has each) | dump-panels PATH (every
//   window's rectangle, JSON lines) | export-final PATH | select I[,J...] |
//   character on|off [X Y] | show accuracy|inspector|help|stats | export-tiled PATH.tmx |
//   long-work undo|trace|cancel (how the script answers the "Long work" prompt: undo the
//   change, the default; trace it, the script waiting until it is done; or trace it and
//   press Cancel once it is under way) | move-lights N (for N frames every light moves a
//   pixel, right then left; the next command waits) | save-stats PATH (each stage's mean
//   time over the frames the Stats panel keeps, JSON: cpu_ms, gpu_ms, tracer, frames) |
//   pan DX DY N (for N frames the view moves DX, DY world pixels, as a held pan; the next command waits)
// Coordinates are window pixels; '#' starts a comment.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace isolux::app {

struct ScriptStep {
    std::string op;
    std::vector<std::string> args;
    int line = 0;
};

struct Script {
    std::vector<ScriptStep> steps;
    std::size_t next = 0;
    int wait = 0;        // frames left to wait
    int release = -1;    // mouse button to release next frame
    int key_up = -1;     // key to release next frame
    std::vector<std::pair<double, double>> drag_path;  // pending drag positions
    bool has_mouse = false;  // the scripted pointer stays where the last command put it
    float mouse_x = 0, mouse_y = 0;
    bool quit = false;
    bool waiting_sweep = false;  // wait-sweep: hold the script until the sweep ends
    std::string window_shot;     // window-shot: written once this frame is drawn
    int resize_w = 0, resize_h = 0;  // resize W H: the window takes that size next frame
    // move-lights N: for N frames every light moves a pixel (right, then
    // left), as a game's lights do; the next command waits for the last.
    int move_lights = 0;
    // pan DX DY N: for N frames the view moves (DX, DY) world pixels; the next command waits.
    double pan_dx = 0, pan_dy = 0;
    int pan_frames = 0;
};

// Parses a script file; throws Error naming the file and line.
Script load_script(const std::filesystem::path& path);

struct App;
// Runs the script's command for this frame (or waits), feeding ImGui's IO or
// calling the editor's actions as a user would.
void run_script_step(App& app);

}  // namespace isolux::app
