// Checked reads and atomic writes: file_io.hpp and atomic_write.hpp.
#include "isolux/file_io.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <vector>
#include <system_error>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "formats/atomic_write.hpp"
#include "isolux/error.hpp"

namespace fs = std::filesystem;

namespace isolux {

namespace {

std::string quoted(const fs::path& p) { return p.string(); }

}  // namespace

void check_output_target(const fs::path& path) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(path, ec);
    if (ec || st.type() == fs::file_type::not_found || st.type() == fs::file_type::regular) return;
    const char* what = st.type() == fs::file_type::directory ? "a folder"
                       : st.type() == fs::file_type::fifo    ? "a FIFO (a pipe)"
                       : st.type() == fs::file_type::socket  ? "a socket"
                       : (st.type() == fs::file_type::character || st.type() == fs::file_type::block) ? "a device"
                                                                                                       : "not a regular file";
    throw Error(quoted(path) + ": is " + what + ": isolux writes only regular files (name a file to create or replace)");
}

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

// A whole file's bytes by POSIX reads (an iostream would throw, or stop
// short, on a read error such as EIO); false with errno set on failure.
bool read_all(const fs::path& path, std::string& out) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    out.clear();
    char buf[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int err = errno;
            ::close(fd);
            errno = err;
            return false;
        }
        if (n == 0) break;
        out.append(buf, std::size_t(n));
    }
    ::close(fd);
    return true;
}

// Writes `bytes` into a new file `path` (which must not exist) and syncs it.
bool write_new_synced(const fs::path& path, const std::string& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) return false;
    const bool ok = write_all(fd, bytes.data(), bytes.size()) && ::fsync(fd) == 0;
    const int err = errno;
    ::close(fd);
    errno = err;
    return ok;
}

// The copy of a linked file's old bytes kept beside it while it is written
// in place: ".NAME.oldPID" (not the temporary files' pattern: no later save
// removes it as litter).
fs::path old_copy_of(const fs::path& path) {
    fs::path c = path;
    c.replace_filename("." + path.filename().string() + ".old" + std::to_string(::getpid()));
    return c;
}

// A file with other hard links keeps them (a rename would leave the other
// names on the old contents): the finished temporary file's bytes are
// written into it in place, but only once a complete, synced copy of its
// old bytes stands beside it (old_copy_of), as Vim and Emacs do for linked
// files. Killed while writing in place, the file is torn, but its old bytes
// are in the copy and its new ones in the temporary file. Space is reserved
// first, so a full disk fails before any old byte changes. False when the
// file has one name, or the copy or the space cannot be had: the caller
// renames, and the other names keep the old contents (a note says so).
bool copy_into_linked(const fs::path& tmp, const fs::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink < 2) return false;
    std::string bytes, old;
    if (!read_all(tmp, bytes) || !read_all(path, old)) return false;
    const fs::path copy = old_copy_of(path);
    std::error_code ec;
    fs::remove(copy, ec);
    if (!write_new_synced(copy, old)) {
        fs::remove(copy, ec);
        return false;
    }
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0 || (!bytes.empty() && ::posix_fallocate(fd, 0, off_t(bytes.size())) != 0)) {
        if (fd >= 0) ::close(fd);
        fs::remove(copy, ec);
        return false;
    }
    const bool ok = write_all(fd, bytes.data(), bytes.size()) && ::ftruncate(fd, off_t(bytes.size())) == 0 &&
                    ::fsync(fd) == 0;
    const int err = errno;
    ::close(fd);
    if (!ok)  // the new contents stay in the temporary file, the old ones in the copy
        throw Error(quoted(path) + ": cannot write in place: " + std::strerror(err) + "; the old contents are in " +
                    quoted(copy) + ", the new ones in " + quoted(tmp));
    fs::remove(copy, ec);
    fs::remove(tmp, ec);
    return true;
}

// What saves had to do that the user should know (thread-local: each
// thread's saves report to it).
std::vector<std::string>& notes() {
    thread_local std::vector<std::string> n;
    return n;
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
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && st.st_nlink >= 2 && notes().size() < 100)
        notes().push_back(quoted(path) + ": had " + std::to_string(st.st_nlink - 1) +
                          " other hard link(s), which keep the old contents: there was no room to write it in place");
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error(quoted(path) + ": cannot write: " + ec.message());
    }
    remove_stale_temps(path);
}

}  // namespace

AtomicWrite::AtomicWrite(const fs::path& link) : target_(write_target(link)), temp_(temp_sibling(target_)) {
    check_output_target(target_);
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
    std::string text;
    if (!read_all(path, text)) throw Error(quoted(path) + ": cannot read: " + std::strerror(errno));
    if (text.size() > max_text_file_bytes)  // grew since it was checked
        throw Error(quoted(path) + ": is over the " + std::to_string(max_text_file_bytes >> 20) + " MB isolux reads");
    return text;
}

void check_output_file(const fs::path& link) {
    const fs::path path = write_target(link);
    check_output_target(path);
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw Error(quoted(link) + ": cannot write: its folder " + quoted(dir) + " does not exist");
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(quoted(link) + ": cannot write: " + std::strerror(errno) + " (its folder " + quoted(dir) + ")");
}

void check_own_name(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(path, ec))) return;
    const fs::path to = fs::read_symlink(path, ec);
    throw Error(quoted(path) + ": is a symbolic link" + (ec ? std::string() : " (to " + quoted(to) + ")") +
                ": isolux writes the files it names itself only inside the folder you chose (remove the link, or "
                "choose another name or folder)");
}

std::vector<std::string> take_write_notes() {
    std::vector<std::string> n;
    n.swap(notes());
    return n;
}

void write_file_atomic(const fs::path& link, std::string_view contents) {
    AtomicWrite w(link);
    const int fd = ::open(w.temp().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    errno = 0;
    bool ok = fd >= 0 && write_all(fd, contents.data(), contents.size()) && ::fsync(fd) == 0;
    int err = ok ? 0 : (errno ? errno : EIO);
    if (fd >= 0 && ::close(fd) != 0 && ok) ok = false, err = errno;
    if (!ok) throw Error(quoted(w.target()) + ": cannot write: " + std::strerror(err) + "; the old file is kept");
    w.commit();
}

}  // namespace isolux
