// The one way in and out for every file isolux reads or writes: inputs are
// checked to be regular files of a bounded size before they are opened, and
// every write is atomic (a temporary file in the same folder, then rename),
// so a crash never leaves a half-written file where the old one was.
// Errors are Error, naming the file.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace isolux {

// Largest text files we read (JSON presets, scenes and manifests; TMX and TSX).
inline constexpr std::uintmax_t max_text_file_bytes = std::uintmax_t(64) << 20;

// Throws Error naming the path unless it is a regular file (not a FIFO,
// device, folder or socket, nor a symlink loop) of at most `max_bytes`.
void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

// A text file's bytes, after check_input_file(path, max_text_file_bytes).
std::string read_text_file(const std::filesystem::path& path);

// Writes `contents` through a temporary file and rename (through a symlink,
// to its target). A file with other hard links keeps them: it is written in
// place once its old bytes stand copied and synced beside it. A target that
// exists and is not a regular file (a FIFO, a device) is refused, as every
// writer of isolux refuses it.
void write_file_atomic(const std::filesystem::path& path, std::string_view contents);

// What a save to `path` would refuse, checked before the work that makes
// its contents: a target that is not a regular file, a folder that does not
// exist or cannot be written. Throws Error naming the path.
void check_output_file(const std::filesystem::path& path);

// For a file or folder isolux names itself inside a folder the user chose
// (an export's TSX, images and image layers; a generated tileset's files):
// refused when it is a symbolic link, which would carry the write out of
// that folder. A file the user names is written through its link instead.
void check_own_name(const std::filesystem::path& path);

// What this thread's saves since the last call had to do that the user
// should know (a hard link that could not be kept), then forgotten.
std::vector<std::string> take_write_notes();

}  // namespace isolux
