// Tiled maps (TMX) into isolux: load_tiled (tiled.hpp). One reader per
// element, as Tiled's own mapreader.cpp: the map's grid, each tileset, each
// kind of layer, each kind of object; then the world is placed.
#include "isolux/tiled.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <map>
#include <optional>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/footprint.hpp"
#include "isolux/params.hpp"
#include "base/warnings.hpp"
#include "formats/json_fields.hpp"
#include "formats/sprite_fields.hpp"
#include "formats/tiled/tiled_grid.hpp"
#include "formats/tiled/tiled_xml.hpp"

namespace fs = std::filesystem;

namespace isolux {

namespace {

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

// The sprite pixels a map loads in all, and the footprint masks its sprites
// may need, against max_input_sprite_pixels.
struct PixelBudget {
    std::int64_t used = 0;
    void add(const fs::path& file, const pugi::xml_node& node, const Image& im) {
        add(file, node, std::int64_t(im.width) * im.height);
    }
    void add(const fs::path& file, const pugi::xml_node& node, std::int64_t pixels) {
        used += pixels;
        if (used > max_input_sprite_pixels)
            fail(file, node, "brings the map's images and footprints to " + std::to_string(used >> 20) +
                                 " megapixels, over the " + std::to_string(max_input_sprite_pixels >> 20) +
                                 " a map may load");
    }
};

Image load_tiled_image(const fs::path& file, const pugi::xml_node& image, const fs::path& base, PixelBudget& budget) {
    const std::string source = image.attribute("source").value();
    if (source.empty()) fail(file, image, "has no source (embedded image data is not supported)");
    Image im;
    try {
        im = load_image(base / source);
    } catch (const Error& e) {
        fail(file, image, e.what());
    }
    budget.add(file, image, im);
    return im;
}

TiledTileset read_tileset(const fs::path& tmx, const pugi::xml_node& ref, WarningRun& animated, PixelBudget& budget) {
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
        const Image sheet = load_tiled_image(file, image, base, budget);
        const int spacing = int_attr(file, node, "spacing", 0, 65536, 0), margin = int_attr(file, node, "margin", 0, 65536, 0);
        const int columns = std::max(1, int_attr(file, node, "columns", 0, 65536, (sheet.width - 2 * margin + spacing) / (t.tile_w + spacing)));
        const int count = int_attr(file, node, "tilecount", 0, 1 << 20, columns * ((sheet.height - 2 * margin + spacing) / (t.tile_h + spacing)));
        for (int id = 0; id < count; ++id) {
            const int x = margin + (id % columns) * (t.tile_w + spacing), y = margin + (id / columns) * (t.tile_h + spacing);
            if (x + t.tile_w > sheet.width || y + t.tile_h > sheet.height) break;
            Image tile(t.tile_w, t.tile_h);
            for (int r = 0; r < t.tile_h; ++r) std::copy_n(sheet.at(x, y + r), std::size_t(t.tile_w) * 4, tile.at(0, r));
            budget.add(file, image, tile);
            t.images.emplace(id, std::move(tile));
        }
    }
    for (pugi::xml_node tile : node.children("tile")) {
        const int id = int_attr(file, tile, "id", 0, 1 << 28);
        if (const pugi::xml_node image = tile.child("image")) t.images[id] = load_tiled_image(file, image, base, budget);
        const std::string k = property(tile, "isolux_kind");
        if (!k.empty()) t.kinds[id] = k;
        for (pugi::xml_node p : tile.child("properties").children("property")) {
            const std::string name = p.attribute("name").value();
            if (name.rfind("isolux_", 0) == 0) t.props[id][name] = p.attribute("value").value();
        }
        if (tile.child("animation")) animated.add(where_of(file, tile) + ": animated: its first frame only is lit");
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

// An infinite map's cells: the bounding box of every tile layer's chunks
// (groups included), its top row even so that a staggered map's rows keep
// their shift. Refused by name when there are none or the box is beyond
// max_tiled_side a side.
void read_chunk_bounds(const fs::path& tmx, const pugi::xml_node& m, Grid& g) {
    long long x0 = LLONG_MAX, y0 = LLONG_MAX, x1 = LLONG_MIN, y1 = LLONG_MIN;
    std::vector<pugi::xml_node> stack{m};
    while (!stack.empty()) {
        const pugi::xml_node n = stack.back();
        stack.pop_back();
        for (pugi::xml_node c : n.children()) {
            const std::string name = c.name();
            if (name == "group") stack.push_back(c);
            if (name != "layer") continue;
            for (pugi::xml_node ch : c.child("data").children("chunk")) {
                const long long x = int_attr(tmx, ch, "x", -1000000000, 1000000000), y = int_attr(tmx, ch, "y", -1000000000, 1000000000);
                const long long w = int_attr(tmx, ch, "width", 1, max_tiled_side), h = int_attr(tmx, ch, "height", 1, max_tiled_side);
                x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + w), y1 = std::max(y1, y + h);
            }
        }
    }
    if (x1 == LLONG_MIN) fail(tmx, m, "is an infinite map (infinite=\"1\") whose tile layers hold no chunks");
    if (y0 % 2 != 0) --y0;  // an even top row: staggered rows keep their shift
    if (!map_size_ok(x1 - x0, y1 - y0))
        fail(tmx, m, "is an infinite map whose chunks span " + std::to_string(x1 - x0) + "x" + std::to_string(y1 - y0) +
                         " tiles: " + map_size_rule());
    g.infinite = true;
    g.map_h = g.h;
    g.x0 = int(x0), g.y0 = int(y0);
    g.w = int(x1 - x0), g.h = int(y1 - y0);
    // The cells' screen pixels must fit the sprites' int coordinates: the
    // corners' pixels within 1e8 (as an isolux_origin), checked in doubles.
    for (int cx : {0, g.w})
        for (int cy : {0, g.h}) {
            double sx = 0, sy = 0;
            g.cell_bottom_left(cx, cy, sx, sy);
            if (!(std::abs(sx) <= 1e8 && std::abs(sy) <= 1e8))
                fail(tmx, m, "is an infinite map whose chunks at tiles (" + std::to_string(x0) + ", " + std::to_string(y0) +
                                 ") to (" + std::to_string(x1) + ", " + std::to_string(y1) +
                                 ") lie beyond 1e8 pixels of Tiled's origin");
        }
}

// The map element: orientation, size and tile size as a Grid.
Grid read_map_grid(const fs::path& tmx, const pugi::xml_node& m) {
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
    g.w = int_attr(tmx, m, "width", 1, max_tiled_side);
    g.h = int_attr(tmx, m, "height", 1, max_tiled_side);
    if (!map_size_ok(g.w, g.h))
        fail(tmx, m, "is " + std::to_string(g.w) + "x" + std::to_string(g.h) + " tiles: " + map_size_rule());
    g.tw = int_attr(tmx, m, "tilewidth", 2, 4096);
    g.th = int_attr(tmx, m, "tileheight", 2, 4096);
    if (std::string(m.attribute("infinite").value()) == "1") read_chunk_bounds(tmx, m, g);
    return g;
}

// A TMX property's text as the JSON value it spells ("12" an integer, "0.5"
// a number), or as a string when it spells none, so that the sprite fields'
// parser reads it by the manifest's rules and names what is wrong.
json property_value(const std::string& text) {
    json v = json::parse(text, nullptr, false);
    return v.is_discarded() || v.is_object() || v.is_array() ? json(text) : v;
}

// The isolux_* properties of a tile of a map isolux exported, as the
// manifest's fields (anchor, tags, opacity_threshold, footprint), read by the
// same parser. An anchor coordinate that is absent keeps the one Tiled's
// drawing gives.
void read_isolux_properties(const std::map<std::string, std::string>& props, const std::string& where, Sprite& s) {
    auto get = [&](const char* k) {
        auto f = props.find(k);
        return f == props.end() ? std::string() : f->second;
    };
    json fields = json::object();
    const std::string ax = get("isolux_anchor_x"), ay = get("isolux_anchor_y");
    if (!ax.empty() || !ay.empty())
        fields["anchor"] = {ax.empty() ? json(s.anchor_x) : property_value(ax), ay.empty() ? json(s.anchor_y) : property_value(ay)};
    if (const std::string tags = get("isolux_tags"); !tags.empty()) {
        fields["tags"] = json::array();
        for (std::size_t pos = 0; pos <= tags.size();) {
            const std::size_t end = std::min(tags.find(',', pos), tags.size());
            fields["tags"].push_back(tags.substr(pos, end - pos));
            pos = end + 1;
        }
    }
    if (const std::string t = get("isolux_opacity_threshold"); !t.empty()) fields["opacity_threshold"] = property_value(t);
    if (const std::string f = get("isolux_footprint"); !f.empty()) fields["footprint"] = parse_json(f, where + ": isolux_footprint");
    read_sprite_fields(Fields{fields, where + " (isolux_* properties)"}, s);
    if (!get("isolux_name").empty()) s.name = get("isolux_name");
}

// The isolux sprites a map uses: one per (gid with its flips, kind), made
// when first used, into `ts`.
class MapSprites {
public:
    MapSprites(const fs::path& tmx, const Grid& g, std::vector<TiledTileset> sets, Tileset& ts, PixelBudget& budget)
        : tmx_(tmx), g_(g), sets_(std::move(sets)), ts_(ts), budget_(budget) {
        std::stable_sort(sets_.begin(), sets_.end(), [](const TiledTileset& a, const TiledTileset& b) { return a.firstgid < b.firstgid; });
    }

    // The tileset a gid (flags removed) falls in: the last one starting at
    // or below it; nullptr when none does.
    const TiledTileset* set_of(std::uint32_t gid) const {
        auto it = std::upper_bound(sets_.begin(), sets_.end(), gid,
                                   [](std::uint32_t v, const TiledTileset& s) { return v < std::uint32_t(s.firstgid); });
        return it == sets_.begin() ? nullptr : &*std::prev(it);
    }

    // The isolux_kind a tile or its tileset names ("" when neither does).
    std::string kind_of(std::uint32_t raw) const {
        const std::uint32_t gid = raw & gid_mask;
        const TiledTileset* set = set_of(gid);
        if (!set) return "";
        auto k = set->kinds.find(int(gid - std::uint32_t(set->firstgid)));
        return k != set->kinds.end() ? k->second : set->kind;
    }

    // The sprite index of gid `raw` (with its flips) drawn as a floor or an
    // overlay; `where` names the element that uses it in errors.
    int sprite_for(const pugi::xml_node& where, std::uint32_t raw, bool floor) {
        auto key = std::make_pair(raw & ~rotate_hex, floor);
        if (auto it = sprite_of_.find(key); it != sprite_of_.end()) return it->second;
        const std::uint32_t gid = raw & gid_mask;
        const TiledTileset* set = set_of(gid);
        const int id = set ? int(gid - std::uint32_t(set->firstgid)) : -1;
        if (!set || !set->images.count(id))
            fail(tmx_, where, "gid " + std::to_string(gid) + " is beyond the tilesets (" + std::to_string(sets_.size()) + " of them)");
        const bool flips = (raw & (flip_h | flip_v | flip_d)) != 0;
        Sprite s;
        s.name = (set->name.empty() ? "tileset" : set->name) + "#" + std::to_string(id);
        if (flips) s.name += "~" + std::to_string(raw >> 29);
        s.kind = floor ? SpriteKind::floor : SpriteKind::overlay;
        s.image = flips ? flipped(set->images.at(id), raw) : set->images.at(id);
        budget_.add(tmx_, where, s.image);
        // Anchored where Tiled draws it on a cell: the image's top-left is
        // the cell's bottom-left + offset - (0, height), and the anchor is
        // the diamond's centre.
        s.anchor_x = g_.tw / 2 - set->offset_x;
        s.anchor_y = s.image.height - set->offset_y - g_.th / 2;
        // A map isolux exported says more: the sprite's own anchor (where
        // it stands), tags, threshold and footprint.
        if (auto it = set->props.find(id); it != set->props.end() && !flips)
            read_isolux_properties(it->second, set->file.string() + ": tile " + std::to_string(id), s);
        budget_.add(tmx_, where, footprint_pixels(s.image.width, s.image.height, s.footprint));
        ts_.sprites.push_back(std::move(s));
        const int index = int(ts_.sprites.size()) - 1;
        sprite_of_[key] = index;
        return index;
    }

private:
    const fs::path& tmx_;
    const Grid& g_;
    std::vector<TiledTileset> sets_;
    Tileset& ts_;
    PixelBudget& budget_;
    std::map<std::pair<std::uint32_t, bool>, int> sprite_of_;
};

// A sprite drawn by the map, before the world's origin is known.
struct Placed {
    SpriteInstance in;
    bool floor;
};

// Reads the layers of a map in Tiled's order into sprites placed where Tiled
// draws them and lights, one reader per element as Tiled's own mapreader.cpp.
class LayerReader {
public:
    LayerReader(const fs::path& tmx, const Grid& g, MapSprites& sprites, const Tileset& ts, TiledMap& out)
        : tmx_(tmx), g_(g), sprites_(sprites), ts_(ts), out_(out),
          image_layers_(&out.warnings, "image layers left out"),
          scaled_(&out.warnings, "scaled tile objects drawn at their image's size") {}

    // Every visible layer under `m`, groups flattened with their offsets
    // added. Walked with a stack of its own, not by recursion: a file sets
    // how deep groups nest.
    std::vector<Placed> read_layers(const pugi::xml_node& m) {
        struct Level {
            pugi::xml_node next;  // the next child to read
            double ox, oy;        // the group's offset
        };
        std::vector<Level> stack{{m.first_child(), 0, 0}};
        while (!stack.empty()) {
            const pugi::xml_node layer = stack.back().next;
            if (!layer) {
                stack.pop_back();
                continue;
            }
            stack.back().next = layer.next_sibling();
            const std::string type = layer.name();
            if (type != "layer" && type != "objectgroup" && type != "group" && type != "imagelayer") continue;
            if (std::string(layer.attribute("visible").value()) == "0") continue;
            const double lx = stack.back().ox + real_attr(tmx_, layer, "offsetx", 0);
            const double ly = stack.back().oy + real_attr(tmx_, layer, "offsety", 0);
            if (std::abs(lx) > 1e7 || std::abs(ly) > 1e7) fail(tmx_, layer, "is offset beyond 1e7 pixels");
            if (type == "group") stack.push_back({layer.first_child(), lx, ly});
            else if (type == "imagelayer") image_layers_.add(where_of(tmx_, layer) + ": image layers are not lit (left out)");
            else if (type == "layer") read_tile_layer(layer, lx, ly);
            else read_object_group(layer, lx, ly);
        }
        return std::move(placed_);
    }

private:
    // A tile layer: each tile a sprite on its cell, in Tiled's painter order
    // (isometric by screen rows, x + y then x; staggered row by row). The
    // first tile layer is the floor unless isolux_kind properties say.
    void read_tile_layer(const pugi::xml_node& layer, double lx, double ly) {
        const std::string layer_kind = property(layer, "isolux_kind");
        std::vector<std::uint32_t> gids;
        if (g_.infinite) {
            gids = chunked_layer_gids(tmx_, layer, g_.x0, g_.y0, g_.w, g_.h);
        } else {
            const int lw = int_attr(tmx_, layer, "width", 1, max_tiled_side, g_.w), lh = int_attr(tmx_, layer, "height", 1, max_tiled_side, g_.h);
            if (lw != g_.w || lh != g_.h)
                fail(tmx_, layer, "is " + std::to_string(lw) + "x" + std::to_string(lh) + ", the map " + std::to_string(g_.w) + "x" + std::to_string(g_.h));
            gids = layer_gids(tmx_, layer, lw, lh);
        }
        const bool floor_layer = layer_kind.empty() ? first_tile_layer_ : layer_kind == "floor";
        first_tile_layer_ = false;
        if (++tile_layers_ > max_tiled_layers)
            fail(tmx_, layer, "is one layer too many: at most " + std::to_string(max_tiled_layers) + " tile layers");
        std::vector<std::pair<int, int>> order;
        order.reserve(std::size_t(g_.w) * g_.h);
        if (g_.isometric) {
            for (int d = 0; d < g_.w + g_.h - 1; ++d)  // screen rows: x + y = d, x increasing
                for (int x = std::max(0, d - (g_.h - 1)); x <= std::min(d, g_.w - 1); ++x) order.push_back({x, d - x});
        } else {
            for (int y = 0; y < g_.h; ++y)
                for (int x = 0; x < g_.w; ++x) order.push_back({x, y});
        }
        for (auto [x, y] : order) {
            const std::uint32_t raw = gids[std::size_t(y) * g_.w + x];
            if ((raw & gid_mask) == 0) continue;
            const std::string k = sprites_.kind_of(raw);
            const bool floor = layer_kind.empty() && !k.empty() ? k == "floor" : floor_layer;
            if (floor && overlay_seen_)
                fail(tmx_, layer, "is a floor layer above an overlay layer: isolux draws floors first (set the layer property isolux_kind)");
            overlay_seen_ = overlay_seen_ || !floor;
            const int sprite = sprites_.sprite_for(layer, raw, floor);
            double bx = 0, by = 0;
            g_.cell_bottom_left(x, y, bx, by);
            const Sprite& s = ts_.sprites[std::size_t(sprite)];
            SpriteInstance in;
            in.sprite = sprite;
            in.w = s.image.width;
            in.h = s.image.height;
            in.x = int(std::lround(bx + lx)) + (g_.tw / 2 - s.anchor_x);
            in.y = int(std::lround(by + ly)) + (s.image.height - s.anchor_y - g_.th / 2) - s.image.height;
            in.ground_x = in.x + s.anchor_x;
            in.ground_y = in.y + s.anchor_y;
            in.tile = y * g_.w + x;
            place(layer, {in, floor});
        }
    }

    // An object group: the one named `lights` holds lights; elsewhere tile
    // objects are overlays and shapes (collision, notes) draw nothing. Drawn
    // in index order or, by default, by y.
    void read_object_group(const pugi::xml_node& layer, double lx, double ly) {
        const bool lights = std::string(layer.attribute("name").value()) == "lights";
        std::vector<pugi::xml_node> objects;
        for (pugi::xml_node o : layer.children("object")) objects.push_back(o);
        if (std::string(layer.attribute("draworder").value()) != "index")
            std::stable_sort(objects.begin(), objects.end(), [&](const pugi::xml_node& a, const pugi::xml_node& b) {
                return real_attr(tmx_, a, "y", 0) < real_attr(tmx_, b, "y", 0);
            });
        for (const pugi::xml_node& o : objects) {
            if (std::string(o.attribute("visible").value()) == "0" && !lights) continue;
            double sx = 0, sy = 0;
            g_.object_to_screen(real_attr(tmx_, o, "x", 0), real_attr(tmx_, o, "y", 0), sx, sy);
            sx += lx, sy += ly;
            if (std::abs(sx) > 1e8 || std::abs(sy) > 1e8) fail(tmx_, o, "lies too far from the map (beyond 1e8 pixels)");
            if (lights) out_.scene.lights.push_back(read_light(o, sx, sy));
            else if (o.attribute("gid")) read_tile_object(o, sx, sy);
        }
    }

    // A light: a point object with color, a, b, intensity and height
    // properties, at screen pixel (sx, sy) (shifted to world pixels later).
    Light read_light(const pugi::xml_node& o, double sx, double sy) const {
        Light l;
        l.x = sx, l.y = sy;
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
                fail(tmx_, o, std::string("property ") + k + "=\"" + v + "\" is not a number in [0, " + std::to_string(max_area) + "]");
            return d;
        };
        if (auto a = num("a")) l.area_a = int(*a);
        if (auto b = num("b")) l.area_b = int(*b);
        if (auto i = num("intensity")) l.intensity = std::min(1000.0, *i);
        if (auto h = num("height")) l.height = *h;
        return l;
    }

    // A tile object: an overlay drawn at its image's size, aligned as its
    // tileset says (Tiled's default: bottom centre on isometric maps,
    // bottom-left on staggered ones).
    void read_tile_object(const pugi::xml_node& o, double sx, double sy) {
        const unsigned long long rawll = std::strtoull(o.attribute("gid").value(), nullptr, 10);
        if (rawll > 0xFFFFFFFFull) fail(tmx_, o, "gid is out of range");
        const std::uint32_t raw = std::uint32_t(rawll);
        const int sprite = sprites_.sprite_for(o, raw, false);
        overlay_seen_ = true;
        const Sprite& s = ts_.sprites[std::size_t(sprite)];
        const TiledTileset* set = sprites_.set_of(raw & gid_mask);
        const double w = real_attr(tmx_, o, "width", s.image.width), h = real_attr(tmx_, o, "height", s.image.height);
        if (std::abs(w - s.image.width) > 0.01 || std::abs(h - s.image.height) > 0.01)
            scaled_.add(where_of(tmx_, o) + ": scaled tile objects are drawn at their image's size");
        const std::string align = set->alignment.empty() || set->alignment == "unspecified"
                                      ? (g_.isometric ? "bottom" : "bottomleft")
                                      : set->alignment;
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
        place(o, {in, false});
    }

    // Every sprite the map draws, within max_tiled_sprites.
    void place(const pugi::xml_node& where, const Placed& p) {
        if (placed_.size() >= std::size_t(max_tiled_sprites))
            fail(tmx_, where, "draws more than " + std::to_string(max_tiled_sprites) + " sprites, the most a map may");
        placed_.push_back(p);
    }

    const fs::path& tmx_;
    const Grid& g_;
    MapSprites& sprites_;
    const Tileset& ts_;
    TiledMap& out_;
    std::vector<Placed> placed_;
    WarningRun image_layers_, scaled_;
    bool first_tile_layer_ = true, overlay_seen_ = false;
    int tile_layers_ = 0;
};

// The world from the placed sprites: its origin the top-left of what they
// cover, as for a seeded map, or the isolux_origin a map isolux exported
// keeps (so lights stay where they were); floors first; the lights moved to
// world pixels; and a map of the grid's layout for the editor's tile lookup.
void place_world(const fs::path& tmx, const pugi::xml_node& m, const Grid& g, const std::vector<Placed>& placed,
                 TiledMap& out) {
    int x0 = INT_MAX, y0 = INT_MAX;
    for (const Placed& p : placed) x0 = std::min(x0, p.in.x), y0 = std::min(y0, p.in.y);
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
    // A map isolux exported keeps its scene's frame (four integers, world pixels).
    if (const std::string f = property(m, "isolux_frame"); !f.empty()) {
        long long v[4] = {0, 0, 0, 0};
        if (std::sscanf(f.c_str(), "%lld,%lld,%lld,%lld", &v[0], &v[1], &v[2], &v[3]) != 4 || std::llabs(v[0]) > 100000000 ||
            std::llabs(v[1]) > 100000000 || v[2] < 1 || v[3] < 1 || v[2] > 100000000 || v[3] > 100000000)
            fail(tmx, m, "property isolux_frame=\"" + f + "\" is not X,Y,W,H in world pixels");
        out.world.frame = Rect{int(v[0]), int(v[1]), int(v[2]), int(v[3])};
    }

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
}

// The scene's size, layout, seed and preset from the map's properties (as
// export_tiled writes them).
void read_map_properties(const fs::path& tmx, const pugi::xml_node& m, const Grid& g, TiledMap& out) {
    Scene& s = out.scene;
    s.width = g.w;
    s.height = g.h;
    s.layout = out.world.map.layout;
    s.seed = property(m, "isolux_seed");
    for (const ParamInfo& info : param_table()) {
        const std::string v = property(m, info.name);
        if (v.empty()) continue;
        set_param(s.params, info.name, v, tmx.string() + ": map property");
    }
}

}  // namespace

TiledMap load_tiled(const fs::path& tmx) {
    TiledMap out;
    const pugi::xml_document doc = read_xml(tmx);
    const pugi::xml_node m = doc.child("map");
    if (!m) throw Error(tmx.string() + ": no <map>: not a TMX file");
    const Grid g = read_map_grid(tmx, m);
    std::vector<TiledTileset> sets;
    PixelBudget budget;
    {
        WarningRun animated(&out.warnings, "animated tiles lit by their first frame");
        for (pugi::xml_node t : m.children("tileset")) sets.push_back(read_tileset(tmx, t, animated, budget));
    }
    Tileset& ts = out.world.tileset;
    ts.tile_width = g.tw;
    ts.tile_height = g.th;
    ts.source = tmx.string();
    MapSprites sprites(tmx, g, std::move(sets), ts, budget);
    const std::vector<Placed> placed = LayerReader(tmx, g, sprites, ts, out).read_layers(m);
    if (placed.empty()) fail(tmx, m, "draws no tile");
    place_world(tmx, m, g, placed, out);
    read_map_properties(tmx, m, g, out);
    return out;
}

}  // namespace isolux
