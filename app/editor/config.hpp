// The per-user config folder: settings, recent files, window layout and the
// autosave, never the working directory.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace isolux::app {

// $ISOLUX_CONFIG_DIR, else $XDG_CONFIG_HOME/isolux, else ~/.config/isolux.
std::filesystem::path config_dir();

// What a file was opened or saved as: the Recent menu opens it as the same.
enum class FileKind { scene, preset, tileset };
std::string_view to_string(FileKind k);

struct RecentFile {
    std::string path;
    FileKind kind = FileKind::scene;
    friend bool operator==(const RecentFile&, const RecentFile&) = default;
};

struct Settings {
    std::vector<RecentFile> recent;  // most recent first, at most 8
    bool show_stats = true;
    // Which tracer the app runs (View › Tracer): "auto" (the GPU's compute
    // shader unless the GL driver is a software rasteriser, where the CPU is
    // faster), "cpu" or "gpu". The pixels are the same either way.
    std::string tracer = "auto";
    // The editor window's size when it last closed (0: never), reopened at
    // that size (fitted to the screen's work area).
    int window_width = 0, window_height = 0;
};

// Reads settings.json from `dir`; a missing or bad file gives the defaults
// (and a warning in `warning`), never an error: settings are not user work.
Settings load_settings(const std::filesystem::path& dir, std::string* warning = nullptr);
void save_settings(const std::filesystem::path& dir, const Settings& s);  // atomic; throws Error
void add_recent(Settings& s, const std::string& path, FileKind kind = FileKind::scene);

}  // namespace isolux::app
