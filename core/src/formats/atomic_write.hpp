// Inside core: a write in progress, shared by every writer (text through
// write_file_atomic, images through OpenImageIO).
#pragma once
#include <filesystem>

namespace isolux {

// Where a write to `path` lands: through a symlink, its target, so saving
// keeps the link (a bounded walk: a loop is an error).
std::filesystem::path write_target(const std::filesystem::path& path);

// Throws Error naming `path` when it exists and is not a regular file (a
// FIFO, a device, a socket, a folder): a save never renames over one.
void check_output_target(const std::filesystem::path& path);

// A temporary sibling of the target that keeps its extension (OpenImageIO
// picks the writer from it), created empty up front so that a folder where
// nothing can be written says why before any writer library hides the
// reason. commit() puts it over the target; if it never is, the temporary
// file is removed and the target keeps its old bytes.
class AtomicWrite {
public:
    explicit AtomicWrite(const std::filesystem::path& link);
    ~AtomicWrite();
    AtomicWrite(const AtomicWrite&) = delete;
    AtomicWrite& operator=(const AtomicWrite&) = delete;

    const std::filesystem::path& target() const { return target_; }
    const std::filesystem::path& temp() const { return temp_; }
    // Replaces the target by the finished temporary file, keeping the old
    // file's permissions and its hard links (file_io.cpp: copy_into_linked).
    void commit();

private:
    std::filesystem::path target_, temp_;
    bool committed_ = false;
};

}  // namespace isolux
