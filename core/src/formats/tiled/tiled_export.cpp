// Tiled maps (TMX) out of isolux: export_tiled (tiled.hpp), as a list of
// steps, each writing one part of the map.
#include "isolux/tiled.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <functional>
#include <cstdio>
#include <sstream>
#include <tuple>

#include "isolux/error.hpp"
#include "isolux/file_io.hpp"
#include "isolux/isolux.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/params.hpp"
#include "isolux/truth.hpp"
#include "formats/atomic_write.hpp"
#include "formats/tiled/tiled_grid.hpp"

namespace fs = std::filesystem;

namespace isolux {

namespace {

// <?xml version="1.0" encoding="UTF-8"?>, as Tiled writes it.
void add_declaration(pugi::xml_document& doc) {
    auto decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
}

void add_property(pugi::xml_node props, const std::string& name, const char* type, const std::string& value) {
    pugi::xml_node p = props.append_child("property");
    p.append_attribute("name") = name.c_str();
    if (type) p.append_attribute("type") = type;
    p.append_attribute("value") = value.c_str();
}

std::string colour_text(const Light& l) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "#ff%02x%02x%02x", l.r, l.g, l.b);
    return buf;
}

// An image-collection tileset of `sprites`, written as a TSX; returns the
// gid of each sprite (0 when not in it).
// A sprite's normal map and height map beside its image: "oak.png" gives
// "oak.normal.png" and "oak.height.png".
std::string beside(const std::string& image_file, const char* kind) {
    return fs::path(image_file).stem().string() + "." + kind + ".png";
}

void write_tsx(const fs::path& path, const std::string& name, const Tileset& ts, const std::vector<int>& sprites,
               const std::vector<std::string>& image_files, const fs::path& image_dir, int offset_x, int offset_y,
               const char* alignment, bool normal_maps) {
    pugi::xml_document doc;
    add_declaration(doc);
    pugi::xml_node t = doc.append_child("tileset");
    t.append_attribute("version") = "1.8";
    t.append_attribute("tiledversion") = "1.8.2";
    t.append_attribute("name") = name.c_str();
    int max_w = 1, max_h = 1;
    for (int s : sprites) {
        max_w = std::max(max_w, ts.sprites[std::size_t(s)].image.width);
        max_h = std::max(max_h, ts.sprites[std::size_t(s)].image.height);
    }
    t.append_attribute("tilewidth") = max_w;
    t.append_attribute("tileheight") = max_h;
    t.append_attribute("tilecount") = int(sprites.size());
    t.append_attribute("columns") = 0;
    if (alignment) t.append_attribute("objectalignment") = alignment;
    pugi::xml_node off = t.append_child("tileoffset");
    off.append_attribute("x") = offset_x;
    off.append_attribute("y") = offset_y;
    pugi::xml_node grid = t.append_child("grid");
    grid.append_attribute("orientation") = "isometric";
    grid.append_attribute("width") = ts.tile_width;
    grid.append_attribute("height") = ts.tile_height;
    for (std::size_t i = 0; i < sprites.size(); ++i) {
        const Sprite& s = ts.sprites[std::size_t(sprites[i])];
        pugi::xml_node tile = t.append_child("tile");
        tile.append_attribute("id") = int(i);
        // What isolux knows of the sprite beyond its pixels, so that an
        // imported map lights as the original (Tiled shows them as custom properties).
        pugi::xml_node props = tile.append_child("properties");
        add_property(props, "isolux_name", nullptr, s.name);
        add_property(props, "isolux_kind", nullptr, s.kind == SpriteKind::floor ? "floor" : "overlay");
        add_property(props, "isolux_anchor_x", "int", std::to_string(s.anchor_x));
        add_property(props, "isolux_anchor_y", "int", std::to_string(s.anchor_y));
        std::string tags;
        for (const std::string& t : s.tags) tags += (tags.empty() ? "" : ",") + t;
        if (!tags.empty()) add_property(props, "isolux_tags", nullptr, tags);
        if (s.opacity_threshold) add_property(props, "isolux_opacity_threshold", "float", number(*s.opacity_threshold));
        const std::string fp = footprint_to_json(s.footprint);
        if (!fp.empty()) add_property(props, "isolux_footprint", nullptr, fp);
        if (normal_maps) {
            const std::string& file = image_files[std::size_t(sprites[i])];
            add_property(props, "normal_map", "file", (image_dir.filename() / beside(file, "normal")).string());
            add_property(props, "isolux_height_map", "file", (image_dir.filename() / beside(file, "height")).string());
        }
        pugi::xml_node img = tile.append_child("image");
        img.append_attribute("width") = s.image.width;
        img.append_attribute("height") = s.image.height;
        img.append_attribute("source") =
            (image_dir.filename() / image_files[std::size_t(sprites[i])]).string().c_str();
    }
    std::ostringstream out;
    doc.save(out, "  ");
    write_file_atomic(path, out.str());
}

// The obstacle map as rectangles: runs of each row, merged down while the
// next row has the same run.
std::vector<Rect> obstacle_rects(const Mask& m) {
    std::vector<Rect> done, open;
    for (int y = 0; y <= m.height; ++y) {
        std::vector<Rect> runs;
        for (int x = 0; y < m.height && x < m.width;) {
            if (!m.bits[std::size_t(y) * m.width + x]) {
                ++x;
                continue;
            }
            int e = x;
            while (e < m.width && m.bits[std::size_t(y) * m.width + e]) ++e;
            runs.push_back({x + m.x0, y + m.y0, e - x, 1});
            x = e;
        }
        std::vector<Rect> next;
        for (Rect r : runs) {
            auto it = std::find_if(open.begin(), open.end(), [&](const Rect& o) { return o.x == r.x && o.w == r.w; });
            if (it != open.end()) {
                Rect grown = *it;
                ++grown.h;
                next.push_back(grown);
                open.erase(it);
            } else {
                next.push_back(r);
            }
        }
        done.insert(done.end(), open.begin(), open.end());
        open = next;
    }
    return done;
}

// The names of one generation of an export's files beside its TMX. A
// re-export writes the generation the existing TMX does not name, replaces
// the TMX last, then removes the old generation: killed at any moment, the
// TMX on disk names files that are whole (the previous export's until the
// rename, the new one's after it). A first export is generation 0.
struct ExportFiles {
    std::string floors_tsx, overlays_tsx, images, light_png, final_png;  // names in the map's folder

    ExportFiles(const std::string& base, int generation) {
        const std::string g = generation == 0 ? "" : ".1";
        floors_tsx = base + "_floors" + g + ".tsx";
        overlays_tsx = base + "_overlays" + g + ".tsx";
        images = base + "_images" + g;
        light_png = base + "_light" + g + ".png";
        final_png = base + "_final" + g + ".png";
    }
    void remove_from(const fs::path& dir) const {
        std::error_code ec;
        for (const std::string* f : {&floors_tsx, &overlays_tsx, &light_png, &final_png}) fs::remove(dir / *f, ec);
        fs::remove_all(dir / images, ec);
    }
};

// The generation the map at `tmx` names (0 or 1), or -1 when there is no map
// there that isolux wrote.
int generation_on_disk(const fs::path& tmx, const std::string& base) {
    std::error_code ec;
    if (!fs::is_regular_file(tmx, ec)) return -1;
    std::string text;
    try {
        text = read_text_file(tmx);
    } catch (const Error&) {
        return -1;
    }
    for (int g : {1, 0})
        if (text.find("\"" + ExportFiles(base, g).overlays_tsx + "\"") != std::string::npos) return g;
    return -1;
}

// The new generation's files, taken back if the export fails before its map
// names them (a full disk, say). `ours`: an isolux map stands there, so
// files under the new generation's names are an interrupted export's
// leftovers that no map names, cleared first. Otherwise a file or folder
// under those names is somebody else's (a user's own `level_floors.tsx`):
// the export is refused by its name rather than replace it.
struct NewFiles {
    fs::path dir;
    ExportFiles files;
    bool done = false;
    NewFiles(fs::path d, ExportFiles f, bool ours, const fs::path& tmx) : dir(std::move(d)), files(std::move(f)) {
        if (ours) files.remove_from(dir);
        for (const std::string* f : {&files.floors_tsx, &files.overlays_tsx, &files.images, &files.light_png, &files.final_png}) {
            check_own_name(dir / *f);
            std::error_code ec;
            if (!ours && fs::exists(fs::symlink_status(dir / *f, ec)))
                throw Error((dir / *f).string() + ": already exists, and no map isolux exported names it at " +
                            tmx.string() + "; an export never replaces a file it did not write (move it away, or "
                            "export under another name)");
        }
        std::error_code ec;
        fs::create_directories(dir / files.images, ec);
        if (ec) throw Error((dir / files.images).string() + ": cannot create (" + ec.message() + ")");
    }
    ~NewFiles() {
        if (!done) files.remove_from(dir);  // every name was free or a leftover: all of it is this export's
    }
};

// The map's Tiled grid over the world's tiles.
Grid grid_of(const Map& map) {
    Grid g;
    g.isometric = map.layout != Layout::staggered;
    g.tw = map.tile_width;
    g.th = map.tile_height;
    g.w = map.width;
    g.h = map.height;
    return g;
}

// The world pixel of Tiled's screen (0, 0), where tile centres agree:
// Tiled's centre of cell (x, y) is its box's bottom-left + (tw/2, -th/2). In
// the paper layout the objects carry every position and the Tiled grid is a
// diamond one over the same pixels: (0, 0).
std::pair<int, int> tiled_origin(const World& world, const Grid& g) {
    const Map& map = world.map;
    if (map.layout == Layout::paper) return {0, 0};
    double bx = 0, by = 0;
    g.cell_bottom_left(0, 0, bx, by);
    int cx = 0, cy = 0;
    tile_center(map.layout, map.tile_width, map.tile_height, 0, 0, cx, cy);
    return {cx + world.placed.shift_x - int(bx + g.tw / 2.0), cy + world.placed.shift_y - int(by - g.th / 2.0)};
}

// The sprites the level uses, in two Tiled tilesets: floors (one offset for
// all, so a cell draws the block where isolux does) and overlays (tile
// objects, top-left aligned); each sprite's gid in them.
struct ExportTilesets {
    std::vector<int> floors, overlays;            // sprite indices, ascending
    std::vector<int> floor_gid, overlay_gid;      // by sprite index; 0 when unused
    int floor_offset_x = 0, floor_offset_y = 0;   // the floors' tileoffset
    int first_floor = 1, first_overlay = 1;
    std::vector<std::string> image_files;          // by sprite index: its PNG's name in the images folder
};

// A sprite's name made into a file name that stays inside the images folder:
// letters, digits, '-', '_' and '.' kept, anything else (a '/', a space) '_',
// no leading dot (no "..", no hidden file), at most 100 characters.
std::string safe_file_stem(const std::string& name) {
    std::string out;
    for (char c : name) {
        const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                          c == '_' || c == '.';
        out += keep ? c : '_';
        if (out.size() == 100) break;
    }
    while (!out.empty() && out.front() == '.') out.erase(out.begin());
    return out.empty() ? "sprite" : out;
}

// One PNG name per sprite used, distinct even where names are the same or
// differ only in case or in characters made safe ("oak", "oak_2", ...), so
// no image (nor normal or height map) is written twice or over another.
std::vector<std::string> image_file_names(const Tileset& ts, const std::vector<int>& floors, const std::vector<int>& overlays) {
    std::vector<std::string> files(ts.sprites.size());
    std::vector<std::string> taken;  // lower-cased
    auto lower = [](std::string t) {
        for (char& c : t) c = char(std::tolower(static_cast<unsigned char>(c)));
        return t;
    };
    for (const std::vector<int>* list : {&floors, &overlays})
        for (int s : *list) {
            const std::string stem = safe_file_stem(ts.sprites[std::size_t(s)].name);
            // A name holds its normal and height maps' names too (--normal-maps):
            // a sprite "oak.normal" never takes the file of "oak"'s normal map.
            auto names = [](const std::string& st) {
                return std::array<std::string, 3>{st + ".png", st + ".normal.png", st + ".height.png"};
            };
            auto clash = [&](const std::string& st) {
                for (const std::string& n : names(st))
                    if (std::find(taken.begin(), taken.end(), lower(n)) != taken.end()) return true;
                return false;
            };
            std::string chosen = stem;
            for (int k = 2; clash(chosen); ++k) chosen = stem + "_" + std::to_string(k);
            for (const std::string& n : names(chosen)) taken.push_back(lower(n));
            files[std::size_t(s)] = chosen + ".png";
        }
    return files;
}

ExportTilesets collect_tilesets(const World& world, const Grid& g, bool floors_as_objects, const fs::path& tmx) {
    const Tileset& ts = world.tileset;
    ExportTilesets e;
    e.floor_gid.assign(ts.sprites.size(), 0);
    e.overlay_gid.assign(ts.sprites.size(), 0);
    for (const SpriteInstance& in : world.placed.instances) {
        if (in.sprite < 0) continue;
        const bool floor = ts.sprites[std::size_t(in.sprite)].kind == SpriteKind::floor && !floors_as_objects;
        std::vector<int>& list = floor ? e.floors : e.overlays;
        if (std::find(list.begin(), list.end(), in.sprite) == list.end()) list.push_back(in.sprite);
    }
    std::sort(e.floors.begin(), e.floors.end());
    std::sort(e.overlays.begin(), e.overlays.end());
    for (std::size_t i = 0; i < e.floors.size(); ++i) {
        const Sprite& s = ts.sprites[std::size_t(e.floors[i])];
        const int ox = g.tw / 2 - s.anchor_x, oy = s.image.height - s.anchor_y - g.th / 2;
        if (i > 0 && (ox != e.floor_offset_x || oy != e.floor_offset_y))
            throw Error(tmx.string() + ": floor sprites \"" + ts.sprites[std::size_t(e.floors[0])].name + "\" and \"" +
                        s.name + "\" are anchored differently: Tiled gives one offset per tileset");
        e.floor_offset_x = ox, e.floor_offset_y = oy;
    }
    e.first_overlay = e.first_floor + int(e.floors.size());
    for (std::size_t i = 0; i < e.floors.size(); ++i) e.floor_gid[std::size_t(e.floors[i])] = e.first_floor + int(i);
    for (std::size_t i = 0; i < e.overlays.size(); ++i) e.overlay_gid[std::size_t(e.overlays[i])] = e.first_overlay + int(i);
    e.image_files = image_file_names(ts, e.floors, e.overlays);
    return e;
}

pugi::xml_node start_map(pugi::xml_document& doc, const Map& map, const Grid& g, bool infinite) {
    add_declaration(doc);
    pugi::xml_node m = doc.append_child("map");
    m.append_attribute("version") = "1.8";
    m.append_attribute("tiledversion") = "1.8.2";
    m.append_attribute("orientation") = g.isometric ? "isometric" : "staggered";
    m.append_attribute("renderorder") = "right-down";
    m.append_attribute("width") = map.width;
    m.append_attribute("height") = map.height;
    m.append_attribute("tilewidth") = g.tw;
    m.append_attribute("tileheight") = g.th;
    m.append_attribute("infinite") = infinite ? 1 : 0;
    if (!g.isometric) {
        m.append_attribute("staggeraxis") = "y";
        m.append_attribute("staggerindex") = "odd";
    }
    return m;
}

// The preset, and what isolux needs to light the map again.
void write_map_properties(pugi::xml_node m, const Scene& scene, Layout layout, std::pair<int, int> origin, Rect frame) {
    pugi::xml_node props = m.append_child("properties");
    // The whole map's picture (World::frame), so a map read back renders the
    // same image as its scene, whatever the edits.
    if (!frame.empty())
        add_property(props, "isolux_frame", nullptr,
                     std::to_string(frame.x) + "," + std::to_string(frame.y) + "," + std::to_string(frame.w) + "," +
                         std::to_string(frame.h));
    add_property(props, "isolux_layout", nullptr, std::string(to_string(layout)));
    add_property(props, "isolux_origin_x", "int", std::to_string(origin.first));
    add_property(props, "isolux_origin_y", "int", std::to_string(origin.second));
    add_property(props, "isolux_seed", nullptr, scene.seed);
    for (const ParamInfo& info : param_table()) {
        const double v = info.get(scene.params);
        const char* type = info.type == ParamType::integer   ? "int"
                           : info.type == ParamType::real    ? "float"
                           : info.type == ParamType::boolean ? "bool"
                                                             : nullptr;
        add_property(props, info.name, type, format_param(info, v));
    }
}

void write_tileset_refs(pugi::xml_node m, const ExportTilesets& e, const ExportFiles& files) {
    if (!e.floors.empty()) {
        pugi::xml_node t = m.append_child("tileset");
        t.append_attribute("firstgid") = e.first_floor;
        t.append_attribute("source") = files.floors_tsx.c_str();
    }
    pugi::xml_node t = m.append_child("tileset");
    t.append_attribute("firstgid") = e.first_overlay;
    t.append_attribute("source") = files.overlays_tsx.c_str();
}

// The gids of cells [col0, col0 + w) x [row0, row0 + h) as CSV, one row a line.
std::string csv_cells(const std::function<int(int, int)>& gid, int col0, int row0, int w, int h) {
    std::string csv = "\n";
    for (int row = row0; row < row0 + h; ++row) {
        for (int col = col0; col < col0 + w; ++col) {
            csv += std::to_string(gid(col, row));
            if (row + 1 < row0 + h || col + 1 < col0 + w) csv += ",";
        }
        csv += "\n";
    }
    return csv;
}

// Floors: tile layers, CSV; each tile's floors from the placed sprites (a
// seeded map holds one a tile; a Tiled map read in may stack several, one
// layer each, marked isolux_kind floor so that they read back as floors).
// With `chunk`, each layer's cells as chunks of that many tiles a side.
void write_floor_layers(pugi::xml_node m, const World& world, const ExportTilesets& e, int& next_id, int chunk) {
    const Map& map = world.map;
    const std::size_t tiles = std::size_t(map.width) * map.height;
    std::vector<std::vector<int>> floors_at(tiles);
    std::size_t layers = 1;
    for (const SpriteInstance& in : world.placed.instances) {
        if (in.sprite < 0 || in.tile < 0 || std::size_t(in.tile) >= tiles) continue;
        if (world.tileset.sprites[std::size_t(in.sprite)].kind != SpriteKind::floor) continue;
        floors_at[std::size_t(in.tile)].push_back(in.sprite);
        layers = std::max(layers, floors_at[std::size_t(in.tile)].size());
    }
    for (std::size_t k = 0; k < layers; ++k) {
        pugi::xml_node layer = m.append_child("layer");
        layer.append_attribute("id") = next_id++;
        layer.append_attribute("name") = k == 0 ? "floors" : ("floors " + std::to_string(k + 1)).c_str();
        layer.append_attribute("width") = map.width;
        layer.append_attribute("height") = map.height;
        if (layers > 1) add_property(layer.append_child("properties"), "isolux_kind", nullptr, "floor");
        auto gid = [&](int col, int row) {
            const std::vector<int>& here = floors_at[std::size_t(row) * map.width + col];
            return k < here.size() ? e.floor_gid[std::size_t(here[k])] : 0;
        };
        pugi::xml_node data = layer.append_child("data");
        data.append_attribute("encoding") = "csv";
        if (chunk <= 0) {
            data.text() = csv_cells(gid, 0, 0, map.width, map.height).c_str();
            continue;
        }
        for (int row = 0; row < map.height; row += chunk)
            for (int col = 0; col < map.width; col += chunk) {
                const int w = std::min(chunk, map.width - col), h = std::min(chunk, map.height - row);
                pugi::xml_node c = data.append_child("chunk");
                c.append_attribute("x") = col;
                c.append_attribute("y") = row;
                c.append_attribute("width") = w;
                c.append_attribute("height") = h;
                c.text() = csv_cells(gid, col, row, w, h).c_str();
            }
    }
}

// Overlays (and, in the paper layout, floors): tile objects in draw order,
// each image's top-left where isolux draws it.
void write_overlay_objects(pugi::xml_node m, const World& world, const Grid& g, const ExportTilesets& e,
                           bool floors_as_objects, std::pair<int, int> origin, int& next_id, int& object_id) {
    pugi::xml_node objects = m.append_child("objectgroup");
    objects.append_attribute("id") = next_id++;
    objects.append_attribute("name") = "overlays";
    objects.append_attribute("draworder") = "index";
    for (std::uint32_t k : draw_order(world.placed, !floors_as_objects)) {
        const SpriteInstance& in = world.placed.instances[k];
        double px = 0, py = 0;
        g.screen_to_object(in.x - origin.first, in.y - origin.second, px, py);
        pugi::xml_node o = objects.append_child("object");
        o.append_attribute("id") = object_id++;
        o.append_attribute("gid") = e.overlay_gid[std::size_t(in.sprite)];
        o.append_attribute("x") = number(px).c_str();
        o.append_attribute("y") = number(py).c_str();
        o.append_attribute("width") = in.w;
        o.append_attribute("height") = in.h;
    }
}

// Lights: points at their ground point, with what isolux needs.
void write_light_objects(pugi::xml_node m, const Scene& scene, const Grid& g, std::pair<int, int> origin, int& next_id,
                         int& object_id) {
    pugi::xml_node lights = m.append_child("objectgroup");
    lights.append_attribute("id") = next_id++;
    lights.append_attribute("name") = "lights";
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        double px = 0, py = 0;
        g.screen_to_object(l.x - origin.first, l.y - origin.second, px, py);
        pugi::xml_node o = lights.append_child("object");
        o.append_attribute("id") = object_id++;
        o.append_attribute("name") = l.name.empty() ? ("light " + std::to_string(i + 1)).c_str() : l.name.c_str();
        o.append_attribute("type") = "light";
        o.append_attribute("x") = number(px).c_str();
        o.append_attribute("y") = number(py).c_str();
        if (l.hidden) o.append_attribute("visible") = 0;
        pugi::xml_node lp = o.append_child("properties");
        add_property(lp, "color", "color", colour_text(l));
        add_property(lp, "a", "int", std::to_string(light_a(l, scene.params)));
        add_property(lp, "b", "int", std::to_string(light_b(l, scene.params)));
        add_property(lp, "intensity", "float", number(l.intensity));
        add_property(lp, "height", "float", number(light_height(l, scene.params)));
        o.append_child("point");
    }
}

// Obstacles: the obstacle map as polygons (screen rectangles, which an
// isometric map's object pixels shear) of type "occluder".
void write_obstacle_objects(pugi::xml_node m, const World& world, const Scene& scene, const Grid& g,
                            std::pair<int, int> origin, int& next_id, int& object_id) {
    pugi::xml_node obstacles = m.append_child("objectgroup");
    obstacles.append_attribute("id") = next_id++;
    obstacles.append_attribute("name") = "obstacles";
    const Mask mask = build_obstacle_map(world.tileset, world.placed, scene.params, world.placed.bounds);
    for (const Rect& r : obstacle_rects(mask)) {
        double px = 0, py = 0;
        g.screen_to_object(r.x - origin.first, r.y - origin.second, px, py);
        pugi::xml_node o = obstacles.append_child("object");
        o.append_attribute("id") = object_id++;
        // What Tiled 1.8 writes for an object's class, and what Tiled
        // importers (Godot 3's, YATI for Godot 4) turn into light occluders.
        o.append_attribute("type") = "occluder";
        o.append_attribute("x") = number(px).c_str();
        o.append_attribute("y") = number(py).c_str();
        const double corners[4][2] = {{0, 0}, {double(r.w), 0}, {double(r.w), double(r.h)}, {0, double(r.h)}};
        std::string points;
        for (const auto& c : corners) {
            double qx = 0, qy = 0;
            g.screen_to_object(r.x - origin.first + c[0], r.y - origin.second + c[1], qx, qy);
            points += (points.empty() ? "" : " ") + number(qx - px) + "," + number(qy - py);
        }
        o.append_child("polygon").append_attribute("points") = points.c_str();
    }
}

// The light texture and the final frame as hidden image layers (PNG beside the map).
void write_image_layers(pugi::xml_node m, const World& world, const Scene& scene, const fs::path& dir,
                        const ExportFiles& files, std::pair<int, int> origin, int& next_id) {
    FrameState st;
    const Rect view = world.placed.bounds;
    render_frame(st, world, scene, Camera{double(view.x), double(view.y), view.w, view.h}, 0);
    const std::tuple<const char*, Image, const std::string*> layers[] = {
        {"light", light_texture_image(st.light), &files.light_png}, {"final", st.final, &files.final_png}};
    for (const auto& [name, image, file_name] : layers) {
        const std::string& file = *file_name;
        save_image(dir / file, image);
        pugi::xml_node il = m.append_child("imagelayer");
        il.append_attribute("id") = next_id++;
        il.append_attribute("name") = name;
        il.append_attribute("visible") = 0;
        il.append_attribute("offsetx") = view.x - origin.first;
        il.append_attribute("offsety") = view.y - origin.second;
        pugi::xml_node img = il.append_child("image");
        img.append_attribute("source") = file.c_str();
        img.append_attribute("width") = image.width;
        img.append_attribute("height") = image.height;
    }
}

}  // namespace

double export_memory(const World& world, const TiledExport& options) {
    const Rect b = world.placed.bounds;
    return double(b.w) * double(b.h) * export_pixel_bytes + (options.images ? render_memory(b) : 0.0);
}

std::pair<int, int> export_tiled(const World& world, const Scene& scene, const fs::path& tmx, const TiledExport& options) {
    if (tmx.extension() != ".tmx") throw Error(tmx.string() + ": the map must be a .tmx file");
    if (const double bytes = export_memory(world, options); bytes > huge_render_bytes && !options.allow_huge) {
        const Rect b = world.placed.bounds;
        throw Error(tmx.string() + ": exporting this " + std::to_string(world.map.width) + "x" +
                    std::to_string(world.map.height) + "-tile map (" + std::to_string(b.w) + "x" + std::to_string(b.h) +
                    " pixels) would hold " + about_gib(bytes) +
                    " at once: export a smaller map or region, or allow it (--allow-huge)");
    }
    // A FIFO, a device or a missing folder is refused before any image or
    // TSX is written, as every other output is (the images' own folder is
    // the export's to make, the map's is not).
    check_output_file(tmx);
    if (options.chunk < 0 || options.chunk > max_tiled_side)
        throw Error(tmx.string() + ": the chunk size " + std::to_string(options.chunk) + " is not in [1, " +
                    std::to_string(max_tiled_side) + "]");
    if (options.chunk > 0 && world.map.layout == Layout::paper)
        throw Error(tmx.string() + ": an infinite map needs tile layers, and the paper layout's floors are tile objects");
    const Tileset& ts = world.tileset;
    const std::string base = tmx.stem().string();
    const fs::path dir = tmx.parent_path().empty() ? fs::path(".") : tmx.parent_path();
    const int old_generation = generation_on_disk(write_target(tmx), base);
    NewFiles written(dir, ExportFiles(base, old_generation == 0 ? 1 : 0), old_generation >= 0, tmx);
    const ExportFiles& files = written.files;
    const fs::path images = dir / files.images;
    const Grid g = grid_of(world.map);
    const bool floors_as_objects = world.map.layout == Layout::paper;
    const std::pair<int, int> origin = tiled_origin(world, g);

    const ExportTilesets e = collect_tilesets(world, g, floors_as_objects, tmx);
    for (const std::vector<int>* list : {&e.floors, &e.overlays})  // an images folder that was there may hold links
        for (int s : *list) {
            check_own_name(images / e.image_files[std::size_t(s)]);
            if (options.normal_maps)
                for (const char* kind : {"normal", "height"}) check_own_name(images / beside(e.image_files[std::size_t(s)], kind));
        }
    // The normal maps first: a sprite refused (shapes it lacks) stops the export before any file.
    std::vector<SpriteNormals> normals(options.normal_maps ? ts.sprites.size() : 0);
    if (options.normal_maps) {
        const SpriteShading from =
            scene.params.sprite_shading == SpriteShading::none ? SpriteShading::solids : scene.params.sprite_shading;
        for (const std::vector<int>* list : {&e.floors, &e.overlays})
            for (int s : *list) normals[std::size_t(s)] = sprite_normals(ts, ts.sprites[std::size_t(s)], scene.params, from);
    }
    for (const std::vector<int>* list : {&e.floors, &e.overlays})
        for (int s : *list) {
            const Sprite& sp = ts.sprites[std::size_t(s)];
            save_image(images / e.image_files[std::size_t(s)], sp.image);
            if (!options.normal_maps) continue;
            const SpriteNormals& n = normals[std::size_t(s)];
            save_rgb8(images / beside(e.image_files[std::size_t(s)], "normal"), n.width, n.height,
                      normal_map_rgb(n, NormalConvention::opengl));
            save_gray16(images / beside(e.image_files[std::size_t(s)], "height"), n.width, n.height, height_map_values(n));
        }
    if (!e.floors.empty())
        write_tsx(dir / files.floors_tsx, base + "_floors", ts, e.floors, e.image_files, images, e.floor_offset_x,
                  e.floor_offset_y, nullptr, options.normal_maps);
    write_tsx(dir / files.overlays_tsx, base + "_overlays", ts, e.overlays, e.image_files, images, 0, 0, "topleft",
              options.normal_maps);

    pugi::xml_document doc;
    pugi::xml_node m = start_map(doc, world.map, g, options.chunk > 0);
    int next_id = 1, object_id = 1;
    write_map_properties(m, scene, world.map.layout, origin, world.frame);
    write_tileset_refs(m, e, files);
    if (!floors_as_objects) write_floor_layers(m, world, e, next_id, options.chunk);
    write_overlay_objects(m, world, g, e, floors_as_objects, origin, next_id, object_id);
    write_light_objects(m, scene, g, origin, next_id, object_id);
    write_obstacle_objects(m, world, scene, g, origin, next_id, object_id);
    if (options.images) write_image_layers(m, world, scene, dir, files, origin, next_id);
    m.append_attribute("nextlayerid") = next_id;
    m.append_attribute("nextobjectid") = object_id;
    std::ostringstream out;
    doc.save(out, "  ");
    write_file_atomic(tmx, out.str());  // the map names the new files from here on
    written.done = true;
    if (old_generation >= 0) ExportFiles(base, old_generation).remove_from(dir);
    return origin;
}

}  // namespace isolux
