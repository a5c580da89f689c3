// `penink fill` through the binary: a filled GeoTIFF with its summary line; a missing -o, an
// output that would replace the DEM and a file-size limit each refused in one line, exit 2,
// leaving no file.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

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

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// `mpirun -n N penink fill` (the ranks as processes of this machine, through the MPI module):
// the very bytes of the one-process fill with 2 and 4 ranks; a bad DEM is one penink line from
// rank 0 and exit code 2 for the run, no file.
TEST(FillCli, MpiRanksWriteTheSameBytes) {
    const auto dir = fresh_dir("fill_mpi");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/jacksboro.tif", dir / "dem.tif");
    RunResult r = run_penink("fill dem.tif -o one.tif --band-rows 20 -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string one = file_bytes(dir / "one.tif");
    ASSERT_GT(one.size(), 10000u);
    // as root Open MPI asks for both variables; 4 ranks on fewer cores need --oversubscribe
    const std::string mpirun = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe ";
    for (const int n : {2, 4}) {
        const std::string out = "ranks" + std::to_string(n) + ".tif";
        r = run_penink("", dir, mpirun + "-n " + std::to_string(n) + " '" PENINK_BINARY_PATH "' fill dem.tif -o " + out +
                                     " --band-rows 20");
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("fill: " + std::to_string(n) + " ranks of "), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 3) << "rank 0 alone reports: " << r.output;
        EXPECT_TRUE(file_bytes(dir / out) == one) << n << " ranks";
    }
    write_text(dir / "bad.asc", "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 1e9 6\n7 8 9\n");
    r = run_penink("", dir, mpirun + "-n 2 '" PENINK_BINARY_PATH "' fill bad.asc -o bad.tif");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output.find("penink: "), r.output.rfind("penink: ")) << "one penink line: " << r.output;
    EXPECT_NE(r.output.find("penink: input: bad.asc: row 2, column 2 holds 1e+09"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "bad.tif"));
}

// How many times the dynamic loader's log of `command` (run in dir) names Open MPI's library.
int mpi_loads(const std::string& command, const fs::path& dir) {
    const RunResult r = run_penink("", dir, "LD_DEBUG=files LD_DEBUG_OUTPUT='" + (dir / "ld").string() + "' " + command);
    EXPECT_EQ(r.code, 0) << r.output;
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().filename().string().rfind("ld.", 0) != 0) continue;
        const std::string log = read_text(e.path());
        for (std::size_t at = log.find("file=libmpi.so"); at != std::string::npos; at = log.find("file=libmpi.so", at + 1)) ++n;
        fs::remove(e.path());
    }
    return n;
}

// Open MPI is loaded by a run an MPI launcher started, and by no other (the module penink_mpi.so).
TEST(FillCli, MpiLoadedOnlyUnderALauncher) {
    const auto dir = fresh_dir("fill_mpi_lazy");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "dem.asc");
    EXPECT_EQ(mpi_loads("'" PENINK_BINARY_PATH "' fill dem.asc -o a.tif -q", dir), 0);
    EXPECT_GT(mpi_loads("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -n 1 '" PENINK_BINARY_PATH
                        "' fill dem.asc -o b.tif -q",
                        dir),
              0);
    EXPECT_TRUE(fs::exists(dir / "a.tif"));
    EXPECT_TRUE(fs::exists(dir / "b.tif"));
}

}  // namespace
}  // namespace penink
