// `mpirun -n N penink drainage` (the ranks as processes of this machine, through the MPI module):
// the very bytes of the one-process database with 2 and 4 ranks, the depressions filled over the
// ranks at factor 1 (rank 0 says so) and by rank 0 alone at another factor, on a DEM with nodata
// too; a bad DEM is one penink line from rank 0 and exit code 2 for the run, no file.
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

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// as root Open MPI asks for both variables; 4 ranks on fewer cores need --oversubscribe
const std::string mpirun =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe ";

TEST(DrainageMpiCli, RanksWriteTheSameDatabase) {
    const auto dir = fresh_dir("drainage_mpi");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/jacksboro.tif", dir / "dem.tif");
    for (const char* factor : {"1", "3"}) {
        const std::string one_path = std::string("one-") + factor + ".dv";
        RunResult r = run_penink(std::string("drainage dem.tif --resample ") + factor + " -o " + one_path + " -q", dir);
        ASSERT_EQ(r.code, 0) << r.output;
        const std::string one = file_bytes(dir / one_path);
        ASSERT_GT(one.size(), 10000u);
        for (const int n : {2, 4}) {
            const std::string out = std::string("ranks") + std::to_string(n) + "-" + factor + ".dv";
            r = run_penink("", dir,
                           mpirun + "-n " + std::to_string(n) + " '" PENINK_BINARY_PATH "' drainage dem.tif --resample " +
                               factor + " -o " + out);
            ASSERT_EQ(r.code, 0) << r.output;
            // 344 rows over 2 ranks: 2 bands a rank of 96 rows; over 4: of 48 rows
            const std::string spread = "drainage: depressions filled over " + std::to_string(n) + " ranks of ";
            if (std::string(factor) == "1") {
                EXPECT_NE(r.output.find(spread), std::string::npos) << r.output;
                EXPECT_NE(r.output.find(n == 2 ? "in bands of 96 rows\n" : "in bands of 48 rows\n"), std::string::npos)
                    << r.output;
            } else {
                EXPECT_EQ(r.output.find(spread), std::string::npos) << "at factor 3 rank 0 fills: " << r.output;
            }
            EXPECT_EQ(r.output.find("drainage: wrote " + out + "\n"), r.output.rfind("drainage: wrote "))
                << "rank 0 alone reports: " << r.output;
            EXPECT_TRUE(file_bytes(dir / out) == one) << n << " ranks, factor " << factor;
        }
    }
    // nodata inside the grid (a hole across band edges, scattered cells) and pits: the ranks read
    // their bands without the opening pass that gives nodata nodes the lowest height
    std::string asc = "ncols 90\nnrows 77\nxllcorner 500000\nyllcorner 4000000\ncellsize 10\nNODATA_value -9999\n";
    for (int r = 0; r < 77; ++r) {
        for (int c = 0; c < 90; ++c) {
            const bool hole = (r > 30 && r < 44 && c > 20 && c < 35) || (r * 7 + c * 13) % 97 == 0;
            const int z = 300 - 2 * r + (c * 37 + r * 11) % 23 - ((r % 19 == 9 && c % 17 == 8) ? 40 : 0);
            asc += hole ? "-9999 " : std::to_string(z) + " ";
        }
        asc += "\n";
    }
    write_text(dir / "holes.asc", asc);
    RunResult one = run_penink("drainage holes.asc --resample 1 -o holes-one.dv -q", dir);
    ASSERT_EQ(one.code, 0) << one.output;
    one = run_penink("", dir, mpirun + "-n 3 '" PENINK_BINARY_PATH "' drainage holes.asc --resample 1 -o holes-ranks.dv");
    ASSERT_EQ(one.code, 0) << one.output;
    EXPECT_NE(one.output.find("depressions filled over 3 ranks of "), std::string::npos) << one.output;
    EXPECT_TRUE(file_bytes(dir / "holes-ranks.dv") == file_bytes(dir / "holes-one.dv"));
    write_text(dir / "bad.asc", "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 1e9 6\n7 8 9\n");
    const RunResult r = run_penink("", dir, mpirun + "-n 2 '" PENINK_BINARY_PATH "' drainage bad.asc -o bad.dv");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output.find("penink: "), r.output.rfind("penink: ")) << "one penink line: " << r.output;
    EXPECT_NE(r.output.find("penink: input: bad.asc: row 2, column 2 holds 1e+09"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "bad.dv"));
}

}  // namespace
}  // namespace penink
