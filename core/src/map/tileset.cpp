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
    for (const Sprite& s : t.sprites) {
        if (s.image.width <= 0 || s.image.height <= 0)
            throw Error(src + ": sprite \"" + s.name + "\": zero-size sprite");
        has_floor = has_floor || s.kind == SpriteKind::floor;
    }
    if (!has_floor) throw Error(src + ": sprites: no sprite of kind \"floor\"; a map needs one");
}

}  // namespace isolux
