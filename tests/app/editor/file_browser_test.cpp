// The file browser's listing (file_browser.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <unistd.h>

#include "editor/file_browser.hpp"
#include "test_util.hpp"

using namespace isolux;
using namespace isolux::app;
using isolux::test::TempDir;
namespace fs = std::filesystem;

TEST(FileBrowser, theBrowserListsFoldersFirstThenFilesOfTheKind) {
    TempDir d;
    fs::create_directories(d.path / "b_folder");
    fs::create_directories(d.path / "a_folder");
    for (const char* f : {"z.json", "a.JSON", "m.png", ".hidden.json", "notes.txt"}) std::ofstream(d.path / f) << "{}";
    const FileFilter json{"JSON", {".json"}};
    std::vector<std::string> names;
    for (const FolderEntry& en : list_folder(d.path, json)) names.push_back(en.name);
    EXPECT_EQ(names, (std::vector<std::string>{"a_folder", "b_folder", "a.JSON", "z.json"}));
    const FileFilter all{"All", {}};
    EXPECT_EQ(list_folder(d.path, all).size(), 6u);
    EXPECT_THROW(list_folder(d.path / "missing", all), Error);
    EXPECT_EQ(recent_folders({"/a/x.json", "/b/y.json", "/a/z.json"}), (std::vector<std::string>{"/a", "/b"}));
}
