// Bad input to `penink render`: one clear line naming the file and the problem, exit code 2,
// and no output file (nor temp file) left behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";

void expect_error(const std::filesystem::path& dir, const std::string& args, const std::string& line,
                  std::size_t files_before) {
    const RunResult r = run_penink(args, dir);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output, line + "\n");
    EXPECT_EQ(file_count(dir), files_before) << "an output or temp file was left behind";
}

std::string grid(int cols, int rows, const std::string& values) {
    return "ncols " + std::to_string(cols) + "\nnrows " + std::to_string(rows) +
           "\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n" + values;
}

}  // namespace

TEST(RenderErrors, MissingFile) {
    const auto dir = fresh_dir("missing");
    expect_error(dir, "render nosuch.tif -o out.svg", "penink: input: nosuch.tif: no such file", 0);
}

TEST(RenderErrors, NotADem) {
    const auto dir = fresh_dir("notdem");
    write_text(dir / "notes.tif", "this is not a raster\n");
    expect_error(dir, "render notes.tif -o out.svg -o out.png",
                 "penink: input: notes.tif: not a DEM raster (GDAL cannot read it)", 1);
}

TEST(RenderErrors, AllNodata) {
    const auto dir = fresh_dir("nodata");
    write_text(dir / "empty.asc", grid(3, 3, "-9999 -9999 -9999\n-9999 -9999 -9999\n-9999 -9999 -9999\n"));
    expect_error(dir, "render empty.asc -o out.svg",
                 "penink: input: empty.asc: DEM has no valid elevation (all nodata)", 1);
}

TEST(RenderErrors, OneByOne) {
    const auto dir = fresh_dir("tiny");
    write_text(dir / "one.asc", grid(1, 1, "5\n"));
    expect_error(dir, "render one.asc -o out.svg",
                 "penink: input: one.asc: DEM is too small (1x1 nodes; at least 2x2 needed)", 1);
}

TEST(RenderErrors, ZeroAndNegativeSizes) {
    const auto dir = fresh_dir("sizes");
    expect_error(dir, "render " + volcano + " -o out.svg --width 0",
                 "penink: cli: --width: must be between 1 and 16384 (got \"0\")", 0);
    expect_error(dir, "render " + volcano + " -o out.svg --height -5",
                 "penink: cli: --height: must be between 1 and 16384 (got \"-5\")", 0);
    write_text(dir / "zero.toml", "[terrain]\ndem = \"" + volcano + "\"\n[camera]\nwidth = 0\n");
    expect_error(dir, "render zero.toml -o out.svg", "penink: scene: zero.toml: image size must be positive (got 0x750)", 1);
}

TEST(RenderErrors, CameraInsideTerrain) {
    const auto dir = fresh_dir("inside");
    // Volcano's crater floor is ~150 m; NZTM position near the summit, elevation 120 m.
    write_text(dir / "scene.toml", "[terrain]\ndem = \"" + volcano +
                                       "\"\n[camera]\nposition = \"1757270 5917440\"\nelevation = 120\n");
    expect_error(dir, "render scene.toml -o out.svg",
                 "penink: scene: scene.toml: camera is inside the terrain (elevation 120 m, ground 159.5 m)", 1);
}

TEST(RenderErrors, UnknownOutputFormat) {
    const auto dir = fresh_dir("format");
    expect_error(dir, "render " + volcano + " -o out.gif",
                 "penink: export: out.gif: unknown output format \".gif\" (use .svg .ps .eps .pdf, or a raster: .png .tif .tiff .jpg .jpeg .webp .exr)", 0);
}

TEST(RenderErrors, MissingOutputDirectory) {
    const auto dir = fresh_dir("nodir");
    expect_error(dir, "render " + volcano + " -o nodir/out.svg",
                 "penink: export: nodir/out.svg: cannot write file (no such directory)", 0);
}
