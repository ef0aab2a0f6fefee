// The file browser behind every open, save and export: a folder's entries
// (folders first, then the files of the chosen kind), listed without ImGui so
// tests can read them; dialogs.cpp draws them.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace isolux::app {

struct FolderEntry {
    std::string name;
    bool folder = false;
    std::uintmax_t bytes = 0;
};

// A kind of file the browser filters by: its label and extensions (".json").
struct FileFilter {
    const char* label;
    std::vector<std::string> extensions;  // empty: every file
};

// Folders first, then files whose extension (case-insensitive) is one of
// `filter.extensions`, each group by name; hidden entries (a leading dot)
// left out; at most `limit` entries. Throws Error naming the folder when it
// cannot be read.
std::vector<FolderEntry> list_folder(const std::filesystem::path& folder, const FileFilter& filter,
                                     std::size_t limit = 5000);

// The folders of recently used files, most recent first, without repeats.
std::vector<std::string> recent_folders(const std::vector<std::string>& recent_files);

}  // namespace isolux::app
