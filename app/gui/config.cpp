#include "gui/config.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "isolux/files.hpp"

namespace fs = std::filesystem;

namespace isolux {

fs::path config_dir() {
    if (const char* d = std::getenv("ISOLUX_CONFIG_DIR"); d && *d) return d;
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x) return fs::path(x) / "isolux";
    if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".config" / "isolux";
    return fs::temp_directory_path() / "isolux-config";
}

Settings load_settings(const fs::path& dir, std::string* warning) {
    Settings s;
    std::ifstream f(dir / "settings.json");
    if (!f) return s;
    std::ostringstream ss;
    ss << f.rdbuf();
    try {
        auto j = nlohmann::json::parse(ss.str());
        if (j.contains("recent") && j["recent"].is_array())
            for (const auto& r : j["recent"])
                if (r.is_string() && s.recent.size() < 8) s.recent.push_back(r.get<std::string>());
        if (j.contains("show_stats") && j["show_stats"].is_boolean()) s.show_stats = j["show_stats"].get<bool>();
    } catch (const std::exception&) {
        if (warning) *warning = (dir / "settings.json").string() + ": unreadable, using defaults";
    }
    return s;
}

void save_settings(const fs::path& dir, const Settings& s) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    nlohmann::json j{{"schema_version", 1}, {"recent", s.recent}, {"show_stats", s.show_stats}};
    write_file_atomic(dir / "settings.json", j.dump(2) + "\n");
}

void add_recent(Settings& s, const std::string& path) {
    s.recent.erase(std::remove(s.recent.begin(), s.recent.end(), path), s.recent.end());
    s.recent.insert(s.recent.begin(), path);
    if (s.recent.size() > 8) s.recent.resize(8);
}

}  // namespace isolux
