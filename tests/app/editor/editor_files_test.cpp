// The editor's files (editor_files.cpp): the window title and unsaved work,
// dropped files opened as what they are.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <unistd.h>

#include "editor/editor.hpp"
#include "editor_util.hpp"
#include "isolux/isolux.hpp"
#include "test_util.hpp"

using namespace isolux;
using namespace isolux::app;
using isolux::test::TempDir;
namespace fs = std::filesystem;
using isolux::test::three_light_editor;

TEST(EditorFiles, theTitleNamesTheFileAndMarksUnsavedWork) {
    TempDir d;
    Editor e = three_light_editor(d.path);
    EXPECT_EQ(window_title(e), "untitled - isolux");
    place_light(e, 10, 10, 1);
    EXPECT_EQ(window_title(e), "untitled * - isolux");
    ASSERT_TRUE(save_scene_to(e, d.path / "forest.json"));
    EXPECT_EQ(window_title(e), "forest.json - isolux");
}

TEST(EditorFiles, droppedFilesOpenAsWhatTheyAre) {
    TempDir d;
    Editor e = three_light_editor(d.path);
    Scene s;
    s.seed = "dropped";
    save_scene(d.path / "level.json", s);
    Params p;
    p.delta_y = 17;
    save_preset(d.path / "tuned.json", p);
    EXPECT_EQ(detect_file_kind(d.path / "level.json"), FileKind::scene);
    EXPECT_EQ(detect_file_kind(d.path / "tuned.json"), FileKind::preset);
    EXPECT_EQ(detect_file_kind(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json"), FileKind::tileset);
    // As the app opens a dropped file: as the kind it detects.
    auto drop = [&](const fs::path& path, double now) {
        return open_recent(e, RecentFile{path.string(), detect_file_kind(path)}, now);
    };
    ASSERT_TRUE(drop(d.path / "tuned.json", 1)) << e.status;
    EXPECT_EQ(e.scene.params.delta_y, 17);
    ASSERT_TRUE(drop(d.path / "level.json", 2)) << e.status;
    EXPECT_EQ(e.scene.seed, "dropped");
    // A folder or a missing file is a message naming it, not a crash.
    std::string message;
    try {
        drop(d.path, 3);
    } catch (const Error& err) {
        message = err.what();
    }
    EXPECT_NE(message.find(d.path.string()), std::string::npos) << message;
    EXPECT_EQ(e.scene.seed, "dropped");
}
