#include "isolux/tileset.hpp"

#include <algorithm>

#include "isolux/error.hpp"

namespace isolux {

bool Sprite::has_tag(std::string_view t) const {
    return std::find(tags.begin(), tags.end(), t) != tags.end();
}

std::vector<int> Tileset::find(SpriteKind kind, std::string_view tag) const {
    std::vector<int> tagged, untagged;
    for (int i = 0; i < int(sprites.size()); ++i) {
        const Sprite& s = sprites[i];
        if (s.kind != kind) continue;
        if (s.has_tag(tag)) tagged.push_back(i);
        if (s.tags.empty()) untagged.push_back(i);
    }
    return tagged.empty() ? untagged : tagged;
}

void validate(const Tileset& t) {
    std::string src = t.source.empty() ? "tileset" : t.source;
    if (t.tile_width < 2 || t.tile_height < 2 || t.tile_width > 4096 || t.tile_height > 4096)
        throw Error(src + ": tile: width and height must be in [2, 4096], got " +
                    std::to_string(t.tile_width) + "x" + std::to_string(t.tile_height));
    bool has_floor = false;
    std::size_t solids = 0;
    for (const Sprite& s : t.sprites) {
        if (s.image.width <= 0 || s.image.height <= 0)
            throw Error(src + ": sprite \"" + s.name + "\": zero-size sprite");
        has_floor = has_floor || s.kind == SpriteKind::floor;
        // The work a sprite's solid asks for grows with its height: a solid
        // stands within its picture, so its height is bounded by the image's.
        if (s.footprint.object_height > s.image.height)
            throw Error(src + ": sprite \"" + s.name + "\": object: height " + std::to_string(s.footprint.object_height) +
                        " is taller than its " + std::to_string(s.image.width) + "x" + std::to_string(s.image.height) +
                        " image (a solid stands within its picture)");
        // Tracing and the 3D reference test every solid of every placed
        // sprite: the shapes' solids are a budget of the whole tileset.
        solids += s.shape.size();
        if (solids > max_tileset_solids)
            throw Error(src + ": sprite \"" + s.name + "\": shape: brings the tileset's solids to " +
                        std::to_string(solids) + ", over the " + std::to_string(max_tileset_solids) +
                        " a tileset may hold in all");
    }
    if (!has_floor) throw Error(src + ": sprites: no sprite of kind \"floor\"; a map needs one");
}

}  // namespace isolux
