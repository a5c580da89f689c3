// Hostile sizes and values refused up front with one line: an image beyond --max-memory, a map
// scale wider than the Earth, a mesh vertex that is not a number.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
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
    // 16384² pixels at 32 B (render_bytes_per_pixel) = 8 GiB, with the DEM's caches' builds (102 MiB)
    expect_refused(dir, "render " + volcano_asc + " --width 16384 --height 16384 --max-memory 2G -o big.png",
                   "penink: scene: " + volcano_asc + ": drawing a 16384x16384 image of the DEM's 61x87 nodes would need "
                   "about 8.1 GiB of memory, 2.0 GiB available (--max-memory)");
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

TEST(BoundedInputs, AFileSizeLimitIsAWriteError) {
    const auto dir = fresh_dir("bounded_fsize");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    // ulimit -f counts 1024-byte blocks: the 6.6 MB database does not fit 100 KiB
    RunResult r = run_penink("", dir, "ulimit -f 100; '" PENINK_BINARY_PATH "' drainage volcano.asc -o x.dv -q");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output, "penink: drainage: x.dv: cannot write drainage database (File too large)\n");
    EXPECT_EQ(file_count(dir), 1u) << "a temporary was left";
    fs::copy_file(volcano_asc, dir / "again.asc");  // no caches to write: only the outputs meet the limit
    r = run_penink("", dir, "ulimit -f 10; '" PENINK_BINARY_PATH "' render again.asc -o big.svg -o b.png -q 2>&1 | grep -v warning");
    EXPECT_NE(r.output.find("penink: export: big.svg: cannot write file (File too large)\n"), std::string::npos) << r.output;
    for (const char* f : {"big.svg", "b.png"}) EXPECT_FALSE(fs::exists(dir / f)) << f;
    for (auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".penink-"), std::string::npos) << e.path();
}

TEST(BoundedInputs, NoThreadToStartIsOneLine) {
    if (::geteuid() != 0 && std::system("command -v prlimit >/dev/null") != 0) GTEST_SKIP() << "prlimit not installed";
    const auto dir = fresh_dir("bounded_nproc");
    fs::permissions(dir, fs::perms::all);
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    fs::permissions(dir / "volcano.asc", fs::perms::all);
    // root is not held to RLIMIT_NPROC: the run is made as nobody where the tests run as root
    const std::string as = ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
    for (const char* n : {"1", "3"}) {
        const RunResult r = run_penink("", dir, "HOME='" + dir.string() + "' timeout 60 " + as + "prlimit --nproc=" + n +
                                                    " '" PENINK_BINARY_PATH "' render volcano.asc -o out.svg");
        EXPECT_EQ(r.code, 2) << n << ": " << r.output;
        EXPECT_EQ(r.output, "penink: cli: cannot start a thread (Resource temporarily unavailable): raise the process "
                            "limit (ulimit -u)\n") << n;
        EXPECT_FALSE(fs::exists(dir / "out.svg"));
    }
}

TEST(BoundedInputs, AFlightPathLineIsBounded) {
    const auto dir = fresh_dir("bounded_csv_line");
    fs::copy_file(volcano_asc, dir / "volcano.asc");
    // one 15 MB line (under the 16 MiB file cap): a crash in the field parsers before the bound
    write_text(dir / "long.csv", "position,elevation,azimuth,altitude\n\"" + std::string(15000000, '1') + "\",100,0,-20\n");
    expect_refused(dir, "batch volcano.asc --path long.csv --out frames",
                   "penink: batch: long.csv: line 2: 15000012 bytes, more than the 4096 a line may have");
    EXPECT_FALSE(fs::exists(dir / "frames"));
}

TEST(BoundedInputs, ALongThinDemIsRefusedByItsPyramid) {
    const auto dir = fresh_dir("bounded_thin");
    // 2 x 100 000 nodes: few nodes, but the level-of-detail pyramid's padded square is
    // (2^17 + 1)^2 errors, whose build holds strips of it (lod_errors_bytes; the cache stores the
    // DEM's 200 000 alone): 4.1 GiB (std::bad_alloc before the estimate counted it)
    std::string grid = "ncols 2\nnrows 100000\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n";
    for (int r = 0; r < 100000; ++r) grid += std::to_string(r % 7) + " " + std::to_string(r % 5) + "\n";
    write_text(dir / "thin.asc", grid);
    expect_refused(dir, "render thin.asc -o thin.svg --max-memory 1G",
                   "penink: input: thin.asc: drawing the DEM's 2x100000 nodes would need about 4.1 GiB of memory, 1.0 GiB "
                   "available (--max-memory)");
}
