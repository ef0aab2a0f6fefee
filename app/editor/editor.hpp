// The editor's document and actions, with no GL and no ImGui: panels and
// scripted input call these; tests call them directly.
#pragma once
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "editor/config.hpp"
#include "isolux/endless.hpp"
#include "isolux/frame.hpp"
#include "isolux/scene.hpp"
#include "isolux/world.hpp"

namespace isolux::app {

struct Overlays {
    bool obstacles = false;
    float obstacles_opacity = 0.85f;
    bool opacity_maps = false;  // added (green) and subtracted (red) per light
    float opacity_maps_opacity = 0.5f;
    bool delta_y_bands = false;  // the rows Algorithm 1 reads on each sprite
    float delta_y_opacity = 0.4f;
    bool light_areas = true;     // the a x b rectangles
    float light_areas_opacity = 0.6f;
    bool raw_light = false;      // the light texture instead of the final frame
    bool split_view = false;     // paper lighting left, flat (Figure 10) or 3D lighting right
    bool split_with_3d = false;  // the right side: the 3D reference instead of flat lighting
    float split = 0.5f;
    bool truth_light = false;       // the 3D reference's light texture instead of the final frame
    bool normals = false;        // with sprite_shading: each sprite pixel's normal as a normal map's RGB
    float normals_opacity = 1.0f;
    bool truth_difference = false;  // magenta: lit in 2.5D, dark in 3D; cyan: the reverse
    float truth_difference_opacity = 0.8f;
    friend bool operator==(const Overlays&, const Overlays&) = default;
};

// A character walking the map with a light (WASD), showing the l-frames shift.
struct Character {
    bool enabled = false;
    bool follow = true;
    double x = 0, y = 0;
    double speed = 240;  // world pixels per second
    Light light;
};

// The level editor's tools (one table: the tool bar, the hotkeys, the Help
// window and the script's `tool` command all read it).
enum class Tool { lights, floor, floor_rect, floor_fill, overlay_add, overlay_remove, eraser, eyedropper };
struct ToolInfo {
    Tool tool;
    const char* name;   // the script's name
    const char* label;  // the tool bar's
    char key;           // its hotkey (a letter)
    const char* help;
};
const std::vector<ToolInfo>& tool_table();
const ToolInfo& tool_info(Tool t);

// What the terrain tools paint with.
struct Brush {
    Tool tool = Tool::lights;
    int floor = -1;           // a floor sprite
    int overlay = -1;         // an overlay sprite, used when overlay_tag is empty
    std::string overlay_tag;  // not empty: any overlay with this tag, picked per tile
};

// A mouse stroke of a terrain tool: one undo step however many tiles it paints.
struct Stroke {
    bool active = false;
    Scene before;
    int col0 = -1, row0 = -1, col1 = -1, row1 = -1;  // the rectangle tool's corners
};

// Where the editor looks: not part of the document (panning is not an edit),
// written into the scene's camera only when the scene is saved.
struct View {
    double x = 0, y = 0;        // top-left, world pixels
    int width = 0, height = 0;  // the scene camera's size, kept for saving and --screenshot (0: the whole map)
    double zoom = 1;            // window pixels per world pixel
};

inline constexpr double min_zoom = 1.0 / 16, max_zoom = 16;

// Where the editor stands in an endless world (editor_endless.cpp). The
// document stays in the frame of the window it edits: its lights are the
// window's pixels and its edits the window's tiles (scene.width and height
// are the window's), so every tool works as on a finite map. When the view
// needs chunks the window lacks, a new window is made and the document, its
// history, the view and the character move into its frame by whole pixels
// and tiles; files hold the world's own pixels and tiles.
struct EndlessPlace {
    bool on = false;
    ChunkRange chunks;                        // the window's tiles, in world tiles
    std::int64_t origin_x = 0, origin_y = 0;  // the world pixel of the window's pixel (0, 0)
    std::vector<TileEdit> far_edits;          // world tiles too far from the window for its int tiles
    WorldRect last_view;                      // the last view followed, world pixels
    std::uint64_t windows_built = 0;
};
// Views whose window would pass this many tiles are refused (zoom in): a
// window is made whole when the view leaves it, in time that grows with it.
inline constexpr long max_endless_window_tiles = 288L * 288;

// One step of the undo or redo history: the document as it was, and about
// how many bytes it holds (scene_bytes).
struct HistoryStep {
    Scene scene;
    std::size_t bytes = 0;
};

struct Editor {
    // The document: what is saved, undone and autosaved. The one source of
    // truth: panels read and edit it (through commit_edit), never a copy.
    // Its camera stays empty while editing: `view` is where the editor looks.
    Scene scene;
    World world;
    Scene world_source;  // the scene the world was built from (seed, size, layout, tileset)
    FrameState frame;  // core's caches for this view
    long frame_number = 0;

    View view;
    int selected = -1;                      // the light the Lights panel edits, or -1
    std::vector<int> selection;             // every selected light, ascending (holds `selected`)
    std::vector<Light> clipboard;           // copied lights
    std::vector<HistoryStep> undo_stack, redo_stack;
    bool dirty = false;                     // changes since the last save or load
    std::filesystem::path scene_path;       // where the document was last saved or loaded

    std::string status;  // the last message, shown in the status bar
    bool status_error = false;

    Overlays overlays;
    Character character;
    EndlessPlace endless;  // an endless world's window (on: the document is endless)

    bool fit_pending = true;  // fit the view to the map next frame (the app knows the free area)
    Brush brush;
    Stroke stroke;
    std::uint32_t strokes = 0;  // strokes so far: seeds "any sprite with tag" picks

    bool footprints_unsaved = false;  // the inspector changed a footprint the manifest does not have yet

    std::filesystem::path config;  // per-user config folder
    Settings settings;
    double autosave_due = -1;  // seconds (editor clock) when an autosave is due; -1: none
    // The window this editor is: its process id (make_editor). Its autosave
    // is config/autosave-WINDOW.json, so two windows never share one.
    long window = 0;
};

inline constexpr double autosave_delay = 2.0;  // seconds after a change
// The undo history keeps at most max_undo steps and, past its newest, at
// most max_undo_bytes of documents: each step holds a whole document, and a
// large painted level's edits are megabytes each (the oldest go first).
inline constexpr std::size_t max_undo = 256;
inline constexpr std::size_t max_undo_bytes = std::size_t(256) << 20;

// About the bytes a document holds: its fields, lights and edits.
std::size_t scene_bytes(const Scene& s);

// A new editor on `scene`; builds its world. Throws Error when even the
// default tileset cannot be loaded.
Editor make_editor(const Scene& scene, const std::filesystem::path& config);

// Messages: every action reports here instead of throwing.
void set_status(Editor& e, std::string text, bool error = false);

// A scene's camera becomes the view (a loaded or new scene's): the document
// keeps none while editing.
void take_camera(Editor& e);

// A new world: the frame's caches start over, its options stay.
void fresh_frame(Editor& e);

// The view back at the map's origin, zoom 1 (View › Reset view, Home).
void reset_view(Editor& e);

// What the Map panel shows: read from the document every frame.
struct MapFields {
    std::string seed;
    int width = 0, height = 0;
    bool endless = false;  // no edge: width and height unused
    Layout layout = Layout::diamond;
    std::string tileset;
    friend bool operator==(const MapFields&, const MapFields&) = default;
};
MapFields map_fields(const Editor& e);

// The document as a file holds it: the scene with the view as its camera.
Scene scene_to_save(const Editor& e);

// Records the document before an edit (one undo step) and marks it dirty.
// `before` is the document as it was; for slider drags the panel keeps it
// from the drag's start and commits once at the end.
void commit_edit(Editor& e, const Scene& before, double now);

// Rebuilds the world when the scene's seed, size, layout or tileset differ
// from what it was built from. On error the previous world stays, the scene's
// world fields are restored and the status says why. Returns false on error.
bool sync_world(Editor& e);

// Edits, each one undo step.
void place_light(Editor& e, double x, double y, double now);
void remove_light(Editor& e, int index, double now);
void move_light(Editor& e, int index, double x, double y);  // no undo step: call commit_edit at drag end
void set_params(Editor& e, const Params& p, double now);   // validated; bad values refused with a message
// Changing seed, size or layout. A scene's edits stay (kept_edits) or are
// cleared; edits beyond a smaller map stay in the file and are reported.
void regenerate(Editor& e, const std::string& seed, int width, int height, Layout layout, double now,
                bool keep_edits = true);
// The Map panel's fields applied: finite, or endless (the document moves
// into the world's frame, around the view).
void regenerate(Editor& e, const MapFields& m, double now, bool keep_edits = true);
// How many of the scene's edits lie outside its map.
int edits_outside(const Scene& s);

// Terrain editing: a stroke starts on a tile, continues over others and ends
// as one undo step. The floor brush, overlay place and remove, the eraser
// (clears a tile's overlays) and the eyedropper act on each tile the stroke
// enters; the rectangle fills its corners' rectangle at the end; the bucket
// fills the connected tiles of the first tile's floor.
void begin_stroke(Editor& e, int col, int row);
void continue_stroke(Editor& e, int col, int row);
void end_stroke(Editor& e, double now);
// What the brush would do on tile (col, row), for the hover tooltip.
std::string brush_preview(const Editor& e, int col, int row);
// Sprite names for messages.
std::string sprite_name(const Editor& e, int sprite);
bool undo(Editor& e, double now);
bool redo(Editor& e, double now);

// Files. Errors go to the status line; the document is never lost.
bool save_scene_to(Editor& e, const std::filesystem::path& path);
bool load_scene_from(Editor& e, const std::filesystem::path& path, double now);
bool export_preset(Editor& e, const std::filesystem::path& path);
bool import_preset(Editor& e, const std::filesystem::path& path, double now);
bool load_tileset_from(Editor& e, const std::filesystem::path& manifest, double now);
// Opens a Recent entry as the kind it was saved or opened as.
bool open_recent(Editor& e, const RecentFile& file, double now);

// Autosave: writes the document to this window's own file,
// config/autosave-WINDOW.json, when due. Returns true when it wrote.
bool autosave_tick(Editor& e, double now);
std::filesystem::path autosave_path(const Editor& e);
// Removes this window's autosave (a clean exit with nothing unsaved).
void discard_autosave(Editor& e);

// Recovery: the newest autosave of a window that no longer runs (its
// process is gone: a crash, or a close that kept unsaved work), or the
// single autosave.json of older versions; never a live window's. Empty when
// there is none.
std::filesystem::path recovery_path(const Editor& e);
bool has_recovery(const Editor& e);
// Loads it as unsaved work, autosaves it as this window's own, then removes
// the dead window's file.
bool recover_autosave(Editor& e, double now);
// The user discarded it: removes the dead window's file.
void discard_recovery(Editor& e);

// The tileset inspector's edits: a sprite's footprint, applied to the world
// at once (the manifest is its own file, not part of the scene's undo), and
// saved into the manifest on request, keeping its other fields.
void set_sprite_footprint(Editor& e, int sprite, const FootprintSpec& spec);
bool save_footprints(Editor& e);
std::filesystem::path tileset_manifest(const Editor& e);

// Endless worlds (editor_endless.cpp). `world_scene` in the world's frame
// (lights in world pixels, edits in world tiles) becomes the document, in
// the frame of a window around `view` (world pixels). Throws Error naming
// `source`; the document is unchanged then.
void open_endless(Editor& e, const Scene& world_scene, WorldRect view, std::string_view source);
// A document scene (the document or one of its history) in the world's frame.
Scene endless_world_scene(const Editor& e, const Scene& s);
// A rectangle of the window's pixels in the world's own (64-bit) pixels.
WorldRect endless_world_rect(const Editor& e, Rect window_rect);
// Keeps the window around `view` (window pixels): when the view needs chunks
// the window lacks, a window around it is made and everything moves into its
// frame (moved). A view too large for a window (over
// max_endless_window_tiles) or too far out is refused with a status message,
// and the window stays.
enum class Follow { kept, moved, refused };
Follow follow_view(Editor& e, Rect view);
// The document's endless scene rebuilt around the last view (its seed,
// layout or tileset changed). False, with a status message, on error.
bool sync_endless_world(Editor& e);
// Where an endless scene opens: its camera, or 1600x900 pixels at the origin.
WorldRect default_endless_view(const Scene& world_scene);

// What the panels show for the document's pixels and tiles: the world's
// own (an endless world's window origin added; zero on a finite map).
struct WorldOffset {
    double x = 0, y = 0;
    std::int64_t col = 0, row = 0;
};
WorldOffset world_offset(const Editor& e);

// The overview of an endless world (the minimap): the chunks within
// `radius` chunks of the one under the view's centre, row by row, each with
// whether the window holds it and the hand edits and lights in it.
struct OverviewChunk {
    std::int64_t cx = 0, cy = 0;  // chunk coordinates: its first tile is (cx, cy) * chunk_tiles
    bool in_window = false;
    int edits = 0, lights = 0;
};
struct Overview {
    std::int64_t col = 0, row = 0;     // the tile under the view's centre
    std::int64_t cx = 0, cy = 0;       // its chunk
    std::vector<OverviewChunk> chunks;  // (2 radius + 1)^2, row-major from (cx - radius, cy - radius)
};
Overview endless_overview(const Editor& e, int radius);

// Walks the character by (dx, dy) world pixels: it stays on the map's tiles
// and does not step onto the obstacle map, sliding along an obstacle when
// only one axis is blocked. Returns whether it moved.
bool walk_character(Editor& e, double dx, double dy);

// The scene as rendered: the document plus the character's light.
Scene render_scene(const Editor& e);

// The light under world pixel (x, y) (within `radius` pixels), or -1.
int light_at(const Editor& e, double x, double y, double radius);

// Selecting lights: one (replacing the selection, or toggled into it with
// `add`), every light in a world rectangle (box select), or none (-1).
void select_light(Editor& e, int index, bool add = false);
void select_lights_in(Editor& e, Rect world, bool add);
bool is_selected(const Editor& e, int index);
// The selection moved by (dx, dy) world pixels, locked lights staying; no
// undo step (the drag commits once at its end).
void move_selection(Editor& e, double dx, double dy);
// Each one undo step; locked lights are neither deleted nor moved.
void delete_selection(Editor& e, double now);
void duplicate_selection(Editor& e, double now);  // copies 16 px right and down, selected
void copy_selection(Editor& e);
void paste_lights(Editor& e, double x, double y, double now);  // the copied group centred on (x, y)
// "light 3" or its name.
std::string light_label(const Scene& s, int index);

// File › New: the default scene, untitled, after the caller asked about unsaved changes.
void new_scene(Editor& e, double now);
// "name.json * - isolux": the file (or "untitled") and an unsaved mark.
std::string window_title(const Editor& e);
// What a JSON file is, from its fields: a scene (seed, lights, edits, ...),
// a tileset manifest (sprites) or a preset (parameters only). Throws Error
// naming the file when it is none of them or unreadable. A file dropped on
// the window opens as what this says (open_recent).
FileKind detect_file_kind(const std::filesystem::path& path);

// The zoom and position that show `world` whole and centred in the window
// rectangle `area` (window pixels), zoom within [min_zoom, max_zoom].
void fit_view(View& v, Rect world, Rect area);
// Set by whatever replaces the map (open, new, regenerate): the app fits the
// view to the map in its next frame, when it knows the free area.
inline bool fit_requested(const Editor& e) { return e.fit_pending; }

}  // namespace isolux::app
