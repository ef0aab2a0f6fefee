#include "editor/file_browser.hpp"

#include <algorithm>
#include <cctype>

#include "isolux/error.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

namespace {
std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(unsigned(c)));
    return s;
}
}  // namespace

std::vector<FolderEntry> list_folder(const fs::path& folder, const FileFilter& filter, std::size_t limit) {
    std::vector<FolderEntry> folders, files;
    std::error_code ec;
    fs::directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec);
    if (ec) throw Error(folder.string() + ": cannot list (" + ec.message() + ")");
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec) break;
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.') continue;
        std::error_code e2;
        if (it->is_directory(e2)) {
            folders.push_back({name, true, 0});
        } else {
            const std::string ext = lower(it->path().extension().string());
            if (!filter.extensions.empty() &&
                std::find(filter.extensions.begin(), filter.extensions.end(), ext) == filter.extensions.end())
                continue;
            const std::uintmax_t bytes = it->is_regular_file(e2) ? it->file_size(e2) : 0;
            files.push_back({name, false, e2 ? 0 : bytes});
        }
        if (folders.size() + files.size() >= limit) break;
    }
    auto by_name = [](const FolderEntry& a, const FolderEntry& b) { return a.name < b.name; };
    std::sort(folders.begin(), folders.end(), by_name);
    std::sort(files.begin(), files.end(), by_name);
    folders.insert(folders.end(), files.begin(), files.end());
    return folders;
}

std::vector<std::string> recent_folders(const std::vector<std::string>& recent_files) {
    std::vector<std::string> out;
    for (const std::string& f : recent_files) {
        const std::string dir = fs::path(f).parent_path().string();
        if (!dir.empty() && std::find(out.begin(), out.end(), dir) == out.end()) out.push_back(dir);
    }
    return out;
}

}  // namespace isolux::app
