// Tiled maps (TMX) out and in: tiled.hpp. Geometry follows Tiled 1.8's own
// renderers (libtiled's isometricrenderer.cpp and hexagonalrenderer.cpp), so
// that tmxrasterizer draws an exported map as isolux does and isolux places
// an imported map's sprites where Tiled does.
#include "isolux/tiled.hpp"

#include <pugixml.hpp>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <climits>
#include <functional>
#include <iterator>
#include <optional>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/params.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/truth.hpp"

namespace fs = std::filesystem;

namespace isolux {

namespace {

// ---------------------------------------------------------------- geometry

// How a Tiled map turns tiles and object pixels into screen pixels.
struct Grid {
    bool isometric = true;  // else staggered, axis y
    bool stagger_even = false;
    int tw = 0, th = 0, w = 0, h = 0;

    // The bottom-left of cell (x, y)'s box: where Tiled draws its image from.
    void cell_bottom_left(int x, int y, double& sx, double& sy) const {
        if (isometric) {
            const double origin_x = double(h) * tw / 2;
            sx = (x - y) * tw / 2.0 + origin_x - tw / 2.0;
            sy = (x + y) * th / 2.0 + th;
        } else {
            const bool shifted = ((y & 1) != 0) != stagger_even;
            sx = double(x) * tw + (shifted ? tw / 2.0 : 0.0);
            sy = double(y) * (th / 2) + th;
        }
    }
    // An object's pixel coordinates to screen pixels, and back.
    void object_to_screen(double px, double py, double& sx, double& sy) const {
        if (!isometric) {
            sx = px, sy = py;
            return;
        }
        const double tx = px / th, ty = py / th;
        sx = (tx - ty) * tw / 2.0 + double(h) * tw / 2;
        sy = (tx + ty) * th / 2.0;
    }
    void screen_to_object(double sx, double sy, double& px, double& py) const {
        if (!isometric) {
            px = sx, py = sy;
            return;
        }
        const double a = (sx - double(h) * tw / 2) / (tw / 2.0), b = sy / (th / 2.0);
        px = (a + b) / 2 * th;
        py = (b - a) / 2 * th;
    }
};

std::string number(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

// ---------------------------------------------------------------- export

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
void write_tsx(const fs::path& path, const std::string& name, const Tileset& ts, const std::vector<int>& sprites,
               const fs::path& image_dir, int offset_x, int offset_y, const char* alignment) {
    pugi::xml_document doc;
    auto decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
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
        pugi::xml_node img = tile.append_child("image");
        img.append_attribute("width") = s.image.width;
        img.append_attribute("height") = s.image.height;
        img.append_attribute("source") = (image_dir.filename() / (s.name + ".png")).string().c_str();
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

}  // namespace

std::pair<int, int> export_tiled(const World& world, const Scene& scene, const fs::path& tmx, const TiledExport& options) {
    if (tmx.extension() != ".tmx") throw Error(tmx.string() + ": the map must be a .tmx file");
    const Map& map = world.map;
    const Tileset& ts = world.tileset;
    const std::string base = tmx.stem().string();
    const fs::path dir = tmx.parent_path().empty() ? fs::path(".") : tmx.parent_path();
    const fs::path image_dir = dir / (base + "_images");
    std::error_code ec;
    const bool image_dir_existed = fs::exists(image_dir, ec);
    fs::create_directories(image_dir, ec);
    if (ec) throw Error(image_dir.string() + ": cannot create (" + ec.message() + ")");
    // An export that fails (a full disk, say) takes back the folder it made.
    struct RemoveUnlessDone {
        fs::path dir;
        bool armed;
        ~RemoveUnlessDone() {
            std::error_code e;
            if (armed) fs::remove_all(dir, e);
        }
    } undo{image_dir, !image_dir_existed};

    Grid g;
    g.isometric = map.layout != Layout::staggered;
    g.tw = map.tile_width;
    g.th = map.tile_height;
    g.w = map.width;
    g.h = map.height;
    const bool floors_as_objects = map.layout == Layout::paper;

    // World pixel of Tiled's screen (0, 0): tile centres agree. Tiled's
    // centre of cell (x, y) is its box's bottom-left + (tw/2, -th/2).
    double bx = 0, by = 0;
    g.cell_bottom_left(0, 0, bx, by);
    int cx = 0, cy = 0;
    tile_center(map.layout, map.tile_width, map.tile_height, 0, 0, cx, cy);
    int origin_x = cx + world.placed.shift_x - int(bx + g.tw / 2.0);
    int origin_y = cy + world.placed.shift_y - int(by - g.th / 2.0);
    if (floors_as_objects) {
        // Paper layout: the objects carry every position; the Tiled grid is a
        // diamond one over the same pixels.
        origin_x = 0, origin_y = 0;
    }

    // The sprites used, in two tilesets: floors (offset so a cell draws the
    // block where isolux does) and overlays (tile objects, top-left aligned).
    std::vector<int> floors, overlays;
    std::vector<int> floor_gid(ts.sprites.size(), 0), overlay_gid(ts.sprites.size(), 0);
    for (const SpriteInstance& in : world.placed.instances) {
        if (in.sprite < 0) continue;
        const bool floor = ts.sprites[std::size_t(in.sprite)].kind == SpriteKind::floor && !floors_as_objects;
        std::vector<int>& list = floor ? floors : overlays;
        if (std::find(list.begin(), list.end(), in.sprite) == list.end()) list.push_back(in.sprite);
    }
    std::sort(floors.begin(), floors.end());
    std::sort(overlays.begin(), overlays.end());
    // One offset for all floors: they must share size and anchor.
    int off_x = 0, off_y = 0;
    for (std::size_t i = 0; i < floors.size(); ++i) {
        const Sprite& s = ts.sprites[std::size_t(floors[i])];
        const int ox = g.tw / 2 - s.anchor_x, oy = s.image.height - s.anchor_y - g.th / 2;
        if (i > 0 && (ox != off_x || oy != off_y))
            throw Error(tmx.string() + ": floor sprites \"" + ts.sprites[std::size_t(floors[0])].name + "\" and \"" +
                        s.name + "\" are anchored differently: Tiled gives one offset per tileset");
        off_x = ox, off_y = oy;
    }
    for (int s : floors) save_image(image_dir / (ts.sprites[std::size_t(s)].name + ".png"), ts.sprites[std::size_t(s)].image);
    for (int s : overlays) save_image(image_dir / (ts.sprites[std::size_t(s)].name + ".png"), ts.sprites[std::size_t(s)].image);
    const int first_floor = 1, first_overlay = 1 + int(floors.size());
    for (std::size_t i = 0; i < floors.size(); ++i) floor_gid[std::size_t(floors[i])] = first_floor + int(i);
    for (std::size_t i = 0; i < overlays.size(); ++i) overlay_gid[std::size_t(overlays[i])] = first_overlay + int(i);
    if (!floors.empty())
        write_tsx(dir / (base + "_floors.tsx"), base + "_floors", ts, floors, image_dir, off_x, off_y, nullptr);
    write_tsx(dir / (base + "_overlays.tsx"), base + "_overlays", ts, overlays, image_dir, 0, 0, "topleft");

    pugi::xml_document doc;
    auto decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    pugi::xml_node m = doc.append_child("map");
    m.append_attribute("version") = "1.8";
    m.append_attribute("tiledversion") = "1.8.2";
    m.append_attribute("orientation") = g.isometric ? "isometric" : "staggered";
    m.append_attribute("renderorder") = "right-down";
    m.append_attribute("width") = map.width;
    m.append_attribute("height") = map.height;
    m.append_attribute("tilewidth") = g.tw;
    m.append_attribute("tileheight") = g.th;
    m.append_attribute("infinite") = 0;
    if (!g.isometric) {
        m.append_attribute("staggeraxis") = "y";
        m.append_attribute("staggerindex") = "odd";
    }
    int next_id = 1;
    // The preset, and what isolux needs to light the map again.
    pugi::xml_node props = m.append_child("properties");
    add_property(props, "isolux_layout", nullptr, std::string(to_string(map.layout)));
    add_property(props, "isolux_origin_x", "int", std::to_string(origin_x));
    add_property(props, "isolux_origin_y", "int", std::to_string(origin_y));
    add_property(props, "isolux_seed", nullptr, scene.seed);
    for (const ParamInfo& info : param_table()) {
        const double v = info.get(scene.params);
        const char* type = info.type == ParamType::integer ? "int"
                           : info.type == ParamType::real  ? "float"
                           : info.type == ParamType::boolean ? "bool"
                                                              : nullptr;
        add_property(props, info.name, type, format_param(info, v));
    }
    if (!floors.empty()) {
        pugi::xml_node t = m.append_child("tileset");
        t.append_attribute("firstgid") = first_floor;
        t.append_attribute("source") = (base + "_floors.tsx").c_str();
    }
    {
        pugi::xml_node t = m.append_child("tileset");
        t.append_attribute("firstgid") = first_overlay;
        t.append_attribute("source") = (base + "_overlays.tsx").c_str();
    }
    // Floors: one tile layer, CSV.
    if (!floors_as_objects) {
        pugi::xml_node layer = m.append_child("layer");
        layer.append_attribute("id") = next_id++;
        layer.append_attribute("name") = "floors";
        layer.append_attribute("width") = map.width;
        layer.append_attribute("height") = map.height;
        std::string csv = "\n";
        for (int row = 0; row < map.height; ++row) {
            for (int col = 0; col < map.width; ++col) {
                const int sprite = world.placed.tile_instances.empty()
                                       ? map.at(col, row).floor
                                       : world.placed.instances[world.placed.tile_instances[std::size_t(row * map.width + col)][0]].sprite;
                csv += std::to_string(floor_gid[std::size_t(sprite)]);
                if (row + 1 < map.height || col + 1 < map.width) csv += ",";
            }
            csv += "\n";
        }
        pugi::xml_node data = layer.append_child("data");
        data.append_attribute("encoding") = "csv";
        data.text() = csv.c_str();
    }
    // Overlays (and, in the paper layout, floors): tile objects in draw
    // order, each image's top-left where isolux draws it.
    pugi::xml_node objects = m.append_child("objectgroup");
    objects.append_attribute("id") = next_id++;
    objects.append_attribute("name") = "overlays";
    objects.append_attribute("draworder") = "index";
    int object_id = 1;
    for (std::uint32_t k : draw_order(world.placed, !floors_as_objects)) {
        const SpriteInstance& in = world.placed.instances[k];
        double px = 0, py = 0;
        g.screen_to_object(in.x - origin_x, in.y - origin_y, px, py);
        pugi::xml_node o = objects.append_child("object");
        o.append_attribute("id") = object_id++;
        o.append_attribute("gid") = overlay_gid[std::size_t(in.sprite)];
        o.append_attribute("x") = number(px).c_str();
        o.append_attribute("y") = number(py).c_str();
        o.append_attribute("width") = in.w;
        o.append_attribute("height") = in.h;
    }
    // Lights: points at their ground point, with what isolux needs.
    pugi::xml_node lights = m.append_child("objectgroup");
    lights.append_attribute("id") = next_id++;
    lights.append_attribute("name") = "lights";
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        double px = 0, py = 0;
        g.screen_to_object(l.x - origin_x, l.y - origin_y, px, py);
        pugi::xml_node o = lights.append_child("object");
        o.append_attribute("id") = object_id++;
        o.append_attribute("name") = l.name.empty() ? ("light " + std::to_string(i + 1)).c_str() : l.name.c_str();
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
    // Obstacles: the obstacle map as polygons (screen rectangles, which an
    // isometric map's object pixels shear), for collision or occluders.
    pugi::xml_node obstacles = m.append_child("objectgroup");
    obstacles.append_attribute("id") = next_id++;
    obstacles.append_attribute("name") = "obstacles";
    const Mask mask = build_obstacle_map(ts, world.placed, scene.params, world.placed.bounds);
    for (const Rect& r : obstacle_rects(mask)) {
        double px = 0, py = 0;
        g.screen_to_object(r.x - origin_x, r.y - origin_y, px, py);
        pugi::xml_node o = obstacles.append_child("object");
        o.append_attribute("id") = object_id++;
        o.append_attribute("x") = number(px).c_str();
        o.append_attribute("y") = number(py).c_str();
        const double corners[4][2] = {{0, 0}, {double(r.w), 0}, {double(r.w), double(r.h)}, {0, double(r.h)}};
        std::string points;
        for (const auto& c : corners) {
            double qx = 0, qy = 0;
            g.screen_to_object(r.x - origin_x + c[0], r.y - origin_y + c[1], qx, qy);
            points += (points.empty() ? "" : " ") + number(qx - px) + "," + number(qy - py);
        }
        o.append_child("polygon").append_attribute("points") = points.c_str();
    }
    if (options.images) {
        FrameState st;
        const Rect view = world.placed.bounds;
        render_frame(st, world, scene, Camera{double(view.x), double(view.y), view.w, view.h}, 0);
        const std::pair<const char*, Image> layers[] = {{"light", light_texture_image(st.light)}, {"final", st.final}};
        for (const auto& [name, image] : layers) {
            const std::string file = base + "_" + name + ".png";
            save_image(dir / file, image);
            pugi::xml_node il = m.append_child("imagelayer");
            il.append_attribute("id") = next_id++;
            il.append_attribute("name") = name;
            il.append_attribute("visible") = 0;
            il.append_attribute("offsetx") = view.x - origin_x;
            il.append_attribute("offsety") = view.y - origin_y;
            pugi::xml_node img = il.append_child("image");
            img.append_attribute("source") = file.c_str();
            img.append_attribute("width") = image.width;
            img.append_attribute("height") = image.height;
        }
    }
    m.append_attribute("nextlayerid") = next_id;
    m.append_attribute("nextobjectid") = object_id;
    std::ostringstream out;
    doc.save(out, "  ");
    write_file_atomic(tmx, out.str());
    undo.armed = false;
    return {origin_x, origin_y};
}


// ---------------------------------------------------------------- import

namespace {

constexpr std::uint32_t flip_h = 0x80000000u, flip_v = 0x40000000u, flip_d = 0x20000000u, rotate_hex = 0x10000000u;
constexpr std::uint32_t gid_mask = ~(flip_h | flip_v | flip_d | rotate_hex);

std::string where_of(const fs::path& file, const pugi::xml_node& node) {
    std::string w = file.string() + ": <" + node.name();
    if (const auto id = node.attribute("id")) w += std::string(" id=\"") + id.value() + "\"";
    if (const auto name = node.attribute("name")) w += std::string(" name=\"") + name.value() + "\"";
    return w + ">";
}

[[noreturn]] void fail(const fs::path& file, const pugi::xml_node& node, const std::string& what) {
    throw Error(where_of(file, node) + ": " + what);
}

int int_attr(const fs::path& file, const pugi::xml_node& node, const char* name, int lo, int hi, std::optional<int> def = {}) {
    const pugi::xml_attribute a = node.attribute(name);
    if (!a) {
        if (def) return *def;
        fail(file, node, std::string("lacks ") + name);
    }
    const std::string text = a.value();
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || v < lo || v > hi)
        fail(file, node, std::string(name) + "=\"" + text + "\" is not an integer in [" + std::to_string(lo) + ", " +
                             std::to_string(hi) + "]");
    return int(v);
}

double real_attr(const fs::path& file, const pugi::xml_node& node, const char* name, double def) {
    const pugi::xml_attribute a = node.attribute(name);
    if (!a) return def;
    const std::string text = a.value();
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v) || std::abs(v) > 1e9)
        fail(file, node, std::string(name) + "=\"" + text + "\" is not a number in [-1e9, 1e9]");
    return v;
}

pugi::xml_document read_xml(const fs::path& path) {
    check_input_file(path, max_text_file_bytes);
    std::ifstream f(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    pugi::xml_document doc;
    const pugi::xml_parse_result r = doc.load_buffer(text.data(), text.size());
    if (!r) throw Error(path.string() + ": malformed XML at byte " + std::to_string(r.offset) + " (" + r.description() + ")");
    return doc;
}

// Base64 as TMX writes it (whitespace around it ignored).
std::string base64_decode(const fs::path& file, const pugi::xml_node& data, const std::string& in) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    std::string out;
    int bits = 0, acc = 0;
    for (char c : in) {
        if (c == '=' ) break;
        if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
        const int v = value(c);
        if (v < 0) fail(file, data, std::string("base64 data holds '") + c + "'");
        acc = (acc << 6) | v;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(char((acc >> bits) & 0xFF));
        }
    }
    return out;
}

// zlib or gzip (windowBits 15 + 32 detects either), never past `limit` bytes.
std::string inflate_bounded(const fs::path& file, const pugi::xml_node& data, const std::string& in, std::size_t limit) {
    z_stream z{};
    if (inflateInit2(&z, 15 + 32) != Z_OK) fail(file, data, "cannot start zlib");
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    z.avail_in = uInt(in.size());
    std::string out;
    char buf[65536];
    int r = Z_OK;
    while (r != Z_STREAM_END) {
        z.next_out = reinterpret_cast<Bytef*>(buf);
        z.avail_out = sizeof buf;
        r = inflate(&z, Z_NO_FLUSH);
        if (r != Z_OK && r != Z_STREAM_END) {
            inflateEnd(&z);
            fail(file, data, "compressed data is corrupt (zlib: " + std::string(z.msg ? z.msg : "error") + ")");
        }
        out.append(buf, sizeof buf - z.avail_out);
        if (out.size() > limit) {
            inflateEnd(&z);
            fail(file, data, "decompresses to more than the layer's size (a compression bomb?)");
        }
        if (r != Z_STREAM_END && z.avail_in == 0 && z.avail_out != 0) {
            inflateEnd(&z);
            fail(file, data, "compressed data ends early");
        }
    }
    inflateEnd(&z);
    return out;
}

std::string unzstd_bounded(const fs::path& file, const pugi::xml_node& data, const std::string& in, std::size_t limit) {
    ZSTD_DStream* z = ZSTD_createDStream();
    ZSTD_initDStream(z);
    ZSTD_inBuffer input{in.data(), in.size(), 0};
    std::string out;
    char buf[65536];
    std::size_t r = 1;
    while (input.pos < input.size || r != 0) {
        ZSTD_outBuffer output{buf, sizeof buf, 0};
        r = ZSTD_decompressStream(z, &output, &input);
        if (ZSTD_isError(r)) {
            ZSTD_freeDStream(z);
            fail(file, data, std::string("compressed data is corrupt (zstd: ") + ZSTD_getErrorName(r) + ")");
        }
        out.append(buf, output.pos);
        if (out.size() > limit) {
            ZSTD_freeDStream(z);
            fail(file, data, "decompresses to more than the layer's size (a compression bomb?)");
        }
        if (output.pos == 0 && input.pos == input.size && r != 0) {
            ZSTD_freeDStream(z);
            fail(file, data, "compressed data ends early");
        }
    }
    ZSTD_freeDStream(z);
    return out;
}

// A layer's gids, w x h of them.
std::vector<std::uint32_t> layer_gids(const fs::path& file, const pugi::xml_node& layer, int w, int h) {
    const pugi::xml_node data = layer.child("data");
    if (!data) fail(file, layer, "has no <data>");
    if (data.child("chunk")) fail(file, data, "holds chunks: infinite maps are not supported (Map > Map Properties > Infinite off)");
    const std::string encoding = data.attribute("encoding").value(), compression = data.attribute("compression").value();
    const std::size_t count = std::size_t(w) * h;
    std::vector<std::uint32_t> gids;
    gids.reserve(count);
    if (encoding == "csv") {
        if (!compression.empty()) fail(file, data, "CSV data cannot be compressed");
        const char* p = data.text().get();
        while (*p) {
            while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t' || *p == ',') ++p;
            if (!*p) break;
            char* end = nullptr;
            const unsigned long long v = std::strtoull(p, &end, 10);
            if (end == p || v > 0xFFFFFFFFull) fail(file, data, "CSV data holds a value that is not a gid");
            gids.push_back(std::uint32_t(v));
            if (gids.size() > count) break;
            p = end;
        }
    } else if (encoding == "base64") {
        std::string bytes = base64_decode(file, data, data.text().get());
        const std::size_t want = count * 4;
        if (compression == "zlib" || compression == "gzip") bytes = inflate_bounded(file, data, bytes, want);
        else if (compression == "zstd") bytes = unzstd_bounded(file, data, bytes, want);
        else if (!compression.empty()) fail(file, data, "compression \"" + compression + "\" is unknown (zlib, gzip, zstd)");
        if (bytes.size() != want)
            fail(file, data, "holds " + std::to_string(bytes.size() / 4) + " tiles, the layer is " + std::to_string(w) + "x" +
                                 std::to_string(h));
        for (std::size_t i = 0; i < count; ++i) {
            const auto* b = reinterpret_cast<const unsigned char*>(&bytes[i * 4]);
            gids.push_back(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24);
        }
    } else if (encoding.empty()) {
        for (pugi::xml_node t : data.children("tile")) {
            gids.push_back(std::uint32_t(std::strtoull(t.attribute("gid").value(), nullptr, 10)));
            if (gids.size() > count) break;
        }
    } else {
        fail(file, data, "encoding \"" + encoding + "\" is unknown (csv, base64)");
    }
    if (gids.size() != count)
        fail(file, data, "holds " + std::to_string(gids.size()) + " tiles, the layer is " + std::to_string(w) + "x" + std::to_string(h));
    return gids;
}

// One Tiled tileset: its tiles' images (from a sheet or a collection) and offset.
struct TiledTileset {
    int firstgid = 0;
    std::string name;
    fs::path file;  // where it was read, for messages
    int tile_w = 0, tile_h = 0, offset_x = 0, offset_y = 0;
    std::string alignment;
    std::map<int, Image> images;                  // tile id -> image
    std::map<int, std::string> kinds;             // tile id -> isolux_kind property
    std::map<int, std::map<std::string, std::string>> props;  // tile id -> its isolux_* properties
    std::string kind;                              // the tileset's isolux_kind
};

std::string property(const pugi::xml_node& node, const char* name) {
    for (pugi::xml_node p : node.child("properties").children("property"))
        if (std::string(p.attribute("name").value()) == name)
            return p.attribute("value") ? p.attribute("value").value() : p.text().get();
    return "";
}

Image load_tiled_image(const fs::path& file, const pugi::xml_node& image, const fs::path& base) {
    const std::string source = image.attribute("source").value();
    if (source.empty()) fail(file, image, "has no source (embedded image data is not supported)");
    try {
        return load_image(base / source);
    } catch (const Error& e) {
        fail(file, image, e.what());
    }
}

TiledTileset read_tileset(const fs::path& tmx, const pugi::xml_node& ref, std::vector<std::string>& warnings) {
    TiledTileset t;
    t.firstgid = int_attr(tmx, ref, "firstgid", 1, 0x0FFFFFFF);
    pugi::xml_document external;
    pugi::xml_node node = ref;
    fs::path file = tmx;
    if (const auto source = ref.attribute("source")) {
        file = tmx.parent_path() / source.value();
        try {
            external = read_xml(file);
        } catch (const Error& e) {
            fail(tmx, ref, std::string("tileset \"") + source.value() + "\": " + e.what());
        }
        node = external.child("tileset");
        if (!node) throw Error(file.string() + ": no <tileset>");
    }
    t.file = file;
    t.name = node.attribute("name").value();
    t.tile_w = int_attr(file, node, "tilewidth", 1, 65536);
    t.tile_h = int_attr(file, node, "tileheight", 1, 65536);
    t.alignment = node.attribute("objectalignment").value();
    t.kind = property(node, "isolux_kind");
    if (const pugi::xml_node off = node.child("tileoffset")) {
        t.offset_x = int_attr(file, off, "x", -65536, 65536, 0);
        t.offset_y = int_attr(file, off, "y", -65536, 65536, 0);
    }
    const fs::path base = file.parent_path();
    if (const pugi::xml_node image = node.child("image")) {
        // A sheet: tiles cut row by row.
        const Image sheet = load_tiled_image(file, image, base);
        const int spacing = int_attr(file, node, "spacing", 0, 65536, 0), margin = int_attr(file, node, "margin", 0, 65536, 0);
        const int columns = std::max(1, int_attr(file, node, "columns", 0, 65536, (sheet.width - 2 * margin + spacing) / (t.tile_w + spacing)));
        const int count = int_attr(file, node, "tilecount", 0, 1 << 20, columns * ((sheet.height - 2 * margin + spacing) / (t.tile_h + spacing)));
        for (int id = 0; id < count; ++id) {
            const int x = margin + (id % columns) * (t.tile_w + spacing), y = margin + (id / columns) * (t.tile_h + spacing);
            if (x + t.tile_w > sheet.width || y + t.tile_h > sheet.height) break;
            Image tile(t.tile_w, t.tile_h);
            for (int r = 0; r < t.tile_h; ++r) std::copy_n(sheet.at(x, y + r), std::size_t(t.tile_w) * 4, tile.at(0, r));
            t.images.emplace(id, std::move(tile));
        }
    }
    for (pugi::xml_node tile : node.children("tile")) {
        const int id = int_attr(file, tile, "id", 0, 1 << 28);
        if (const pugi::xml_node image = tile.child("image")) t.images[id] = load_tiled_image(file, image, base);
        const std::string k = property(tile, "isolux_kind");
        if (!k.empty()) t.kinds[id] = k;
        for (pugi::xml_node p : tile.child("properties").children("property")) {
            const std::string name = p.attribute("name").value();
            if (name.rfind("isolux_", 0) == 0) t.props[id][name] = p.attribute("value").value();
        }
        if (tile.child("animation")) warnings.push_back(where_of(file, tile) + ": animated: its first frame only is lit");
    }
    return t;
}

Image flipped(const Image& in, std::uint32_t flags) {
    Image src = in;
    if (flags & flip_d) {  // the anti-diagonal flip Tiled applies first: a transpose
        Image t(in.height, in.width);
        for (int y = 0; y < in.height; ++y)
            for (int x = 0; x < in.width; ++x) std::copy_n(in.at(x, y), 4, t.at(y, x));
        src = std::move(t);
    }
    Image out(src.width, src.height);
    for (int y = 0; y < src.height; ++y)
        for (int x = 0; x < src.width; ++x) {
            const int sx = (flags & flip_h) ? src.width - 1 - x : x, sy = (flags & flip_v) ? src.height - 1 - y : y;
            std::copy_n(src.at(sx, sy), 4, out.at(x, y));
        }
    return out;
}

}  // namespace

TiledMap load_tiled(const fs::path& tmx) {
    TiledMap out;
    const pugi::xml_document doc = read_xml(tmx);
    const pugi::xml_node m = doc.child("map");
    if (!m) throw Error(tmx.string() + ": no <map>: not a TMX file");
    const std::string orientation = m.attribute("orientation").value();
    Grid g;
    if (orientation == "isometric") {
        g.isometric = true;
    } else if (orientation == "staggered") {
        g.isometric = false;
        if (std::string(m.attribute("staggeraxis").value()) == "x")
            fail(tmx, m, "staggeraxis=\"x\" is not supported (isolux's staggered maps shift rows: staggeraxis y)");
        g.stagger_even = std::string(m.attribute("staggerindex").value()) == "even";
    } else {
        fail(tmx, m, "orientation \"" + orientation + "\" is not supported: isolux lights isometric and staggered maps");
    }
    if (std::string(m.attribute("infinite").value()) == "1") fail(tmx, m, "infinite maps are not supported");
    g.w = int_attr(tmx, m, "width", 1, max_tiled_side);
    g.h = int_attr(tmx, m, "height", 1, max_tiled_side);
    g.tw = int_attr(tmx, m, "tilewidth", 2, 4096);
    g.th = int_attr(tmx, m, "tileheight", 2, 4096);

    std::vector<TiledTileset> sets;
    for (pugi::xml_node t : m.children("tileset")) sets.push_back(read_tileset(tmx, t, out.warnings));
    std::sort(sets.begin(), sets.end(), [](const TiledTileset& a, const TiledTileset& b) { return a.firstgid < b.firstgid; });

    Tileset& ts = out.world.tileset;
    ts.tile_width = g.tw;
    ts.tile_height = g.th;
    ts.source = tmx.string();
    // One isolux sprite per (gid with its flips, kind), made when first used.
    // The tileset a gid (flags removed) falls in: the last one starting at or below it.
    auto set_of = [&](std::uint32_t gid) -> const TiledTileset* {
        const TiledTileset* set = nullptr;
        for (const TiledTileset& s : sets)
            if (std::uint32_t(s.firstgid) <= gid) set = &s;
        return set;
    };
    std::map<std::pair<std::uint32_t, bool>, int> sprite_of;
    auto sprite_for = [&](const pugi::xml_node& where, std::uint32_t raw, bool floor) -> int {
        auto key = std::make_pair(raw & ~rotate_hex, floor);
        if (auto it = sprite_of.find(key); it != sprite_of.end()) return it->second;
        const std::uint32_t gid = raw & gid_mask;
        const TiledTileset* set = set_of(gid);
        const int id = set ? int(gid - std::uint32_t(set->firstgid)) : -1;
        if (!set || !set->images.count(id))
            fail(tmx, where, "gid " + std::to_string(gid) + " is beyond the tilesets (" + std::to_string(sets.size()) + " of them)");
        Sprite s;
        s.name = (set->name.empty() ? "tileset" : set->name) + "#" + std::to_string(id);
        if (raw & (flip_h | flip_v | flip_d)) s.name += "~" + std::to_string(raw >> 29);
        s.kind = floor ? SpriteKind::floor : SpriteKind::overlay;
        s.image = (raw & (flip_h | flip_v | flip_d)) ? flipped(set->images.at(id), raw) : set->images.at(id);
        // Anchored where Tiled draws it on a cell: the image's top-left is
        // the cell's bottom-left + offset - (0, height), and the anchor is
        // the diamond's centre.
        s.anchor_x = g.tw / 2 - set->offset_x;
        s.anchor_y = s.image.height - set->offset_y - g.th / 2;
        // A map isolux exported says more: the sprite's own anchor (where
        // it stands), tags, threshold and footprint.
        if (auto it = set->props.find(id); it != set->props.end() && !(raw & (flip_h | flip_v | flip_d))) {
            const auto& p = it->second;
            auto get = [&](const char* k) { auto f = p.find(k); return f == p.end() ? std::string() : f->second; };
            const std::string where = set->file.string() + ": tile " + std::to_string(id);
            auto integer = [&](const std::string& v, int def) {
                if (v.empty()) return def;
                char* end = nullptr;
                const long x = std::strtol(v.c_str(), &end, 10);
                if (*end != '\0' || std::labs(x) > 65536) throw Error(where + ": an isolux_anchor property is not an integer");
                return int(x);
            };
            s.anchor_x = integer(get("isolux_anchor_x"), s.anchor_x);
            s.anchor_y = integer(get("isolux_anchor_y"), s.anchor_y);
            if (!get("isolux_name").empty()) s.name = get("isolux_name");
            const std::string tags = get("isolux_tags");
            for (std::size_t pos = 0; !tags.empty() && pos <= tags.size();) {
                const std::size_t end = std::min(tags.find(',', pos), tags.size());
                s.tags.push_back(tags.substr(pos, end - pos));
                pos = end + 1;
            }
            if (!get("isolux_opacity_threshold").empty()) {
                char* end = nullptr;
                const double v = std::strtod(get("isolux_opacity_threshold").c_str(), &end);
                if (*end != '\0' || !(v >= 0 && v <= 1)) throw Error(where + ": isolux_opacity_threshold must be in [0, 1]");
                s.opacity_threshold = v;
            }
            if (!get("isolux_footprint").empty()) s.footprint = parse_footprint(get("isolux_footprint"), where + ": isolux_footprint");
        }
        ts.sprites.push_back(std::move(s));
        const int index = int(ts.sprites.size()) - 1;
        sprite_of[key] = index;
        return index;
    };
    auto kind_of = [&](std::uint32_t raw) -> std::string {
        const std::uint32_t gid = raw & gid_mask;
        const TiledTileset* set = set_of(gid);
        if (!set) return "";
        auto k = set->kinds.find(int(gid - std::uint32_t(set->firstgid)));
        return k != set->kinds.end() ? k->second : set->kind;
    };

    // The layers, in Tiled's order (groups flattened, their offsets added).
    struct Placed {
        SpriteInstance in;
        bool floor;
    };
    std::vector<Placed> placed;
    bool first_tile_layer = true, overlay_seen = false;
    int tile_layers = 0;
    std::function<void(const pugi::xml_node&, double, double)> walk = [&](const pugi::xml_node& parent, double ox, double oy) {
        for (pugi::xml_node layer : parent.children()) {
            const std::string type = layer.name();
            if (type != "layer" && type != "objectgroup" && type != "group" && type != "imagelayer") continue;
            if (std::string(layer.attribute("visible").value()) == "0") continue;
            const double lx = ox + real_attr(tmx, layer, "offsetx", 0), ly = oy + real_attr(tmx, layer, "offsety", 0);
            if (std::abs(lx) > 1e7 || std::abs(ly) > 1e7) fail(tmx, layer, "is offset beyond 1e7 pixels");
            if (type == "group") {
                walk(layer, lx, ly);
                continue;
            }
            if (type == "imagelayer") {
                out.warnings.push_back(where_of(tmx, layer) + ": image layers are not lit (left out)");
                continue;
            }
            const std::string layer_kind = property(layer, "isolux_kind");
            if (type == "layer") {
                const int lw = int_attr(tmx, layer, "width", 1, max_tiled_side, g.w), lh = int_attr(tmx, layer, "height", 1, max_tiled_side, g.h);
                if (lw != g.w || lh != g.h) fail(tmx, layer, "is " + std::to_string(lw) + "x" + std::to_string(lh) + ", the map " + std::to_string(g.w) + "x" + std::to_string(g.h));
                const std::vector<std::uint32_t> gids = layer_gids(tmx, layer, lw, lh);
                const bool floor_layer = layer_kind.empty() ? first_tile_layer : layer_kind == "floor";
                first_tile_layer = false;
                // Tiled's painter order: isometric by screen rows (x + y, then x);
                // staggered row by row.
                if (++tile_layers > max_tiled_layers)
                    fail(tmx, layer, "is one layer too many: at most " + std::to_string(max_tiled_layers) + " tile layers");
                std::vector<std::pair<int, int>> order;
                order.reserve(std::size_t(g.w) * g.h);
                if (g.isometric) {
                    for (int d = 0; d < g.w + g.h - 1; ++d)  // screen rows: x + y = d, x increasing
                        for (int x = std::max(0, d - (g.h - 1)); x <= std::min(d, g.w - 1); ++x) order.push_back({x, d - x});
                } else {
                    for (int y = 0; y < g.h; ++y)
                        for (int x = 0; x < g.w; ++x) order.push_back({x, y});
                }
                for (auto [x, y] : order) {
                    const std::uint32_t raw = gids[std::size_t(y) * g.w + x];
                    if ((raw & gid_mask) == 0) continue;
                    const std::string k = kind_of(raw);
                    const bool floor = layer_kind.empty() && !k.empty() ? k == "floor" : floor_layer;
                    if (floor && overlay_seen)
                        fail(tmx, layer, "is a floor layer above an overlay layer: isolux draws floors first (set the layer property isolux_kind)");
                    overlay_seen = overlay_seen || !floor;
                    const int sprite = sprite_for(layer, raw, floor);
                    double bx = 0, by = 0;
                    g.cell_bottom_left(x, y, bx, by);
                    const Sprite& s = ts.sprites[std::size_t(sprite)];
                    SpriteInstance in;
                    in.sprite = sprite;
                    in.w = s.image.width;
                    in.h = s.image.height;
                    in.x = int(std::lround(bx + lx)) + (g.tw / 2 - s.anchor_x);
                    in.y = int(std::lround(by + ly)) + (s.image.height - s.anchor_y - g.th / 2) - s.image.height;
                    in.ground_x = in.x + s.anchor_x;
                    in.ground_y = in.y + s.anchor_y;
                    in.tile = y * g.w + x;
                    placed.push_back({in, floor});
                }
                continue;
            }
            // An object group: tile objects are overlays; `lights` holds lights.
            const bool lights = std::string(layer.attribute("name").value()) == "lights";
            std::vector<pugi::xml_node> objects;
            for (pugi::xml_node o : layer.children("object")) objects.push_back(o);
            if (std::string(layer.attribute("draworder").value()) != "index")
                std::stable_sort(objects.begin(), objects.end(), [&](const pugi::xml_node& a, const pugi::xml_node& b) {
                    return real_attr(tmx, a, "y", 0) < real_attr(tmx, b, "y", 0);
                });
            for (const pugi::xml_node& o : objects) {
                if (std::string(o.attribute("visible").value()) == "0" && !lights) continue;
                double sx = 0, sy = 0;
                g.object_to_screen(real_attr(tmx, o, "x", 0), real_attr(tmx, o, "y", 0), sx, sy);
                sx += lx, sy += ly;
                if (std::abs(sx) > 1e8 || std::abs(sy) > 1e8) fail(tmx, o, "lies too far from the map (beyond 1e8 pixels)");
                if (lights) {
                    Light l;
                    l.x = sx, l.y = sy;  // shifted to world pixels below
                    l.name = o.attribute("name").value();
                    l.hidden = std::string(o.attribute("visible").value()) == "0";
                    const std::string colour = property(o, "color");
                    if (colour.size() == 9 && colour[0] == '#') parse_hex_color(colour.substr(3), l.r, l.g, l.b);
                    else if (colour.size() == 7 && colour[0] == '#') parse_hex_color(colour.substr(1), l.r, l.g, l.b);
                    auto num = [&](const char* k) -> std::optional<double> {
                        const std::string v = property(o, k);
                        if (v.empty()) return std::nullopt;
                        char* end = nullptr;
                        const double d = std::strtod(v.c_str(), &end);
                        if (*end != '\0' || !std::isfinite(d) || d < 0 || d > max_area)
                            fail(tmx, o, std::string("property ") + k + "=\"" + v + "\" is not a number in [0, " + std::to_string(max_area) + "]");
                        return d;
                    };
                    if (auto a = num("a")) l.area_a = int(*a);
                    if (auto b = num("b")) l.area_b = int(*b);
                    if (auto i = num("intensity")) l.intensity = std::min(1000.0, *i);
                    if (auto h = num("height")) l.height = *h;
                    out.scene.lights.push_back(l);
                    continue;
                }
                if (!o.attribute("gid")) continue;  // shapes (collision, notes): nothing to draw
                const unsigned long long rawll = std::strtoull(o.attribute("gid").value(), nullptr, 10);
                if (rawll > 0xFFFFFFFFull) fail(tmx, o, "gid is out of range");
                const std::uint32_t raw = std::uint32_t(rawll);
                const int sprite = sprite_for(o, raw, false);
                overlay_seen = true;
                const Sprite& s = ts.sprites[std::size_t(sprite)];
                const TiledTileset* set = set_of(raw & gid_mask);
                const double w = real_attr(tmx, o, "width", s.image.width), h = real_attr(tmx, o, "height", s.image.height);
                if (std::abs(w - s.image.width) > 0.01 || std::abs(h - s.image.height) > 0.01)
                    out.warnings.push_back(where_of(tmx, o) + ": scaled tile objects are drawn at their image's size");
                // Alignment: Tiled's default for isometric maps is bottom
                // (centre); staggered maps use bottom-left.
                std::string align = set->alignment.empty() || set->alignment == "unspecified"
                                        ? (g.isometric ? "bottom" : "bottomleft") : set->alignment;
                double ax = 0, ay = 0;
                if (align.find("right") != std::string::npos) ax = s.image.width;
                else if (align == "top" || align == "bottom" || align == "center") ax = s.image.width / 2.0;
                if (align.rfind("bottom", 0) == 0) ay = s.image.height;
                else if (align == "left" || align == "right" || align == "center") ay = s.image.height / 2.0;
                SpriteInstance in;
                in.sprite = sprite;
                in.w = s.image.width;
                in.h = s.image.height;
                in.x = int(std::lround(sx - ax + set->offset_x));
                in.y = int(std::lround(sy - ay + set->offset_y));
                in.ground_x = in.x + s.anchor_x;
                in.ground_y = in.y + s.anchor_y;
                placed.push_back({in, false});
            }
        }
    };
    walk(m, 0, 0);
    if (placed.empty()) fail(tmx, m, "draws no tile");

    // The world's origin is the top-left of what the sprites cover, as for a
    // seeded map; floors first (they are, by the rule above).
    int x0 = INT_MAX, y0 = INT_MAX;
    for (const Placed& p : placed) x0 = std::min(x0, p.in.x), y0 = std::min(y0, p.in.y);
    // A map isolux exported keeps its world pixels (lights stay where they were).
    if (!property(m, "isolux_origin_x").empty() && !property(m, "isolux_origin_y").empty()) {
        const long ox = std::strtol(property(m, "isolux_origin_x").c_str(), nullptr, 10);
        const long oy = std::strtol(property(m, "isolux_origin_y").c_str(), nullptr, 10);
        if (std::labs(ox) > 100000000 || std::labs(oy) > 100000000) fail(tmx, m, "isolux_origin lies beyond 1e8 pixels");
        x0 = -int(ox);
        y0 = -int(oy);
    }
    PlacedMap& pm = out.world.placed;
    for (const Placed& p : placed)
        if (p.floor) pm.instances.push_back(p.in);
    pm.first_overlay = pm.instances.size();
    for (const Placed& p : placed)
        if (!p.floor) pm.instances.push_back(p.in);
    for (SpriteInstance& in : pm.instances) in.x -= x0, in.y -= y0, in.ground_x -= x0, in.ground_y -= y0;
    out.origin_x = -x0;
    out.origin_y = -y0;
    finish_placed(pm);
    for (Light& l : out.scene.lights) l.x += out.origin_x, l.y += out.origin_y;

    // A map for the editor's tile lookup: the grid's layout and size.
    Map& map = out.world.map;
    map.width = g.w;
    map.height = g.h;
    map.layout = g.isometric ? Layout::diamond : Layout::staggered;
    map.tile_width = g.tw;
    map.tile_height = g.th;
    map.tiles.assign(std::size_t(g.w) * g.h, Tile{});
    double bx = 0, by = 0;
    g.cell_bottom_left(0, 0, bx, by);
    int cx = 0, cy = 0;
    tile_center(map.layout, g.tw, g.th, 0, 0, cx, cy);
    pm.shift_x = int(bx + g.tw / 2.0) + out.origin_x - cx;
    pm.shift_y = int(by - g.th / 2.0) + out.origin_y - cy;
    out.world.seeded = map;
    touch(out.world);

    // The preset from the map's properties (as export_tiled writes them).
    Scene& s = out.scene;
    s.width = g.w;
    s.height = g.h;
    s.layout = map.layout;
    s.seed = property(m, "isolux_seed");
    for (const ParamInfo& info : param_table()) {
        const std::string v = property(m, info.name);
        if (v.empty()) continue;
        set_param(s.params, info.name, v, tmx.string() + ": map property");
    }
    return out;
}

}  // namespace isolux
