#include "editor/config.hpp"

#include <algorithm>
#include <cstdlib>
#include <sys/stat.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"

namespace fs = std::filesystem;

namespace isolux::app {

fs::path config_dir() {
    if (const char* d = std::getenv("ISOLUX_CONFIG_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x) return fs::path(x) / "isolux";
    if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".config" / "isolux";
    // No home: a folder of this user's own under the temporary folder, made
    // 0700. One that is not a real folder owned by this user and closed to
    // others (a link or a folder someone planted) is never used: a fresh
    // private one is made instead, for this run only.
    const fs::path dir = fs::temp_directory_path() / ("isolux-config-" + std::to_string(::getuid()));
    ::mkdir(dir.c_str(), 0700);
    struct stat st {};
    if (::lstat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == ::getuid() && (st.st_mode & 077) == 0)
        return dir;
    std::string own = (fs::temp_directory_path() / "isolux-config-XXXXXX").string();
    if (::mkdtemp(own.data())) return own;
    return dir / "unusable";  // saves there fail by name; nothing is written elsewhere
}

Settings load_settings(const fs::path& dir, std::string* warning) {
    Settings s;
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(dir / "settings.json", ec))) return s;
    try {
        // Checked as every input is: a FIFO or a device there is refused, not read.
        auto j = nlohmann::json::parse(read_text_file(dir / "settings.json"));
        if (j.contains("recent") && j["recent"].is_array())
            for (const auto& r : j["recent"]) {
                if (s.recent.size() >= 8) break;
                if (r.is_string()) {
                    s.recent.push_back({r.get<std::string>(), FileKind::scene});  // settings from before kinds
                } else if (r.is_object() && r.contains("path") && r["path"].is_string()) {
                    RecentFile f{r["path"].get<std::string>(), FileKind::scene};
                    const std::string kind = r.contains("kind") && r["kind"].is_string() ? r["kind"].get<std::string>() : "";
                    for (FileKind k : {FileKind::scene, FileKind::preset, FileKind::tileset})
                        if (kind == to_string(k)) f.kind = k;
                    s.recent.push_back(f);
                }
            }
        if (j.contains("show_stats") && j["show_stats"].is_boolean()) s.show_stats = j["show_stats"].get<bool>();
        for (auto [key, field, lo] : {std::tuple{"window_width", &s.window_width, 320}, {"window_height", &s.window_height, 240}})
            if (j.contains(key) && j[key].is_number_integer()) {
                const long long v = j[key].get<long long>();
                if (v >= lo && v <= 8192) *field = int(v);
            }
        if (j.contains("tracer") && j["tracer"].is_string()) {
            const std::string t = j["tracer"].get<std::string>();
            if (t == "auto" || t == "cpu" || t == "gpu") s.tracer = t;
        }
    } catch (const Error& e) {
        if (warning) *warning = std::string(e.what()) + "; using default settings";
    } catch (const std::exception&) {
        if (warning) *warning = (dir / "settings.json").string() + ": unreadable, using defaults";
    }
    return s;
}

void save_settings(const fs::path& dir, const Settings& s) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    nlohmann::json recent = nlohmann::json::array();
    for (const RecentFile& f : s.recent) recent.push_back({{"path", f.path}, {"kind", std::string(to_string(f.kind))}});
    nlohmann::json j{{"schema_version", 1}, {"recent", recent}, {"show_stats", s.show_stats}, {"tracer", s.tracer}};
    if (s.window_width > 0 && s.window_height > 0) j["window_width"] = s.window_width, j["window_height"] = s.window_height;
    // Paths that are not UTF-8 are written with U+FFFD in their place, not refused.
    write_file_atomic(dir / "settings.json", j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

std::string_view to_string(FileKind k) {
    switch (k) {
        case FileKind::scene: return "scene";
        case FileKind::preset: return "preset";
        case FileKind::tileset: return "tileset";
    }
    return "scene";
}

void add_recent(Settings& s, const std::string& path, FileKind kind) {
    std::erase_if(s.recent, [&](const RecentFile& f) { return f.path == path; });
    s.recent.insert(s.recent.begin(), RecentFile{path, kind});
    if (s.recent.size() > 8) s.recent.resize(8);
}

}  // namespace isolux::app
