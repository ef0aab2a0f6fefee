// The per-user config folder: settings, recent files, window layout and the
// autosave, never the working directory.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace isolux {

// $ISOLUX_CONFIG_DIR, else $XDG_CONFIG_HOME/isolux, else ~/.config/isolux.
std::filesystem::path config_dir();

struct Settings {
    std::vector<std::string> recent;  // most recent first, at most 8
    bool show_stats = true;
};

// Reads settings.json from `dir`; a missing or bad file gives the defaults
// (and a warning in `warning`), never an error: settings are not user work.
Settings load_settings(const std::filesystem::path& dir, std::string* warning = nullptr);
void save_settings(const std::filesystem::path& dir, const Settings& s);  // atomic; throws Error
void add_recent(Settings& s, const std::string& path);

}  // namespace isolux
