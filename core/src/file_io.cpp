// Checked reads and atomic writes: file_io.hpp and atomic_write.hpp.
#include "isolux/file_io.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "atomic_write.hpp"
#include "isolux/error.hpp"

namespace fs = std::filesystem;

namespace isolux {

namespace {

std::string quoted(const fs::path& p) { return p.string(); }

}  // namespace

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

namespace {

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

AtomicWrite::AtomicWrite(const fs::path& link) : target_(write_target(link)), temp_(temp_sibling(target_)) {
    create_temp(temp_, target_);
}

AtomicWrite::~AtomicWrite() {
    if (committed_) return;
    std::error_code ec;
    fs::remove(temp_, ec);
}

void AtomicWrite::commit() {
    committed_ = true;  // from here commit_temp owns the temporary file (it keeps it when a linked write fails)
    commit_temp(temp_, target_);
}

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

std::string read_text_file(const fs::path& path) {
    check_input_file(path, max_text_file_bytes);
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(quoted(path) + ": cannot open");
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (f.bad()) throw Error(quoted(path) + ": cannot read: " + std::strerror(errno));
    return text;
}

void write_file_atomic(const fs::path& link, std::string_view contents) {
    AtomicWrite w(link);
    const int fd = ::open(w.temp().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    bool ok = fd >= 0 && write_all(fd, contents.data(), contents.size()) && ::fsync(fd) == 0;
    int err = ok ? 0 : errno;
    if (fd >= 0 && ::close(fd) != 0 && ok) ok = false, err = errno;
    if (!ok) throw Error(quoted(w.target()) + ": cannot write: " + std::strerror(err) + "; the old file is kept");
    w.commit();
}

}  // namespace isolux
