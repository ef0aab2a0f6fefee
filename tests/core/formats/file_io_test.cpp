// Checked reads and atomic writes (file_io.cpp): no temporary file left,
// links and modes kept, FIFOs and devices refused, read errors named.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <sys/stat.h>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/world.hpp"
#include "test_util.hpp"

using namespace isolux;
using isolux::test::error_of;
using isolux::test::TempDir;
namespace fs = std::filesystem;

TEST(Files, savingIsAtomicAndLeavesNoTemporaryFiles) {
    TempDir d;
    fs::path p = d.path / "p.json";
    save_preset(p, Params{});
    Params q;
    q.delta_y = 40;
    save_preset(p, q);
    EXPECT_EQ(load_preset(p).delta_y, 40);
    int files = 0;
    for ([[maybe_unused]] auto& e : fs::directory_iterator(d.path)) ++files;
    EXPECT_EQ(files, 1);
    // An invalid preset is refused before anything is written: the old file stays.
    q.noise_window = 0;
    EXPECT_THROW(save_preset(p, q), Error);
    EXPECT_EQ(load_preset(p).delta_y, 40);
}

TEST(Files, savingThroughASymlinkKeepsTheLinkAndTheModeAndALoopIsRefused) {
    TempDir d;
    fs::create_directories(d.path / "real");
    const fs::path target = d.path / "real" / "scene.json", link = d.path / "scene.json";
    write_file_atomic(target, "old");
    fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write);
    fs::create_symlink(fs::path("real") / "scene.json", link);
    write_file_atomic(link, "new");
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
    std::ifstream in(target);
    std::string text;
    in >> text;
    EXPECT_EQ(text, "new");
    EXPECT_EQ(fs::status(target).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
    // A loop of links is refused, not followed forever.
    fs::create_symlink("loop_b.json", d.path / "loop_a.json");
    fs::create_symlink("loop_a.json", d.path / "loop_b.json");
    EXPECT_MENTIONS(error_of([&] { write_file_atomic(d.path / "loop_a.json", "x"); }), "loop_a.json");
}

TEST(Files, savingAFileWithHardLinksKeepsThemAndItsInode) {
    TempDir d;
    const fs::path a = d.path / "scene.json", b = d.path / "also_scene.json";
    write_file_atomic(a, "old contents, longer than the new");
    fs::create_hard_link(a, b);
    struct stat before {};
    ASSERT_EQ(::stat(a.c_str(), &before), 0);
    write_file_atomic(a, "new");
    struct stat after {};
    ASSERT_EQ(::stat(a.c_str(), &after), 0);
    EXPECT_EQ(after.st_ino, before.st_ino);
    EXPECT_EQ(after.st_nlink, 2u);
    for (const fs::path& p : {a, b}) {
        std::ifstream in(p);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        EXPECT_EQ(text, "new") << p;
    }
    // No temporary file is left beside them.
    int files = 0;
    for (const auto& e : fs::directory_iterator(d.path)) files += e.is_regular_file();
    EXPECT_EQ(files, 2);
    // An image too.
    Image im(3, 2);
    for (std::uint8_t& v : im.rgba) v = 200;
    save_image(d.path / "shot.png", im);
    fs::create_hard_link(d.path / "shot.png", d.path / "shot_link.png");
    im.rgba[0] = 7;
    save_image(d.path / "shot.png", im);
    EXPECT_EQ(load_image(d.path / "shot_link.png").rgba, im.rgba);
}

TEST(Files, noSaveReplacesAFifoADeviceOrASocketAndTheMessageSaysWhy) {
    TempDir d;
    const fs::path fifo = d.path / "pipe", link = d.path / "link.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    fs::create_symlink(fifo, link);
    std::string m = error_of([&] { write_file_atomic(fifo, "x"); });
    EXPECT_MENTIONS(m, "is a FIFO");
    m = error_of([&] { save_image(link, Image(2, 2)); });
    EXPECT_MENTIONS(m, "is a FIFO");
    m = error_of([&] { check_output_file(d.path / "no" / "such.csv"); });
    EXPECT_MENTIONS(m, "does not exist");
    EXPECT_TRUE(fs::is_fifo(fifo));
    // The machine's own /dev/null is refused by name (nothing is written: the
    // check comes before any temporary file).
    m = error_of([&] { check_output_file("/dev/null"); });
    EXPECT_MENTIONS(m, "is a device");
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(Files, aReadErrorIsAnErrorNamingTheFileNotAnotherException) {
    // /proc/self/mem is a regular file whose reads fail (EIO at offset 0).
    std::string m;
    try {
        read_text_file("/proc/self/mem");
    } catch (const Error& e) {
        m = e.what();
    }
    EXPECT_MENTIONS(m, "/proc/self/mem: cannot read");
}

TEST(Files, messagesCarryControlCharactersEscaped) {
    const std::string m = Error(std::string("a\x1b[2J\nb\x07" "c\xc2\x9b" "d\xc3\xa9")).what();
    EXPECT_EQ(m, "a\\x1b[2J\\x0ab\\x07c\\x9bd\xc3\xa9");  // C0, C1 (UTF-8) escaped; é kept
}

// The files isolux names itself inside a folder the user chose never follow
// a symbolic link out of it: an export's TSX or images folder, an image in the
// images folder an interrupted export left, a generated tileset's image. Each is
// refused by name, and what the link points to keeps its bytes.
TEST(Files, filesIsoluxNamesItselfInAChosenFolderNeverFollowALinkOutOfIt) {
    TempDir d;
    const fs::path outside = d.path / "outside";
    fs::create_directories(outside);
    write_file_atomic(outside / "victim.tsx", "keep");
    const Scene scene = [] {
        Scene s;
        s.width = s.height = 4;
        return s;
    }();
    const World w = make_world(test::default_tileset(), scene);
    auto outside_untouched = [&] {
        EXPECT_EQ(read_text_file(outside / "victim.tsx"), "keep");
        std::size_t n = 0;
        for ([[maybe_unused]] const auto& f : fs::directory_iterator(outside)) ++n;
        EXPECT_EQ(n, 1u) << "a file was written outside the chosen folder";
    };
    {  // the export's TSX is a link to a file outside
        fs::create_directories(d.path / "a");
        fs::create_symlink(outside / "victim.tsx", d.path / "a" / "m_floors.tsx");
        EXPECT_MENTIONS(error_of([&] { export_tiled(w, scene, d.path / "a" / "m.tmx"); }), "m_floors.tsx");
        EXPECT_FALSE(fs::exists(d.path / "a" / "m.tmx"));
        outside_untouched();
    }
    {  // the export's images folder is a link to a folder outside
        fs::create_directories(d.path / "b");
        fs::create_symlink(outside, d.path / "b" / "m_images");
        EXPECT_MENTIONS(error_of([&] { export_tiled(w, scene, d.path / "b" / "m.tmx"); }), "m_images");
        outside_untouched();
    }
    {  // the images folder an interrupted re-export left holds a link where an image goes
        fs::create_directories(d.path / "c");
        export_tiled(w, scene, d.path / "c" / "m.tmx");  // an isolux map: the next export writes m_images.1
        std::string image;
        for (const auto& f : fs::directory_iterator(d.path / "c" / "m_images")) image = f.path().filename().string();
        ASSERT_FALSE(image.empty());
        fs::create_directories(d.path / "c" / "m_images.1");
        fs::create_symlink(outside / "victim.tsx", d.path / "c" / "m_images.1" / image);
        export_tiled(w, scene, d.path / "c" / "m.tmx");  // the leftovers are cleared, the link never followed
        EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(d.path / "c" / "m_images.1" / image)));
        outside_untouched();
    }
    {  // a generated tileset's image is a link
        fs::create_directories(d.path / "t");
        const GeneratedTileset g = generate_default_tileset(0.5);
        fs::create_symlink(outside / "victim.tsx", d.path / "t" / g.image_files.back());
        EXPECT_MENTIONS(error_of([&] { save_generated_tileset(d.path / "t", g); }), g.image_files.back());
        EXPECT_FALSE(fs::exists(d.path / "t" / "tileset.json"));
        outside_untouched();
    }
    // A file the user names is still written through its link.
    fs::create_directories(d.path / "e");
    fs::create_symlink(outside / "victim.tsx", d.path / "e" / "named.json");
    write_file_atomic(d.path / "e" / "named.json", "new");
    EXPECT_EQ(read_text_file(outside / "victim.tsx"), "new");
}
