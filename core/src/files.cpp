// All file I/O of isolux::core: images through OpenImageIO, JSON through
// nlohmann-json. Errors name the file and the entry; writes are atomic.
#include "isolux/files.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <climits>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

#include "isolux/error.hpp"
#include "isolux/footprint.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace isolux {

namespace {

std::string quoted(const fs::path& p) { return p.string(); }

// Where a write to `path` lands: through a symlink, its target, so saving
// keeps the link (a bounded walk: a loop is an error).
fs::path write_target(const fs::path& path) {
    fs::path p = path;
    for (int hops = 0; hops < 40; ++hops) {
        std::error_code ec;
        if (!fs::is_symlink(fs::symlink_status(p, ec))) return p;
        const fs::path next = fs::read_symlink(p, ec);
        if (ec) throw Error(quoted(path) + ": cannot write: " + ec.message());
        p = next.is_absolute() ? next : p.parent_path() / next;
    }
    throw Error(quoted(path) + ": cannot write: too many levels of symbolic links");
}

// A sibling temporary path that keeps the extension (OpenImageIO picks the
// writer from it) and is unique per process and call.
fs::path temp_sibling(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path tmp = path;
    tmp.replace_filename("." + path.stem().string() + ".tmp" + std::to_string(::getpid()) + "_" +
                         std::to_string(counter++) + path.extension().string());
    return tmp;
}

// Temporary siblings of `path` left by a process that no longer runs (one
// killed mid-save): removed, so a killed session leaves no litter. Only our
// own pattern (".STEM.tmpPID_N.EXT") and only dead writers' files.
void remove_stale_temps(const fs::path& path) {
    const std::string prefix = "." + path.stem().string() + ".tmp";
    std::error_code ec;
    fs::directory_iterator it(path.parent_path().empty() ? fs::path(".") : path.parent_path(), ec);
    int seen = 0;
    for (; !ec && it != fs::directory_iterator() && ++seen < 100000; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const std::size_t digits = name.find('_', prefix.size());
        if (digits == std::string::npos || digits == prefix.size()) continue;
        const std::string pid_text = name.substr(prefix.size(), digits - prefix.size());
        if (pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9) continue;
        const long pid = std::stol(pid_text);
        if (pid == ::getpid() || ::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
        std::error_code rm;
        fs::remove(it->path(), rm);
    }
}

// Creates the temporary sibling (empty) so that a folder where nothing can be
// written says why (read-only file system, permission denied, no space)
// before any writer library hides the reason.
void create_temp(const fs::path& tmp, const fs::path& path) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0)
        throw Error(quoted(path) + ": cannot write: " + std::strerror(errno) + " (creating a temporary file beside it)");
    ::close(fd);
}

// Writes all of `data` to `fd`; false (errno set) on a short or failed write.
bool write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        data += n;
        size -= std::size_t(n);
    }
    return true;
}

// A file with other hard links keeps them: the finished temporary file's
// bytes are copied into it in place (a rename would leave the other names on
// the old contents). Space is reserved first, so a full disk fails before
// any old byte changes; then the old file takes the new bytes and its size.
// False when the file has one name (the caller renames) or the space cannot
// be had (the caller renames too: the other names keep the old contents).
bool copy_into_linked(const fs::path& tmp, const fs::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink < 2) return false;
    std::ifstream in(tmp, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) return false;
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return false;
    if (!bytes.empty() && ::posix_fallocate(fd, 0, off_t(bytes.size())) != 0) {
        ::close(fd);
        return false;
    }
    const bool ok = write_all(fd, bytes.data(), bytes.size()) && ::ftruncate(fd, off_t(bytes.size())) == 0 &&
                    ::fsync(fd) == 0;
    const int err = errno;
    ::close(fd);
    if (!ok)  // the new contents stay in the temporary file
        throw Error(quoted(path) + ": cannot write in place: " + std::strerror(err) + "; the new contents are in " +
                    quoted(tmp));
    std::error_code ec;
    fs::remove(tmp, ec);
    return true;
}

// Replaces `path` by the finished temporary file, keeping the old file's
// permissions (a 600 file stays 600) and its hard links.
void commit_temp(const fs::path& tmp, const fs::path& path) {
    if (copy_into_linked(tmp, path)) {
        remove_stale_temps(path);
        return;
    }
    std::error_code ec;
    const fs::file_status old = fs::status(path, ec);
    if (!ec && fs::is_regular_file(old)) fs::permissions(tmp, old.permissions(), ec);
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error(quoted(path) + ": cannot write: " + ec.message());
    }
    remove_stale_temps(path);
}

}  // namespace

void check_input_file(const fs::path& path, std::uintmax_t max_bytes) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);  // follows links; a loop is an error, not an exception
    if (ec) {
        if (ec == std::errc::no_such_file_or_directory) throw Error(quoted(path) + ": file not found");
        throw Error(quoted(path) + ": cannot read: " + ec.message());
    }
    switch (st.type()) {
        case fs::file_type::regular: break;
        case fs::file_type::directory: throw Error(quoted(path) + ": is a folder, not a file");
        case fs::file_type::fifo: throw Error(quoted(path) + ": is a FIFO (a pipe), not a file");
        case fs::file_type::character:
        case fs::file_type::block: throw Error(quoted(path) + ": is a device, not a file");
        case fs::file_type::socket: throw Error(quoted(path) + ": is a socket, not a file");
        default: throw Error(quoted(path) + ": is not a regular file");
    }
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw Error(quoted(path) + ": cannot read: " + ec.message());
    if (size > max_bytes)
        throw Error(quoted(path) + ": is " + std::to_string(size >> 20) + " MB, over the " +
                    std::to_string(max_bytes >> 20) + " MB isolux reads");
}

namespace {

// libpng reports a broken file on stderr by itself before OpenImageIO returns
// the same error: while an image is read, stderr goes nowhere, so a bad image
// gives the one line that names it. (Reads happen on the calling thread.)
struct QuietStderr {
    int saved = -1;
    QuietStderr() {
        std::fflush(stderr);
        saved = ::dup(2);
        const int null = ::open("/dev/null", O_WRONLY);
        if (null >= 0) ::dup2(null, 2), ::close(null);
    }
    ~QuietStderr() {
        if (saved < 0) return;
        std::fflush(stderr);
        ::dup2(saved, 2);
        ::close(saved);
    }
};

// One line: a library's multi-line message joined.
std::string one_line(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ';';
    while (!s.empty() && (s.back() == ';' || s.back() == ' ')) s.pop_back();
    return s;
}

}  // namespace

// ---------------------------------------------------------------- images

Image load_image(const fs::path& path) {
    check_input_file(path, max_image_file_bytes);
    QuietStderr quiet;
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // keep PNG's straight alpha as stored
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in) throw Error(quoted(path) + ": not a readable image (" + one_line(OIIO::geterror()) + ")");
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.width > max_image_side || spec.height > max_image_side)
        throw Error(quoted(path) + ": image size " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + " is outside [1, " + std::to_string(max_image_side) + "]");
    // Refused from the header, before any decoding: a tiny file may declare a huge image.
    if (std::int64_t(spec.width) * spec.height > max_image_pixels)
        throw Error(quoted(path) + ": image size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    " is over the " + std::to_string(max_image_pixels >> 20) + " megapixels isolux reads");
    const int nch = spec.nchannels;
    if (nch < 1 || nch > 16) throw Error(quoted(path) + ": unsupported channel count " + std::to_string(nch));
    // Read at 16 bits when the source has more than 8, so that alpha keeps
    // its precision for the opacity threshold.
    const bool deep = spec.format.size() > 1;
    const std::size_t n = std::size_t(spec.width) * spec.height;
    // 8-bit sources are read at 8 bits (half the memory of 16).
    std::vector<std::uint16_t> wide;
    std::vector<std::uint8_t> narrow;
    const bool ok = deep ? (wide.resize(n * nch), in->read_image(0, 0, 0, nch, OIIO::TypeDesc::UINT16, wide.data()))
                         : (narrow.resize(n * nch), in->read_image(0, 0, 0, nch, OIIO::TypeDesc::UINT8, narrow.data()));
    if (!ok) throw Error(quoted(path) + ": corrupt image data (" + one_line(in->geterror()) + ")");
    in->close();
    Image out(spec.width, spec.height);
    const int alpha = spec.alpha_channel >= 0 ? spec.alpha_channel : (nch == 2 || nch >= 4 ? nch - 1 : -1);
    if (deep && alpha >= 0) out.alpha16.resize(n);
    // 16 to 8 bits exactly as OpenImageIO converts: round(v * 255 / 65535).
    auto at8 = [&](std::size_t i, int k) {
        return deep ? std::uint8_t((wide[i * nch + k] * 255u + 32767u) / 65535u) : narrow[i * nch + k];
    };
    for (std::size_t i = 0; i < n; ++i) {
        std::uint8_t* d = &out.rgba[i * 4];
        if (nch <= 2) {
            d[0] = d[1] = d[2] = at8(i, 0);  // grey
        } else {
            d[0] = at8(i, 0), d[1] = at8(i, 1), d[2] = at8(i, 2);
        }
        d[3] = alpha >= 0 ? at8(i, alpha) : 255;
        if (!out.alpha16.empty()) out.alpha16[i] = wide[i * nch + alpha];
    }
    return out;
}

void check_image_output(const fs::path& link) {
    const fs::path path = write_target(link);
    std::error_code dir_ec;
    if (fs::is_directory(path, dir_ec)) throw Error(quoted(path) + ": is a folder: name an image file (.png or .exr)");
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(c));
    if (ext != ".exr" && ext != ".png") throw Error(quoted(path) + ": unsupported image extension (use .png or .exr)");
}

void save_image(const fs::path& link, const Image& image) {
    check_image_output(link);
    const fs::path path = write_target(link);
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(c));
    const bool exr = ext == ".exr";
    auto out = OIIO::ImageOutput::create(exr ? "openexr" : "png");
    if (!out) throw Error(quoted(path) + ": no image writer (" + OIIO::geterror() + ")");
    OIIO::ImageSpec spec(image.width, image.height, 4, exr ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    fs::path tmp = temp_sibling(path);
    create_temp(tmp, path);
    if (!out->open(tmp.string(), spec)) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw Error(quoted(path) + ": cannot write (" + out->geterror() + ")");
    }
    bool ok = out->write_image(OIIO::TypeDesc::UINT8, image.rgba.data());
    ok = out->close() && ok;
    std::string why = ok ? "" : out->geterror();
    if (ok) {
        // OpenImageIO's PNG writer does not report a full disk: read the
        // file back whole before it replaces the old one.
        auto in = OIIO::ImageInput::open(tmp.string());
        std::vector<std::uint8_t> back(std::size_t(image.width) * image.height * 4);
        ok = in && in->spec().width == image.width && in->spec().height == image.height &&
             in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, back.data());
        if (in) in->close();
        if (!ok) why = "the written file does not read back whole: is the disk full?";
    }
    if (!ok) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw Error(quoted(path) + ": cannot write (" + why + "); the old file is kept");
    }
    commit_temp(tmp, path);
}

std::vector<std::uint16_t> load_gray16(const fs::path& path, int width, int height) {
    check_input_file(path, max_image_file_bytes);
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(quoted(path) + ": not a readable image (" + OIIO::geterror() + ")");
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width != width || spec.height != height)
        throw Error(quoted(path) + ": is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    ", the sprite is " + std::to_string(width) + "x" + std::to_string(height));
    std::vector<std::uint16_t> values(std::size_t(width) * height);
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, values.data()))
        throw Error(quoted(path) + ": corrupt image data (" + in->geterror() + ")");
    return values;
}

void save_gray16(const fs::path& link, int width, int height, const std::vector<std::uint16_t>& values) {
    const fs::path path = write_target(link);
    auto out = OIIO::ImageOutput::create("png");
    if (!out) throw Error(quoted(path) + ": no PNG writer (" + OIIO::geterror() + ")");
    OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::UINT16);
    fs::path tmp = temp_sibling(path);
    create_temp(tmp, path);
    bool ok = out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::UINT16, values.data());
    ok = out->close() && ok;
    if (ok) {  // read back whole, as save_image does (the PNG writer misses a full disk)
        auto in = OIIO::ImageInput::open(tmp.string());
        std::vector<std::uint16_t> back(values.size());
        ok = in && in->spec().width == width && in->spec().height == height &&
             in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, back.data()) && back == values;
        if (in) in->close();
    }
    if (!ok) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw Error(quoted(path) + ": cannot write (the written file does not read back whole: is the disk full?); "
                    "the old file is kept");
    }
    commit_temp(tmp, path);
}

void write_file_atomic(const fs::path& link, std::string_view contents) {
    const fs::path path = write_target(link);
    fs::path tmp = temp_sibling(path);
    create_temp(tmp, path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    bool ok = fd >= 0 && write_all(fd, contents.data(), contents.size()) && ::fsync(fd) == 0;
    int err = ok ? 0 : errno;
    if (fd >= 0 && ::close(fd) != 0 && ok) ok = false, err = errno;
    if (!ok) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw Error(quoted(path) + ": cannot write: " + std::strerror(err) + "; the old file is kept");
    }
    commit_temp(tmp, path);
}

// ---------------------------------------------------------------- JSON helpers

namespace {

std::string read_text(const fs::path& path) {
    check_input_file(path, max_text_file_bytes);
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(quoted(path) + ": cannot open");
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

json parse_json(std::string_view text, std::string_view source) {
    try {
        return json::parse(text);
    } catch (const json::parse_error& e) {
        throw Error(std::string(source) + ": malformed JSON at byte " + std::to_string(e.byte));
    } catch (const json::exception& e) {
        // e.g. a number beyond the range of a double (out_of_range 406)
        throw Error(std::string(source) + ": malformed JSON (" + e.what() + ")");
    }
}

// Field access that names the file and the field in every error.
struct Fields {
    const json& obj;
    std::string where;  // "file.json" or "file.json: sprites[2] (\"oak\")"

    [[noreturn]] void fail(const std::string& field, const std::string& what) const {
        throw Error(where + ": " + field + " " + what);
    }
    bool has(const char* k) const { return obj.contains(k) && !obj[k].is_null(); }

    long long integer(const char* k, long long lo, long long hi) const {
        const json& v = obj[k];
        if (!v.is_number_integer()) fail(k, "must be an integer, got " + std::string(v.type_name()));
        long long x = v.is_number_unsigned() ? (long long)std::min<unsigned long long>(v.get<unsigned long long>(), (unsigned long long)LLONG_MAX) : v.get<long long>();
        if (x < lo || x > hi)
            fail(k, "= " + std::to_string(x) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return x;
    }
    double real(const char* k) const {
        const json& v = obj[k];
        if (!v.is_number()) fail(k, "must be a number, got " + std::string(v.type_name()));
        double x = v.get<double>();
        if (!std::isfinite(x)) fail(k, "must be finite");
        return x;
    }
    std::string text(const char* k) const {
        const json& v = obj[k];
        if (!v.is_string()) fail(k, "must be a string, got " + std::string(v.type_name()));
        return v.get<std::string>();
    }
    bool boolean(const char* k) const {
        const json& v = obj[k];
        if (!v.is_boolean()) fail(k, "must be true or false, got " + std::string(v.type_name()));
        return v.get<bool>();
    }
    void warn_unknown(std::initializer_list<const char*> known, std::vector<std::string>* warnings) const {
        if (!warnings) return;
        std::vector<std::string> unknown;
        for (auto it = obj.begin(); it != obj.end(); ++it) {  // nlohmann's object is a std::map: ordered
            bool ok = false;
            for (const char* k : known) ok = ok || it.key() == k;
            if (!ok) unknown.push_back(it.key());
        }
        report_unknown(where, unknown, warnings);
    }
    // The first few unknown fields by name, then how many more: a file with
    // 200000 of them gives 11 lines, not 200000.
    static void report_unknown(const std::string& where, const std::vector<std::string>& unknown,
                               std::vector<std::string>* warnings) {
        constexpr std::size_t named = 10;
        for (std::size_t i = 0; i < unknown.size() && i < named; ++i)
            warnings->push_back(where + ": unknown field \"" + unknown[i] + "\" ignored");
        if (unknown.size() > named)
            warnings->push_back(where + ": and " + std::to_string(unknown.size() - named) + " more unknown fields ignored");
    }
};

void check_object(const json& j, const std::string& where) {
    if (!j.is_object()) throw Error(where + ": must be a JSON object, got " + std::string(j.type_name()));
}

void check_schema(const Fields& f, std::vector<std::string>* warnings, int newest = schema_version) {
    if (!f.has("schema_version")) {
        if (warnings) warnings->push_back(f.where + ": no schema_version; reading as version 1");
        return;
    }
    long long v = f.integer("schema_version", 1, 1000000);
    if (v > newest)
        f.fail("schema_version", "= " + std::to_string(v) + " is newer than this isolux reads (" +
                                     std::to_string(newest) + ")");
}

// Reads every parameter the object holds, by the table; the rest stay at
// their defaults.
Params params_from(const Fields& f) {
    Params p;
    for (const ParamInfo& info : param_table()) {
        const char* k = info.name;
        if (!f.has(k)) continue;
        double v = 0;
        switch (info.type) {
            case ParamType::integer: v = double(f.integer(k, (long long)info.min, (long long)info.max)); break;
            case ParamType::real: v = f.real(k); break;
            case ParamType::choice: v = parse_param(info, f.text(k), f.where); break;
            case ParamType::boolean: v = f.boolean(k) ? 1 : 0; break;
        }
        check_param(info, v, f.where);
        info.set(p, v);
    }
    return p;
}

json params_json(const Params& p) {
    json j = json::object();
    for (const ParamInfo& info : param_table()) {
        const double v = info.get(p);
        switch (info.type) {
            case ParamType::integer: j[info.name] = (long long)v; break;
            case ParamType::real: j[info.name] = v; break;
            case ParamType::choice: j[info.name] = format_param(info, v); break;
            case ParamType::boolean: j[info.name] = v != 0; break;
        }
    }
    return j;
}

// Warns about every field of a preset object that is neither a parameter nor
// one of `extra`.
void warn_unknown_params(const Fields& f, std::initializer_list<const char*> extra, std::vector<std::string>* warnings) {
    if (!warnings) return;
    std::vector<std::string> unknown;
    for (auto it = f.obj.begin(); it != f.obj.end(); ++it) {  // nlohmann's object is a std::map: ordered
        bool known = find_param(it.key()) != nullptr;
        for (const char* k : extra) known = known || it.key() == k;
        if (!known) unknown.push_back(it.key());
    }
    Fields::report_unknown(f.where, unknown, warnings);
}

// A sprite's solids: [{"kind": "box", "min": [x,y,z], "max": [x,y,z]},
// {"kind": "cylinder"|"cone", "base": [x,y,z], "radius": r, "height": h},
// {"kind": "ellipsoid", "center": [x,y,z], "radii": [x,y,z]}].
std::vector<Solid> shape_from(const json& arr, const std::string& where) {
    if (!arr.is_array()) throw Error(where + ": must be an array of solids");
    if (arr.size() > 1000) throw Error(where + ": holds more than 1000 solids");
    std::vector<Solid> out;
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string at = where + "[" + std::to_string(i) + "]";
        check_object(arr[i], at);
        Fields f{arr[i], at};
        auto vec = [&](const char* k) {
            if (!f.has(k)) f.fail(k, "is required");
            const json& v = arr[i][k];
            if (!v.is_array() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_number(); }))
                f.fail(k, "must be [x, y, z] numbers");
            Vec3 r{v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
            if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z) || std::abs(r.x) > 1e6 ||
                std::abs(r.y) > 1e6 || std::abs(r.z) > 1e6)
                f.fail(k, "must be finite numbers within ±1e6");
            return r;
        };
        auto size = [&](const char* k) {
            if (!f.has(k)) f.fail(k, "is required");
            const double v = f.real(k);
            if (v < 0 || v > 1e6) f.fail(k, "= " + std::to_string(v) + " must be in [0, 1e6]");
            return v;
        };
        if (!f.has("kind")) f.fail("kind", "is required (box, cylinder, cone or ellipsoid)");
        const std::string kind = f.text("kind");
        Solid s;
        if (kind == "box") {
            s.kind = SolidKind::box;
            s.a = vec("min");
            s.b = vec("max");
            if (s.b.x < s.a.x || s.b.y < s.a.y || s.b.z < s.a.z) f.fail("max", "must not be below min (a negative size)");
        } else if (kind == "cylinder" || kind == "cone") {
            s.kind = kind == "cone" ? SolidKind::cone : SolidKind::cylinder;
            s.a = vec("base");
            const double r = size("radius");
            s.b = {r, r, size("height")};
        } else if (kind == "ellipsoid") {
            s.kind = SolidKind::ellipsoid;
            s.a = vec("center");
            s.b = vec("radii");
            if (s.b.x < 0 || s.b.y < 0 || s.b.z < 0) f.fail("radii", "must not be negative");
        } else {
            f.fail("kind", "\"" + kind + "\" is unknown (use box, cylinder, cone or ellipsoid)");
        }
        out.push_back(s);
    }
    return out;
}

// "auto" | "paper" | "none" | {"mode": ..., "run": [x, y, length],
// "polygon": [[x, y], ...], "shadow_alpha": a, "shadow_luminance": l,
// "ground_tolerance": t}; a run or polygon without a mode sets it.
FootprintSpec footprint_from(const json& j, const std::string& where) {
    FootprintSpec spec;
    auto mode_of = [&](const std::string& m) {
        for (FootprintMode k : {FootprintMode::automatic, FootprintMode::paper, FootprintMode::none, FootprintMode::run,
                                FootprintMode::polygon})
            if (m == to_string(k)) return k;
        throw Error(where + ": \"" + m + "\" is not one of auto, paper, none, run, polygon");
    };
    if (j.is_string()) {
        spec.mode = mode_of(j.get<std::string>());
        if (spec.mode == FootprintMode::run || spec.mode == FootprintMode::polygon)
            throw Error(where + ": " + j.get<std::string>() + " needs an object with its \"" + j.get<std::string>() + "\"");
        return spec;
    }
    check_object(j, where);
    Fields f{j, where};
    if (f.has("mode")) spec.mode = mode_of(f.text("mode"));
    auto unit = [&](const char* k, double& v) {
        if (!f.has(k)) return;
        v = f.real(k);
        if (v < 0 || v > 1) f.fail(k, "must be in [0, 1]");
    };
    unit("shadow_alpha", spec.shadow_alpha);
    unit("shadow_luminance", spec.shadow_luminance);
    unit("ground_tolerance", spec.ground_tolerance);
    auto coord = [&](const json& v, const char* k) {
        if (!v.is_number_integer()) f.fail(k, "must hold integers");
        const long long x = v.get<long long>();
        if (x < -100000 || x > 100000) f.fail(k, "holds a coordinate beyond ±100000");
        return int(x);
    };
    if (f.has("run")) {
        const json& r = j["run"];
        if (!r.is_array() || r.size() != 3) f.fail("run", "must be [x, y, length]");
        spec.run_x = coord(r[0], "run");
        spec.run_y = coord(r[1], "run");
        spec.run_length = coord(r[2], "run");
        if (spec.run_length < 1) f.fail("run", "length must be at least 1");
        if (!spec.mode) spec.mode = FootprintMode::run;
    }
    if (f.has("polygon")) {
        const json& poly = j["polygon"];
        if (!poly.is_array() || poly.size() < 3 || poly.size() > 1000) f.fail("polygon", "must be 3 to 1000 [x, y] points");
        for (const json& pt : poly) {
            if (!pt.is_array() || pt.size() != 2) f.fail("polygon", "must be [x, y] points");
            spec.polygon.push_back({coord(pt[0], "polygon"), coord(pt[1], "polygon")});
        }
        if (!spec.mode) spec.mode = FootprintMode::polygon;
    }
    if (spec.mode == FootprintMode::run && spec.run_length < 1) f.fail("run", "is required for mode run");
    if (spec.mode == FootprintMode::polygon && spec.polygon.empty()) f.fail("polygon", "is required for mode polygon");
    return spec;
}

json shape_json(const std::vector<Solid>& shape) {
    json arr = json::array();
    auto v = [](Vec3 p) { return json::array({p.x, p.y, p.z}); };
    for (const Solid& s : shape) {
        switch (s.kind) {
            case SolidKind::box: arr.push_back({{"kind", "box"}, {"min", v(s.a)}, {"max", v(s.b)}}); break;
            case SolidKind::cylinder:
            case SolidKind::cone:
                arr.push_back({{"kind", std::string(to_string(s.kind))}, {"base", v(s.a)}, {"radius", s.b.x}, {"height", s.b.z}});
                break;
            case SolidKind::ellipsoid: arr.push_back({{"kind", "ellipsoid"}, {"center", v(s.a)}, {"radii", v(s.b)}}); break;
        }
    }
    return arr;
}

std::string hex_color(const Light& l) {
    static const char* d = "0123456789abcdef";
    std::string s;
    for (std::uint8_t c : {l.r, l.g, l.b}) {
        s += d[c >> 4];
        s += d[c & 15];
    }
    return s;
}

}  // namespace

bool parse_hex_color(std::string_view s, std::uint8_t& r, std::uint8_t& g, std::uint8_t& b) {
    if (!s.empty() && s[0] == '#') s.remove_prefix(1);
    if (s.size() != 6) return false;
    unsigned v[6];
    for (int i = 0; i < 6; ++i) {
        char c = s[i];
        if (c >= '0' && c <= '9') v[i] = unsigned(c - '0');
        else if (c >= 'a' && c <= 'f') v[i] = unsigned(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F') v[i] = unsigned(c - 'A' + 10);
        else return false;
    }
    r = std::uint8_t(v[0] * 16 + v[1]);
    g = std::uint8_t(v[2] * 16 + v[3]);
    b = std::uint8_t(v[4] * 16 + v[5]);
    return true;
}

// ---------------------------------------------------------------- presets

Params preset_from_json(std::string_view text, std::string_view source, std::vector<std::string>* warnings) {
    json j = parse_json(text, source);
    check_object(j, std::string(source));
    Fields f{j, std::string(source)};
    check_schema(f, warnings);
    warn_unknown_params(f, {"schema_version", "name"}, warnings);
    return params_from(f);
}

std::string preset_to_json(const Params& p) {
    json j = params_json(p);
    j["schema_version"] = schema_version;
    return j.dump(2) + "\n";
}

Params load_preset(const fs::path& path, std::vector<std::string>* warnings) {
    return preset_from_json(read_text(path), path.string(), warnings);
}

void save_preset(const fs::path& path, const Params& p) {
    validate(p, path.string());
    write_file_atomic(path, preset_to_json(p));
}

// ---------------------------------------------------------------- scenes

namespace {

// "edits": [{"tile": [x, y], "floor": "water"}, {"tile": [x, y], "overlays": ["oak"]}]
std::vector<TileEdit> edits_from(const json& arr, const Fields& scene) {
    if (!arr.is_array()) scene.fail("edits", "must be an array");
    // A tile holds one edit that matters; more than a 1024 x 1024 map's worth is not a level.
    constexpr std::size_t max_edits = std::size_t(max_map_side) * max_map_side;
    if (arr.size() > max_edits) scene.fail("edits", "holds more than " + std::to_string(max_edits) + " entries");
    std::vector<TileEdit> out;
    out.reserve(arr.size());
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string where = scene.where + ": edits[" + std::to_string(i) + "]";
        check_object(arr[i], where);
        Fields ef{arr[i], where};
        for (auto it = arr[i].begin(); it != arr[i].end(); ++it)
            if (it.key() != "tile" && it.key() != "floor" && it.key() != "overlays")
                ef.fail("\"" + it.key() + "\"", "is not a field of an edit (tile, floor, overlays)");
        if (!ef.has("tile")) ef.fail("tile", "is required: [column, row]");
        const json& t = arr[i]["tile"];
        if (!t.is_array() || t.size() != 2 || !t[0].is_number_integer() || !t[1].is_number_integer())
            ef.fail("tile", "must be [column, row], two integers");
        TileEdit e;
        auto coord = [&](const json& v) {
            const long long x = v.is_number_unsigned()
                                    ? (long long)std::min<unsigned long long>(v.get<unsigned long long>(), 1ull << 40)
                                    : v.get<long long>();
            if (x < -(1 << 30) || x > (1 << 30)) ef.fail("tile", "= " + std::to_string(x) + " is out of range");
            return int(x);
        };
        e.col = coord(t[0]);
        e.row = coord(t[1]);
        if (ef.has("floor")) e.floor = ef.text("floor");
        if (ef.has("overlays")) {
            const json& o = arr[i]["overlays"];
            if (!o.is_array()) ef.fail("overlays", "must be an array of sprite names");
            if (o.size() > 3) ef.fail("overlays", "holds " + std::to_string(o.size()) + " sprites; a tile holds at most 3");
            e.overlays.emplace();
            for (const json& n : o) {
                if (!n.is_string()) ef.fail("overlays", "must hold sprite names (strings)");
                e.overlays->push_back(n.get<std::string>());
            }
        }
        if (!e.floor && !e.overlays) ef.fail("floor, overlays", "are both missing: an edit sets at least one");
        out.push_back(std::move(e));
    }
    return out;
}

json edits_json(const std::vector<TileEdit>& edits) {
    json arr = json::array();
    for (const TileEdit& e : edits) {
        json o{{"tile", {e.col, e.row}}};
        if (e.floor) o["floor"] = *e.floor;
        if (e.overlays) o["overlays"] = *e.overlays;
        arr.push_back(o);
    }
    return arr;
}

}  // namespace

Scene scene_from_json(std::string_view text, std::string_view source, std::vector<std::string>* warnings) {
    json j = parse_json(text, source);
    const std::string src(source);
    check_object(j, src);
    Fields f{j, src};
    check_schema(f, warnings, scene_schema_version);
    f.warn_unknown(
        {"schema_version", "seed", "width", "height", "layout", "tileset", "map", "preset", "lights", "camera", "edits"},
        warnings);
    Scene s;
    if (f.has("seed")) s.seed = f.text("seed");
    if (f.has("width")) s.width = int(f.integer("width", 1, max_map_side));
    if (f.has("height")) s.height = int(f.integer("height", 1, max_map_side));
    if (f.has("layout")) s.layout = parse_layout(f.text("layout"), src + ": layout");
    if (f.has("tileset")) s.tileset = f.text("tileset");
    if (f.has("map")) s.map = f.text("map");
    if (f.has("preset")) {
        const json& p = j["preset"];
        if (p.is_string()) {
            s.params = builtin_preset(p.get<std::string>());
        } else {
            check_object(p, src + ": preset");
            Fields pf{p, src + ": preset"};
            warn_unknown_params(pf, {"name"}, warnings);
            s.params = params_from(pf);
        }
    }
    if (f.has("lights")) {
        const json& arr = j["lights"];
        if (!arr.is_array()) f.fail("lights", "must be an array");
        if (arr.size() > 100000) f.fail("lights", "holds more than 100000 lights");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string where = src + ": lights[" + std::to_string(i) + "]";
            check_object(arr[i], where);
            Fields lf{arr[i], where};
            lf.warn_unknown({"x", "y", "a", "b", "color", "intensity", "height", "name", "hidden", "locked"}, warnings);
            Light l;
            if (!lf.has("x") || !lf.has("y")) lf.fail("x, y", "are required");
            l.x = lf.real("x");
            l.y = lf.real("y");
            if (std::abs(l.x) > 1e9 || std::abs(l.y) > 1e9) lf.fail("x, y", "must be within ±1e9 pixels");
            if (lf.has("a")) l.area_a = int(lf.integer("a", 0, max_area));
            if (lf.has("b")) l.area_b = int(lf.integer("b", 0, max_area));
            if (lf.has("color") && !parse_hex_color(lf.text("color"), l.r, l.g, l.b))
                lf.fail("color", "must be RRGGBB hex, got \"" + lf.text("color") + "\"");
            if (lf.has("intensity")) {
                l.intensity = lf.real("intensity");
                if (l.intensity < 0 || l.intensity > 1000) lf.fail("intensity", "must be in [0, 1000]");
            }
            if (lf.has("height")) {
                const ParamInfo& range = *find_param("light_height");
                l.height = lf.real("height");
                if (*l.height < range.min || *l.height > range.max)
                    lf.fail("height", "must be in " + param_range_text(range) + " pixels");
            }
            if (lf.has("name")) l.name = lf.text("name");
            if (lf.has("hidden")) l.hidden = lf.boolean("hidden");
            if (lf.has("locked")) l.locked = lf.boolean("locked");
            s.lights.push_back(l);
        }
    }
    if (f.has("camera")) {
        const json& c = j["camera"];
        check_object(c, src + ": camera");
        Fields cf{c, src + ": camera"};
        cf.warn_unknown({"x", "y", "width", "height"}, warnings);
        if (cf.has("x")) s.camera.x = cf.real("x");
        if (cf.has("y")) s.camera.y = cf.real("y");
        if (cf.has("width")) s.camera.width = int(cf.integer("width", 0, max_image_side));
        if (cf.has("height")) s.camera.height = int(cf.integer("height", 0, max_image_side));
    }
    if (f.has("edits")) s.edits = edits_from(j["edits"], f);
    return s;
}

std::string scene_to_json(const Scene& s) {
    json lights = json::array();
    for (const Light& l : s.lights) {
        json o{{"x", l.x}, {"y", l.y}, {"color", hex_color(l)}, {"intensity", l.intensity}};
        if (l.area_a) o["a"] = *l.area_a;
        if (l.area_b) o["b"] = *l.area_b;
        if (l.height) o["height"] = *l.height;
        if (!l.name.empty()) o["name"] = l.name;
        if (l.hidden) o["hidden"] = true;
        if (l.locked) o["locked"] = true;
        lights.push_back(o);
    }
    json j{{"schema_version", scene_schema_version},
           {"seed", s.seed},
           {"width", s.width},
           {"height", s.height},
           {"layout", std::string(to_string(s.layout))},
           {"tileset", s.tileset},
           {"preset", params_json(s.params)},
           {"lights", lights},
           {"camera", {{"x", s.camera.x}, {"y", s.camera.y}, {"width", s.camera.width}, {"height", s.camera.height}}}};
    if (!s.edits.empty()) j["edits"] = edits_json(s.edits);
    if (!s.map.empty()) j["map"] = s.map;
    return j.dump(2) + "\n";
}

Scene load_scene(const fs::path& path, std::vector<std::string>* warnings) {
    Scene s = scene_from_json(read_text(path), path.string(), warnings);
    if (!s.tileset.empty() && fs::path(s.tileset).is_relative())
        s.tileset = (path.parent_path() / s.tileset).lexically_normal().string();
    if (!s.map.empty() && fs::path(s.map).is_relative())
        s.map = (path.parent_path() / s.map).lexically_normal().string();
    return s;
}

void save_scene(const fs::path& path, const Scene& scene) {
    validate(scene.params, path.string());
    Scene copy = scene;
    for (std::string* file : {&copy.tileset, &copy.map}) {
        if (file->empty()) continue;
        fs::path base = fs::absolute(path).parent_path();
        fs::path rel = fs::absolute(*file).lexically_relative(base);
        if (!rel.empty()) *file = rel.string();
    }
    write_file_atomic(path, scene_to_json(copy));
}

// ---------------------------------------------------------------- tilesets

Tileset load_tileset(const fs::path& manifest) {
    const std::string src = manifest.string();
    json j = parse_json(read_text(manifest), src);
    check_object(j, src);
    Fields f{j, src};
    check_schema(f, nullptr);
    Tileset ts;
    ts.source = src;
    if (f.has("tile")) {
        const json& t = j["tile"];
        check_object(t, src + ": tile");
        Fields tf{t, src + ": tile"};
        if (tf.has("width")) ts.tile_width = int(tf.integer("width", 2, 4096));
        if (tf.has("height")) ts.tile_height = int(tf.integer("height", 2, 4096));
    }
    if (!f.has("sprites") || !j["sprites"].is_array()) f.fail("sprites", "must be an array of sprites");
    const json& arr = j["sprites"];
    std::map<fs::path, Image> sheets;  // ordered: loading order does not depend on hashing
    for (std::size_t i = 0; i < arr.size(); ++i) {
        std::string where = src + ": sprites[" + std::to_string(i) + "]";
        check_object(arr[i], where);
        Fields sf{arr[i], where};
        Sprite s;
        if (!sf.has("name")) sf.fail("name", "is required");
        s.name = sf.text("name");
        where += " (\"" + s.name + "\")";
        sf.where = where;
        if (!sf.has("image")) sf.fail("image", "is required");
        fs::path image_path = manifest.parent_path() / sf.text("image");
        auto it = sheets.find(image_path);
        if (it == sheets.end()) {
            try {
                it = sheets.emplace(image_path, load_image(image_path)).first;
            } catch (const Error& e) {
                throw Error(where + ": image: " + e.what());
            }
        }
        const Image& sheet = it->second;
        Rect rect{0, 0, sheet.width, sheet.height};
        if (sf.has("rect")) {
            const json& r = arr[i]["rect"];
            if (!r.is_array() || r.size() != 4 || !std::all_of(r.begin(), r.end(), [](const json& v) { return v.is_number_integer(); }))
                sf.fail("rect", "must be [x, y, w, h] integers");
            // Read wide and checked in 64 bits: no value wraps, no sum overflows.
            std::int64_t v[4];
            for (int k = 0; k < 4; ++k) {
                if (r[std::size_t(k)].is_number_unsigned() && r[std::size_t(k)].get<std::uint64_t>() > std::uint64_t(INT64_MAX))
                    sf.fail("rect", "holds a value beyond 64 bits");
                v[k] = r[std::size_t(k)].get<std::int64_t>();
            }
            if (v[2] <= 0 || v[3] <= 0) sf.fail("rect", "has zero size: zero-size sprite");
            if (v[0] < 0 || v[1] < 0 || v[0] > sheet.width || v[1] > sheet.height || v[2] > sheet.width ||
                v[3] > sheet.height || v[0] + v[2] > sheet.width || v[1] + v[3] > sheet.height)
                sf.fail("rect", "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) +
                                    ", " + std::to_string(v[3]) + "] lies outside " + image_path.filename().string() + " (" +
                                    std::to_string(sheet.width) + "x" + std::to_string(sheet.height) + ")");
            rect = {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
            if (rect.x + rect.w > sheet.width || rect.y + rect.h > sheet.height)
                sf.fail("rect", "[" + std::to_string(rect.x) + ", " + std::to_string(rect.y) + ", " +
                                    std::to_string(rect.w) + ", " + std::to_string(rect.h) + "] lies outside " +
                                    image_path.filename().string() + " (" + std::to_string(sheet.width) + "x" +
                                    std::to_string(sheet.height) + ")");
        }
        s.image = Image(rect.w, rect.h);
        for (int y = 0; y < rect.h; ++y)
            std::copy_n(sheet.at(rect.x, rect.y + y), std::size_t(rect.w) * 4, s.image.at(0, y));
        if (!sheet.alpha16.empty()) {
            s.image.alpha16.resize(std::size_t(rect.w) * rect.h);
            for (int y = 0; y < rect.h; ++y)
                std::copy_n(&sheet.alpha16[std::size_t(rect.y + y) * sheet.width + rect.x], std::size_t(rect.w),
                            &s.image.alpha16[std::size_t(y) * rect.w]);
        }
        if (!sf.has("kind")) sf.fail("kind", "is required (floor or overlay)");
        std::string kind = sf.text("kind");
        if (kind == "floor") s.kind = SpriteKind::floor;
        else if (kind == "overlay") s.kind = SpriteKind::overlay;
        else sf.fail("kind", "\"" + kind + "\" is unknown (use floor or overlay)");
        if (sf.has("anchor")) {
            const json& a = arr[i]["anchor"];
            if (!a.is_array() || a.size() != 2 || !a[0].is_number_integer() || !a[1].is_number_integer())
                sf.fail("anchor", "must be [x, y] integers");
            const bool wide = (a[0].is_number_unsigned() && a[0].get<std::uint64_t>() > 100000) ||
                              (a[1].is_number_unsigned() && a[1].get<std::uint64_t>() > 100000);
            const std::int64_t ax = wide ? 0 : a[0].get<std::int64_t>(), ay = wide ? 0 : a[1].get<std::int64_t>();
            if (wide || ax < -100000 || ax > 100000 || ay < -100000 || ay > 100000)
                sf.fail("anchor", "is too far off the sprite (each coordinate within ±100000)");
            s.anchor_x = int(ax);
            s.anchor_y = int(ay);
        } else if (s.kind == SpriteKind::floor) {
            s.anchor_x = rect.w / 2;  // the diamond's centre, with the diamond at the sprite's top
            s.anchor_y = ts.tile_height / 2;
        } else {
            s.anchor_x = rect.w / 2;  // standing on the sprite's bottom centre
            s.anchor_y = rect.h - 1;
        }
        if (sf.has("tags")) {
            const json& t = arr[i]["tags"];
            if (!t.is_array()) sf.fail("tags", "must be an array of strings");
            for (const json& v : t) {
                if (!v.is_string()) sf.fail("tags", "must be an array of strings");
                s.tags.push_back(v.get<std::string>());
            }
        }
        if (sf.has("opacity_threshold")) {
            double th = sf.real("opacity_threshold");
            if (th < 0 || th > 1) sf.fail("opacity_threshold", "must be in [0, 1]");
            s.opacity_threshold = th;
        }
        if (sf.has("height_map")) {
            try {
                s.height = load_gray16(manifest.parent_path() / sf.text("height_map"), rect.w, rect.h);
            } catch (const Error& e) {
                throw Error(where + ": height_map: " + e.what());
            }
        }
        if (sf.has("shape")) s.shape = shape_from(arr[i]["shape"], where + ": shape");
        if (sf.has("footprint")) s.footprint = footprint_from(arr[i]["footprint"], where + ": footprint");
        ts.sprites.push_back(std::move(s));
    }
    validate(ts);
    return ts;
}

namespace {
json footprint_json(const FootprintSpec& f) {
    const FootprintSpec defaults;
    json j = json::object();
    if (f.mode) j["mode"] = std::string(to_string(*f.mode));
    if (f.mode == FootprintMode::run) j["run"] = {f.run_x, f.run_y, f.run_length};
    if (f.mode == FootprintMode::polygon) {
        j["polygon"] = json::array();
        for (auto [x, y] : f.polygon) j["polygon"].push_back({x, y});
    }
    if (f.shadow_alpha != defaults.shadow_alpha) j["shadow_alpha"] = f.shadow_alpha;
    if (f.shadow_luminance != defaults.shadow_luminance) j["shadow_luminance"] = f.shadow_luminance;
    if (f.ground_tolerance != defaults.ground_tolerance) j["ground_tolerance"] = f.ground_tolerance;
    return j;
}
}  // namespace

FootprintSpec parse_footprint(std::string_view text, std::string_view source) {
    return footprint_from(parse_json(text, source), std::string(source));
}

std::string footprint_to_json(const FootprintSpec& spec) {
    const json j = footprint_json(spec);
    return j.empty() ? "" : j.dump();
}

void save_manifest_footprints(const fs::path& manifest, const Tileset& ts) {
    const std::string src = manifest.string();
    json j = parse_json(read_text(manifest), src);
    check_object(j, src);
    if (!j.contains("sprites") || !j["sprites"].is_array() || j["sprites"].size() != ts.sprites.size())
        throw Error(src + ": sprites no longer match the loaded tileset: reload it before saving footprints");
    for (std::size_t i = 0; i < ts.sprites.size(); ++i) {
        json& entry = j["sprites"][i];
        if (!entry.is_object() || !entry.contains("name") || entry["name"] != ts.sprites[i].name)
            throw Error(src + ": sprites[" + std::to_string(i) + "] is no longer \"" + ts.sprites[i].name + "\"");
        const json f = footprint_json(ts.sprites[i].footprint);
        if (f.empty()) entry.erase("footprint");
        else entry["footprint"] = f;
    }
    write_file_atomic(manifest, j.dump(2) + "\n");
}

void save_generated_tileset(const fs::path& folder, const GeneratedTileset& g) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw Error(folder.string() + ": cannot create folder: " + ec.message());
    json sprites = json::array();
    for (std::size_t i = 0; i < g.tileset.sprites.size(); ++i) {
        const Sprite& s = g.tileset.sprites[i];
        const std::string file = g.image_files[i];
        const std::string height_file = fs::path(file).stem().string() + ".height.png";
        save_image(folder / file, s.image);
        save_gray16(folder / height_file, s.image.width, s.image.height, g.heights[i]);
        sprites.push_back({{"name", s.name},
                           {"image", file},
                           {"anchor", {s.anchor_x, s.anchor_y}},
                           {"kind", s.kind == SpriteKind::floor ? "floor" : "overlay"},
                           {"tags", s.tags},
                           {"height_map", height_file},
                           {"shape", shape_json(s.shape)}});
    }
    json j{{"schema_version", schema_version},
           {"tile", {{"width", g.tileset.tile_width}, {"height", g.tileset.tile_height}}},
           {"sprites", sprites}};
    write_file_atomic(folder / "tileset.json", j.dump(2) + "\n");
}

}  // namespace isolux
