// `penink fill` through the binary: a filled GeoTIFF with its summary line; a missing -o, an
// output that would replace the DEM and a file-size limit each refused in one line, exit 2,
// leaving no file.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>

#include "cli_support.hpp"

namespace penink {
namespace {

namespace fs = std::filesystem;
using namespace penink::test;

TEST(FillCli, WritesTheFilledDemOrOneLine) {
    const auto dir = fresh_dir("fill");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/jacksboro.tif", dir / "dem.tif");
    RunResult r = run_penink("fill dem.tif -o filled.tif --band-rows 50", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("fill: 403x344 nodes, "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("in 7 bands of 50 rows"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("fill: wrote filled.tif\n"), std::string::npos) << r.output;
    EXPECT_GT(fs::file_size(dir / "filled.tif"), 10000u);
    fs::remove(dir / "filled.tif");
    r = run_penink("fill dem.tif", dir);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output, "penink: cli: --output is required\n");
    r = run_penink("fill dem.tif -o ./dem.tif -q", dir);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output, "penink: fill: ./dem.tif: is the DEM dem.tif (an output never replaces an input)\n");
    // ulimit -f counts 1024-byte blocks: the filled DEM (about 150 KB) does not fit 20 KiB
    r = run_penink("", dir, "ulimit -f 20; '" PENINK_BINARY_PATH "' fill dem.tif -o f.tif -q");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output.rfind("penink: fill: f.tif: cannot write raster (", 0), 0u) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(file_count(dir), 1u) << "an output or a temporary was left";
}

}  // namespace
}  // namespace penink
