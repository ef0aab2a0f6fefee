// Images in and out through OpenImageIO: image_file.hpp.
#include "isolux/image_file.hpp"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <fcntl.h>
#include <unistd.h>

#include "formats/atomic_write.hpp"
#include "isolux/error.hpp"
#include "isolux/file_io.hpp"

namespace fs = std::filesystem;

namespace isolux {

namespace {

std::string quoted(const fs::path& p) { return p.string(); }

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
    check_output_file(path);
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
    AtomicWrite w(path);
    const fs::path& tmp = w.temp();
    if (!out->open(tmp.string(), spec)) throw Error(quoted(path) + ": cannot write (" + out->geterror() + ")");
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
    if (!ok) throw Error(quoted(path) + ": cannot write (" + why + "); the old file is kept");
    w.commit();
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

namespace {

// A PNG of `channels` channels of `T`, written atomically and read back
// whole before it replaces the target.
template <class T>
void save_png(const fs::path& link, int width, int height, int channels, OIIO::TypeDesc type, const std::vector<T>& values) {
    const fs::path path = write_target(link);
    auto out = OIIO::ImageOutput::create("png");
    if (!out) throw Error(quoted(path) + ": no PNG writer (" + OIIO::geterror() + ")");
    OIIO::ImageSpec spec(width, height, channels, type);
    AtomicWrite w(path);
    const fs::path& tmp = w.temp();
    bool ok = out->open(tmp.string(), spec) && out->write_image(type, values.data());
    ok = out->close() && ok;
    if (ok) {  // read back whole, as save_image does (the PNG writer misses a full disk)
        auto in = OIIO::ImageInput::open(tmp.string());
        std::vector<T> back(values.size());
        ok = in && in->spec().width == width && in->spec().height == height && in->spec().nchannels == channels &&
             in->read_image(0, 0, 0, channels, type, back.data()) && back == values;
        if (in) in->close();
    }
    if (!ok)
        throw Error(quoted(path) + ": cannot write (the written file does not read back whole: is the disk full?); "
                    "the old file is kept");
    w.commit();
}

}  // namespace

void save_gray16(const fs::path& link, int width, int height, const std::vector<std::uint16_t>& values) {
    save_png(link, width, height, 1, OIIO::TypeDesc::UINT16, values);
}

void save_rgb8(const fs::path& link, int width, int height, const std::vector<std::uint8_t>& rgb) {
    save_png(link, width, height, 3, OIIO::TypeDesc::UINT8, rgb);
}

}  // namespace isolux
