// Input files checked before they are opened (input_files.hpp): local regular files, a size cap,
// a bound on TOML nesting, and outputs compared with inputs by device and inode.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "support/temp_dir.hpp"

using namespace penink;
using namespace penink::test;
namespace fs = std::filesystem;

namespace {

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(InputFiles, NetworkAndVirtualPathsAreRefused) {
    for (const char* p : {"/vsicurl/http://127.0.0.1:8/x.tif", "/vsis3/bucket/x.tif", "/VSIZIP/a.zip/x.tif",
                          "http://example.org/x.tif", "https://e/x", "ftp:x.tif", "s3://b/k", "file:///etc/passwd"})
        EXPECT_EQ(error_of([&] { check_local_path("input", p); }),
                  std::string("penink: input: ") + p + ": is a network or virtual path (penink reads local files only)");
    for (const char* p : {"dem.tif", "/tmp/a:b.tif", "./vsicurl.tif", "c:dem.tif"}) EXPECT_EQ(error_of([&] { check_local_path("input", p); }), "") << p;
    EXPECT_EQ(error_of([&] { check_local_path("input", std::string("volcano.asc\0x", 13)); }),
              "penink: input: volcano.asc\\x00x: path holds a NUL byte");
}

TEST(InputFiles, OnlyRegularFilesWithinTheirCap) {
    TempDir dir("input_files");
    EXPECT_EQ(error_of([&] { read_input_text("scene", "/dev/zero"); }), "penink: scene: /dev/zero: not a regular file (a device)");
    EXPECT_EQ(error_of([&] { read_input_text("scene", dir.path.string()); }),
              "penink: scene: " + dir.path.string() + ": not a regular file (a folder)");
    const std::string fifo = dir.file("f.toml");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    EXPECT_EQ(error_of([&] { read_input_text("scene", fifo); }), "penink: scene: " + fifo + ": not a regular file (a FIFO)");
    EXPECT_EQ(error_of([&] { read_input_text("scene", dir.file("none.toml")); }), "penink: scene: " + dir.file("none.toml") + ": no such file");
    const std::string big = dir.file("big.toml");
    std::ofstream(big) << std::string(2 << 20, '#');
    EXPECT_EQ(error_of([&] { read_input_text("style", big, 1 << 20, "style file"); }),
              "penink: style: " + big + ": file of 2097152 bytes is larger than the 1 MiB style file may have");
    EXPECT_EQ(read_input_text("style", big, 4 << 20).size(), std::size_t(2 << 20));
}

TEST(InputFiles, TomlNestingIsBoundedOutsideStringsAndComments) {
    const std::string deep = "a = " + std::string(65, '[') + std::string(65, ']') + "\n";
    EXPECT_EQ(error_of([&] { check_toml_nesting("scene", "s.toml", deep); }),
              "penink: scene: s.toml: TOML nests brackets or braces deeper than 64 levels");
    const std::string ok = "a = " + std::string(64, '[') + std::string(64, ']') + "\n";
    EXPECT_EQ(error_of([&] { check_toml_nesting("scene", "s.toml", ok); }), "");
    // brackets in strings (basic, literal, multi-line, escaped quotes) and comments do not count
    const std::string text = "# " + std::string(100, '[') + "\nb = \"" + std::string(100, '{') + "\\\"[[\"\nc = '" +
                             std::string(100, '[') + "'\nd = \"\"\"\n" + std::string(100, '[') + "\n\"\"\"\n[t]\ne = {x = [1]}\n";
    EXPECT_EQ(error_of([&] { check_toml_nesting("scene", "s.toml", text); }), "");
    std::string dotted = "[a";  // 65 parts
    std::string parts64 = "[a";
    for (int i = 0; i < 63; ++i) parts64 += ".a";
    EXPECT_EQ(error_of([&] { check_toml_nesting("scene", "s.toml", parts64 + "]\n"); }), "");  // 64 parts: allowed
    for (int i = 0; i < 64; ++i) dotted += ".a";
    EXPECT_EQ(error_of([&] { check_toml_nesting("scene", "s.toml", dotted + "]\n"); }),
              "penink: scene: s.toml: TOML key has more than 64 dotted parts");
    EXPECT_EQ(error_of([&] { check_toml_nesting("scene", "s.toml", "x = {" + dotted.substr(1) + " = 1}\n"); }),
              "penink: scene: s.toml: TOML key has more than 64 dotted parts");
    // numbers and dates after = [ , each start again
    EXPECT_EQ(error_of([&] { check_toml_nesting("scene", "s.toml", "[a.b.c]\nx = [" + std::string(200, ' ') + "1.5, 2.5]\nd = 1979-05-27T07:32:00.999\n"); }), "");
    const std::string inline_tables = "a = " + std::string(100, '{');
    EXPECT_NE(error_of([&] { check_toml_nesting("scene", "s.toml", inline_tables); }), "");
}

TEST(InputFiles, AnOutputThatIsAnInputByAnyNameIsRefused) {
    TempDir dir("outputs_inputs");
    const std::string dem = dir.file("volcano.tif"), link = dir.file("dem_link.tif"), hard = dir.file("hard.tif");
    std::ofstream(dem) << "dem";
    fs::create_symlink(dem, link);
    fs::create_hard_link(dem, hard);
    const std::vector<NamedInput> in = {{link, "the DEM"}, {dir.file("missing.prj"), "the DEM's side file"}};
    for (const std::string& out : {dem, hard, link, dir.path.string() + "/./volcano.tif"})
        EXPECT_EQ(error_of([&] { check_outputs_not_inputs("export", {dir.file("new.svg"), out}, in); }),
                  "penink: export: " + out + ": is the DEM " + link + " (an output never replaces an input)");
    EXPECT_EQ(error_of([&] { check_outputs_not_inputs("export", {dir.file("new.svg"), dir.file("missing.prj")}, in); }), "");
}
