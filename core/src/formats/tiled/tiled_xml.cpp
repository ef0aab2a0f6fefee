// Reading TMX and TSX elements: tiled_xml.hpp.
#include "formats/tiled/tiled_xml.hpp"

#include <zlib.h>
#include <zstd.h>

#include <cmath>
#include <cstdlib>

#include "isolux/error.hpp"
#include "isolux/tiled.hpp"
#include "isolux/file_io.hpp"

namespace fs = std::filesystem;

namespace isolux {

std::string where_of(const fs::path& file, const pugi::xml_node& node) {
    std::string w = file.string() + ": <" + node.name();
    if (const auto id = node.attribute("id")) w += std::string(" id=\"") + id.value() + "\"";
    if (const auto name = node.attribute("name")) w += std::string(" name=\"") + name.value() + "\"";
    return w + ">";
}

[[noreturn]] void fail(const fs::path& file, const pugi::xml_node& node, const std::string& what) {
    throw Error(where_of(file, node) + ": " + what);
}

int int_attr(const fs::path& file, const pugi::xml_node& node, const char* name, int lo, int hi, std::optional<int> def) {
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
    const std::string text = read_text_file(path);
    pugi::xml_document doc;
    const pugi::xml_parse_result r = doc.load_buffer(text.data(), text.size());
    if (!r) throw Error(path.string() + ": malformed XML at byte " + std::to_string(r.offset) + " (" + r.description() + ")");
    return doc;
}

std::string property(const pugi::xml_node& node, const char* name) {
    for (pugi::xml_node p : node.child("properties").children("property"))
        if (std::string(p.attribute("name").value()) == name)
            return p.attribute("value") ? p.attribute("value").value() : p.text().get();
    return "";
}

namespace {

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

}  // namespace

namespace {

// One gid as TMX writes it in CSV and in XML <tile>s: a decimal of at most
// 32 bits (the flip flags included), read from `p` and moved past it; false
// when there is none or it is larger (truncated, it would draw another tile).
bool read_gid(const char*& p, std::uint32_t& gid) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(p, &end, 10);
    if (end == p || v > 0xFFFFFFFFull || *p == '-') return false;
    gid = std::uint32_t(v);
    p = end;
    return true;
}

// `count` gids from `holder` (a layer's <data>, or one of its <chunk>s) in the
// <data>'s encoding and compression.
std::vector<std::uint32_t> decode_gids(const fs::path& file, const pugi::xml_node& data, const pugi::xml_node& holder,
                                       std::size_t count, const std::string& size_text) {
    const std::string encoding = data.attribute("encoding").value(), compression = data.attribute("compression").value();
    std::vector<std::uint32_t> gids;
    gids.reserve(count);
    if (encoding == "csv") {
        if (!compression.empty()) fail(file, data, "CSV data cannot be compressed");
        const char* p = holder.text().get();
        while (*p) {
            while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t' || *p == ',') ++p;
            if (!*p) break;
            std::uint32_t gid = 0;
            if (!read_gid(p, gid)) fail(file, holder, "CSV data holds a value that is not a gid");
            gids.push_back(gid);
            if (gids.size() > count) break;
        }
    } else if (encoding == "base64") {
        std::string bytes = base64_decode(file, holder, holder.text().get());
        const std::size_t want = count * 4;
        if (compression == "zlib" || compression == "gzip") bytes = inflate_bounded(file, holder, bytes, want);
        else if (compression == "zstd") bytes = unzstd_bounded(file, holder, bytes, want);
        else if (!compression.empty()) fail(file, data, "compression \"" + compression + "\" is unknown (zlib, gzip, zstd)");
        if (bytes.size() != want) fail(file, holder, "holds " + std::to_string(bytes.size() / 4) + " tiles, " + size_text);
        for (std::size_t i = 0; i < count; ++i) {
            const auto* b = reinterpret_cast<const unsigned char*>(&bytes[i * 4]);
            gids.push_back(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24);
        }
    } else if (encoding.empty()) {
        for (pugi::xml_node t : holder.children("tile")) {
            std::uint32_t gid = 0;  // a <tile> without a gid is empty
            if (const pugi::xml_attribute a = t.attribute("gid")) {
                const char* p = a.value();
                if (!read_gid(p, gid) || *p != '\0')
                    fail(file, t, "gid \"" + std::string(a.value()) + "\" is not a gid (a whole number below 2^32)");
            }
            gids.push_back(gid);
            if (gids.size() > count) break;
        }
    } else {
        fail(file, data, "encoding \"" + encoding + "\" is unknown (csv, base64)");
    }
    if (gids.size() != count) fail(file, holder, "holds " + std::to_string(gids.size()) + " tiles, " + size_text);
    return gids;
}

}  // namespace

std::vector<std::uint32_t> layer_gids(const fs::path& file, const pugi::xml_node& layer, int w, int h) {
    const pugi::xml_node data = layer.child("data");
    if (!data) fail(file, layer, "has no <data>");
    if (data.child("chunk"))
        fail(file, data, "holds chunks, but the map is not infinite (infinite=\"1\" on the map reads them)");
    return decode_gids(file, data, data, std::size_t(w) * h,
                       "the layer is " + std::to_string(w) + "x" + std::to_string(h));
}

std::vector<std::uint32_t> chunked_layer_gids(const fs::path& file, const pugi::xml_node& layer, int x0, int y0, int w,
                                              int h) {
    const pugi::xml_node data = layer.child("data");
    if (!data) fail(file, layer, "has no <data>");
    std::vector<std::uint32_t> gids(std::size_t(w) * h, 0);
    // Each cell is held by one chunk at most (Tiled never writes two over one
    // cell), checked before a chunk is decoded: so a layer decodes at most
    // its w x h cells, however many chunks its file repeats.
    std::vector<bool> held(std::size_t(w) * h, false);
    for (pugi::xml_node ch : data.children("chunk")) {
        const int cx = int_attr(file, ch, "x", -1000000000, 1000000000), cy = int_attr(file, ch, "y", -1000000000, 1000000000);
        const int cw = int_attr(file, ch, "width", 1, max_tiled_side), chh = int_attr(file, ch, "height", 1, max_tiled_side);
        for (int y = 0; y < chh; ++y)
            for (int x = 0; x < cw; ++x) {
                const std::size_t at = std::size_t(cy + y - y0) * std::size_t(w) + std::size_t(cx + x - x0);
                if (held[at])
                    fail(file, ch, "overlaps an earlier chunk of its layer at tile (" + std::to_string(cx + x) + ", " +
                                       std::to_string(cy + y) + ")");
                held[at] = true;
            }
        const std::vector<std::uint32_t> part =
            decode_gids(file, data, ch, std::size_t(cw) * chh, "the chunk is " + std::to_string(cw) + "x" + std::to_string(chh));
        // Every chunk lies inside the bounds read_chunk_bounds took of them all.
        for (int y = 0; y < chh; ++y)
            for (int x = 0; x < cw; ++x)
                gids[std::size_t(cy + y - y0) * std::size_t(w) + std::size_t(cx + x - x0)] = part[std::size_t(y) * cw + x];
    }
    return gids;
}

}  // namespace isolux
