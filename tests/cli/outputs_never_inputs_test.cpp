// Hostile inputs, the families of data loss and reach: an output that would replace an input (by
// its name, a symlink, or a raster's shared world file), a drainage database or raster written
// over a file penink did not make, paths that are not local regular files, and parsers fed
// unbounded nesting. Each ends with one line, exit 2, and every file as it was.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "cli_support.hpp"

using namespace penink::test;
namespace fs = std::filesystem;

namespace {

const std::string volcano_tif = PENINK_SOURCE_DIR "/tests/data/volcano.tif";
const std::string volcano_asc = PENINK_SOURCE_DIR "/examples/volcano.asc";

// Every regular file under dir with its content.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file() && !e.is_symlink()) files[fs::relative(e.path(), dir).string()] = read_text(e.path());
    return files;
}

// `args` in `dir`: exit 2, exactly `line`, every file unchanged and none added.
void expect_refused(const fs::path& dir, const std::string& args, const std::string& line) {
    const auto before = snapshot(dir);
    const RunResult r = run_penink(args, dir);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_EQ(r.output, line + "\n") << args;
    EXPECT_TRUE(snapshot(dir) == before) << args << ": a file changed, appeared or went";
}

}  // namespace

TEST(OutputsNeverInputs, RenderOverTheDemOrItsWorldFile) {
    const auto dir = fresh_dir("never_inputs_render");
    fs::copy_file(volcano_tif, dir / "volcano.tif");
    fs::create_symlink("volcano.tif", dir / "dem_link.tif");
    expect_refused(dir, "render volcano.tif -o volcano.tif",
                   "penink: export: volcano.tif: is the DEM volcano.tif (an output never replaces an input)");
    expect_refused(dir, "render dem_link.tif -o out.svg -o volcano.tif",
                   "penink: export: volcano.tif: is the DEM dem_link.tif (an output never replaces an input)");
    // dem.tiff beside dem.tif does not take (nor remove) dem.tif's world file
    fs::copy_file(volcano_tif, dir / "dem.tif");
    write_text(dir / "dem.tfw", "10\n0\n0\n-10\n0\n0\n");
    expect_refused(dir, "render dem.tif --map -o dem.tiff",
                   "penink: export: dem.tiff: dem.tfw beside it is another raster's world file, which GDAL would read "
                   "as this one's (name the output .tif or move that file)");
    write_text(dir / "scene.toml", "[terrain]\ndem = \"volcano.tif\"\n");
    expect_refused(dir, "render scene.toml --map -o scene.toml",
                   "penink: export: scene.toml: unknown output format \".toml\" (use .svg .ps .eps .pdf, or a raster: "
                   ".png .tif .tiff .jpg .jpeg .webp .exr)");
}

TEST(OutputsNeverInputs, DrainageOverFilesItDidNotWrite) {
    const auto dir = fresh_dir("never_inputs_drainage");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    write_text(dir / "volcano.toml", "[terrain]\ndem = \"volcano.asc\"\n");
    expect_refused(dir, "drainage volcano.asc -o volcano.asc",
                   "penink: drainage: volcano.asc: exists and is not a drainage database (penink replaces only its own .dv files)");
    expect_refused(dir, "drainage volcano.asc -o volcano.toml",
                   "penink: drainage: volcano.toml: exists and is not a drainage database (penink replaces only its own .dv files)");
    fs::create_directory(dir / "R");
    fs::copy_file(volcano_asc, dir / "R" / "accumulation.tif");
    expect_refused(dir, "drainage volcano.asc -o v.dv --rasters R",
                   "penink: drainage: R/accumulation.tif: exists and was not written by penink drainage (--rasters "
                   "replaces only its own rasters)");
    expect_refused(dir, "drainage R/accumulation.tif -o v.dv --rasters R",
                   "penink: drainage: R/accumulation.tif: is the DEM R/accumulation.tif (an output never replaces an input)");
    // its own rasters it replaces, all four together
    fs::remove(dir / "R" / "accumulation.tif");
    RunResult r = run_penink("drainage volcano.asc -o v.dv --rasters R -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    r = run_penink("drainage volcano.asc -o v.dv --rasters R -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    std::vector<std::string> names;
    for (auto& e : fs::directory_iterator(dir / "R")) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"accumulation.tif", "basin.tif", "flow_direction.tif", "stream_order.tif"}));
}

TEST(OutputsNeverInputs, ScenePathsStayLocal) {
    const auto dir = fresh_dir("never_inputs_local");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    write_text(dir / "nul.toml", "[terrain]\ndem = \"volcano.asc\\u0000x\"\n");
    expect_refused(dir, "render nul.toml -o out.svg", "penink: input: volcano.asc\\x00x: path holds a NUL byte");
    write_text(dir / "net.toml", "[terrain]\ndem = \"/vsicurl/http://127.0.0.1:9/served.tif\"\n");
    expect_refused(dir, "render net.toml -o out.svg",
                   "penink: input: /vsicurl/http://127.0.0.1:9/served.tif: is a network or virtual path (penink reads local files only)");
    expect_refused(dir, "render http://127.0.0.1:9/served.tif -o out.svg",
                   "penink: input: http://127.0.0.1:9/served.tif: is a network or virtual path (penink reads local files only)");
    // a VRT names other files, and could name a URL: refused whatever it holds
    write_text(dir / "dem.vrt", "<VRTDataset rasterXSize=\"2\" rasterYSize=\"2\"><VRTRasterBand dataType=\"Float32\" band=\"1\">"
                                "<SimpleSource><SourceFilename>/vsicurl/http://127.0.0.1:9/x.tif</SourceFilename>"
                                "</SimpleSource></VRTRasterBand></VRTDataset>\n");
    expect_refused(dir, "render dem.vrt -o out.svg",
                   "penink: input: dem.vrt: a VRT is refused (it can name other files and network sources; gdal_translate it to a GeoTIFF)");
}

TEST(OutputsNeverInputs, OnlyRegularFilesAreRead) {
    const auto dir = fresh_dir("never_inputs_regular");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    expect_refused(dir, "render /dev/zero -o out.svg", "penink: input: /dev/zero: not a regular file (a device)");
    expect_refused(dir, "render volcano.asc --style /dev/urandom -o out.svg",
                   "penink: style: /dev/urandom: not a regular file (a device)");
    fs::create_symlink("/dev/zero", dir / "zero.toml");
    expect_refused(dir, "render zero.toml -o out.svg", "penink: scene: zero.toml: not a regular file (a device)");
    fs::create_symlink("/dev/zero", dir / "zero.obj");
    expect_refused(dir, "render zero.obj -o out.svg", "penink: input: zero.obj: not a regular file (a device)");
    fs::create_directory(dir / "d.toml");
    expect_refused(dir, "render d.toml -o out.svg", "penink: scene: d.toml: not a regular file (a folder)");
    ASSERT_EQ(::mkfifo((dir / "f.tif").c_str(), 0644), 0);
    expect_refused(dir, "render f.tif -o out.svg", "penink: input: f.tif: not a regular file (a FIFO)");
    ASSERT_EQ(::mkfifo((dir / "f.toml").c_str(), 0644), 0);
    expect_refused(dir, "render f.toml -o out.svg", "penink: scene: f.toml: not a regular file (a FIFO)");
    expect_refused(dir, "batch volcano.asc --path /dev/zero --out frames", "penink: batch: /dev/zero: not a regular file (a device)");
    write_text(dir / "long.csv", std::string((16 << 20) + 1, 'x'));
    expect_refused(dir, "batch volcano.asc --path long.csv --out frames",
                   "penink: batch: long.csv: file of 16777217 bytes is larger than the 16 MiB flight path may have");
}

TEST(OutputsNeverInputs, TomlNestingIsBounded) {
    const auto dir = fresh_dir("never_inputs_nesting");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    write_text(dir / "arrays.toml", "[terrain]\ndem = \"volcano.asc\"\n[camera]\nx = " + std::string(100000, '[') +
                                        std::string(100000, ']') + "\n");
    expect_refused(dir, "render arrays.toml -o out.svg",
                   "penink: scene: arrays.toml: TOML nests brackets or braces deeper than 64 levels");
    std::string tables = "a = ";
    for (int i = 0; i < 100000; ++i) tables += "{b = ";
    write_text(dir / "tables.toml", tables + "1" + std::string(100000, '}') + "\n");
    expect_refused(dir, "render volcano.asc --style tables.toml -o out.svg",
                   "penink: style: tables.toml: TOML nests brackets or braces deeper than 64 levels");
}

TEST(OutputsNeverInputs, FileNamesThatAreNotTextMakeValidSvg) {
    if (std::system("xmllint --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "xmllint not installed (apt-get install libxml2-utils)";
    const auto dir = fresh_dir("never_inputs_xml");
    const std::string name = "v\xff\xfe\x1bx<&>.asc";
    fs::copy_file(volcano_asc, dir / name);
    const RunResult r = run_penink("render '" + name + "' --map -o out.svg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const RunResult lint = run_penink("", dir, "xmllint --noout out.svg");
    EXPECT_EQ(lint.code, 0) << lint.output;
    EXPECT_NE(read_text(dir / "out.svg").find("<title id=\"title\">v\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBDx&lt;&amp;&gt;.asc"),
              std::string::npos);
}

TEST(OutputsNeverInputs, RastersOnAFullDiskLeaveNothing) {
    const auto dir = fresh_dir("never_inputs_full");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    fs::create_directory(dir / "R");
    if (std::system(("mount -t tmpfs -o size=8k tmpfs '" + (dir / "R").string() + "' 2>/dev/null").c_str()) != 0)
        GTEST_SKIP() << "cannot mount a small tmpfs here (needs root or CAP_SYS_ADMIN)";
    const RunResult r = run_penink("drainage volcano.asc -o v.dv --rasters R -q", dir);
    std::size_t left = 0;
    for (auto& e : fs::directory_iterator(dir / "R")) left += 1 + 0 * e.is_regular_file();
    std::system(("umount '" + (dir / "R").string() + "'").c_str());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("penink: ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find("R/"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
    EXPECT_EQ(left, 0u) << "a raster or temporary left on the full disk";
}

TEST(OutputsNeverInputs, DottedKeysAreBounded) {
    const auto dir = fresh_dir("never_inputs_dotted");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    std::string key = "a";
    for (int i = 0; i < 100000; ++i) key += ".a";
    write_text(dir / "dots.toml", "[terrain]\ndem = \"volcano.asc\"\n[" + key + "]\nx = 1\n");
    expect_refused(dir, "render dots.toml -o out.svg", "penink: scene: dots.toml: TOML key has more than 64 dotted parts");
}

namespace {

// Sets or clears the immutable attribute of `path` (chattr): a file that can be neither replaced,
// renamed onto nor linked, so placing an output over it fails after every temporary is written.
// False where the file system or the user cannot (not root, tmpfs, no chattr).
bool set_immutable(const fs::path& path, bool on) {
    return std::system(("chattr " + std::string(on ? "+i" : "-i") + " '" + path.string() + "' 2>/dev/null").c_str()) == 0;
}

// `args` in `dir` while `frozen` is immutable: exit 2 with one line naming it, and every file in
// `dir` as it was before (the set rolled back, no temporary or kept old file left).
void expect_placement_rolled_back(const fs::path& dir, const fs::path& frozen, const std::string& args) {
    const auto before = snapshot(dir);
    if (!set_immutable(frozen, true)) GTEST_SKIP() << "cannot make a file immutable here (chattr +i needs root on ext4/xfs/btrfs)";
    const RunResult r = run_penink(args, dir);
    set_immutable(frozen, false);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("penink: ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find(frozen.filename().string()), std::string::npos) << r.output;
    const auto after = snapshot(dir);
    EXPECT_TRUE(after == before) << args << ": a file changed, appeared or went (" << before.size() << " files before, "
                                 << after.size() << " after)";
}

}  // namespace

// The drainage database and its rasters are one set: when the last raster cannot be placed, the
// database placed before it is put back as it was, and nothing is left beside either.
TEST(OutputsNeverInputs, DrainageSetThatCannotBePlacedStaysAsItWas) {
    const auto dir = fresh_dir("never_inputs_drainage_set");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    const RunResult first = run_penink("drainage volcano.asc -o v.dv --rasters R -q", dir);
    ASSERT_EQ(first.code, 0) << first.output;
    ASSERT_TRUE(fs::exists(dir / "R/stream_order.tif"));
    // least-cost routing gives another database and other rasters: a real replacement to roll back
    expect_placement_rolled_back(dir, dir / "R/stream_order.tif",
                                 "drainage volcano.asc -o v.dv --rasters R --routing least-cost -q");
}

// A render's outputs are one set: an SVG placed before a PNG that cannot be is put back.
TEST(OutputsNeverInputs, RenderSetThatCannotBePlacedStaysAsItWas) {
    const auto dir = fresh_dir("never_inputs_render_set");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    const RunResult first = run_penink("render volcano.asc -o a.svg -o a.png --width 160 --height 120 -q", dir);
    ASSERT_EQ(first.code, 0) << first.output;
    // the other view's crease tiles built first (a cache a render adds to, written file by file
    // as it builds them, whatever becomes of its outputs), so that only the outputs are at stake
    const RunResult other = run_penink("render volcano.asc -o b.svg --width 160 --height 120 --azimuth 90 -q", dir);
    ASSERT_EQ(other.code, 0) << other.output;
    expect_placement_rolled_back(dir, dir / "a.png",
                                 "render volcano.asc -o a.svg -o a.png --width 160 --height 120 --azimuth 90 -q");
}
