// Hostile sizes and values refused up front with one line: an image beyond --max-memory, a map
// scale wider than the Earth, a mesh vertex that is not a number.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_support.hpp"

using namespace penink::test;
namespace fs = std::filesystem;

namespace {

const std::string volcano_asc = PENINK_SOURCE_DIR "/examples/volcano.asc";
const std::string volcano_tif = PENINK_SOURCE_DIR "/tests/data/volcano.tif";

void expect_refused(const fs::path& dir, const std::string& args, const std::string& line) {
    const std::size_t before = file_count(dir);
    const RunResult r = run_penink(args, dir);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_EQ(r.output, line + "\n") << args;
    EXPECT_EQ(file_count(dir), before) << args << ": a file was left behind";
}

}  // namespace

TEST(BoundedInputs, AnImageBeyondMaxMemoryIsRefusedUpFront) {
    const auto dir = fresh_dir("bounded_image");
    // 16384² pixels at 32 B (render_bytes_per_pixel) = 8 GiB, with the DEM's few MiB
    expect_refused(dir, "render " + volcano_asc + " --width 16384 --height 16384 --max-memory 2G -o big.png",
                   "penink: scene: " + volcano_asc + ": drawing a 16384x16384 image of the DEM's 61x87 nodes would need "
                   "about 8.0 GiB of memory, 2.0 GiB available (--max-memory)");
}

TEST(BoundedInputs, AMapWiderThanTheEarthIsRefused) {
    const auto dir = fresh_dir("bounded_scale");
    // the image's width of paper at 96 dpi, at 1:1e9
    expect_refused(dir, "render " + volcano_tif + " --map --scale 1:1000000000 -o map.svg",
                   "penink: scene: " + volcano_tif + ": --scale 1:1000000000 makes the map 264583 km across, more than "
                   "the Earth's circumference (at most 1:151464631 here)");
}

TEST(BoundedInputs, AMeshVertexThatIsNotANumberIsNamed) {
    const auto dir = fresh_dir("bounded_mesh");
    write_text(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 1 0\nf 1 2 3\nf 2 4 3\n");
    expect_refused(dir, "render nan.obj -o out.svg",
                   "penink: input: nan.obj: vertex 4 has coordinate nan, out of range (mesh coordinates must be finite "
                   "and within +-1e9)");
    write_text(dir / "inf.obj", "v 0 0 0\nv 1 0 -Inf\nv 0 1 0\nf 1 2 3\n");
    expect_refused(dir, "render inf.obj -o out.svg",
                   "penink: input: inf.obj: vertex 2 has coordinate -Inf, out of range (mesh coordinates must be finite "
                   "and within +-1e9)");
}
