// Hostile inputs: each ends quickly with exit code 2, one line naming the real problem and the
// file or key, and no output file (nor temp file) left behind.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "cli_support.hpp"

using namespace penink::test;
namespace fs = std::filesystem;

namespace {

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";

// Every file under dir, recursively (an output left in a subfolder counts too).
std::size_t files_under(const fs::path& dir) {
    std::size_t n = 0;
    for (auto& e : fs::recursive_directory_iterator(dir)) n += e.is_regular_file();
    return n;
}

// Runs `args` in `dir`: exit code 2, the output exactly `line`, as many files as before, in under
// `seconds`.
void expect_refused(const fs::path& dir, const std::string& args, const std::string& line, double seconds = 5.0) {
    const std::size_t before = files_under(dir);
    const auto t0 = std::chrono::steady_clock::now();
    const RunResult r = run_penink(args, dir);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), seconds) << args;
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_EQ(r.output, line + "\n") << args;
    EXPECT_EQ(files_under(dir), before) << args << ": an output or temp file was left behind";
}

// As expect_refused, for a line whose middle depends on the machine: it starts with `head` and
// ends with `tail`.
void expect_refused_like(const fs::path& dir, const std::string& args, const std::string& head,
                         const std::string& tail) {
    const std::size_t before = files_under(dir);
    const RunResult r = run_penink(args, dir);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind(head, 0), 0u) << r.output;
    ASSERT_GE(r.output.size(), tail.size() + 1);
    EXPECT_EQ(r.output.substr(r.output.size() - tail.size() - 1), tail + "\n") << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(files_under(dir), before) << args << ": an output or temp file was left behind";
}

std::string grid(int cols, int rows, const std::string& values, double cellsize = 10) {
    return "ncols " + std::to_string(cols) + "\nnrows " + std::to_string(rows) +
           "\nxllcorner 0\nyllcorner 0\ncellsize " + std::to_string(cellsize) + "\nNODATA_value -9999\n" + values;
}

}  // namespace

TEST(HostileInputs, GridDeclaringHugeSizeWithFewValues) {
    const auto dir = fresh_dir("hostile_huge");
    write_text(dir / "huge.asc", grid(50000, 50000, "1 2 3 4 5 6 7 8\n"));
    const std::string line = "penink: input: huge.asc: ASCII grid declares 50000x50000 values but its 102 bytes hold at most 51";
    expect_refused(dir, "render huge.asc -o out.svg -o out.png", line, 1.0);
    expect_refused(dir, "drainage huge.asc", line, 1.0);
    write_text(dir / "huge.toml", "[terrain]\ndem = \"huge.asc\"\n");
    expect_refused(dir, "batch huge.toml --path " PENINK_SOURCE_DIR "/examples/volcano_flight.csv --out frames", line, 1.0);
    EXPECT_FALSE(fs::exists(dir / "frames"));
}

TEST(HostileInputs, DemBeyondMaxMemory) {
    const auto dir = fresh_dir("hostile_budget");
    fs::create_directories(dir / "dem");  // a copy without caches: their builds are counted
    fs::copy_file(volcano, dir / "dem" / "volcano.asc");
    expect_refused(dir, "render dem/volcano.asc -o out.svg --max-memory 1M",
                   "penink: input: dem/volcano.asc: drawing the DEM's 61x87 nodes would need about 102 MiB of memory, "
                   "1 MiB available (--max-memory)");
    // between the drawing's need without the drainage build (94 MiB) and with it (102 MiB): the
    // creases' build named, and how to draw the DEM without it
    expect_refused(dir, "render dem/volcano.asc -o out.svg --max-memory 98M",
                   "penink: drainage: dem/volcano.asc: the drainage grid of the creases and ridges at factor 5 (301x431 "
                   "points) would need about 102 MiB of memory, 98 MiB available (--max-memory); without creases and "
                   "ridges ([creases] and [ridges] enabled = false) the drawing needs about 94 MiB");
    expect_refused(dir, "render dem/volcano.asc -o out.svg --max-memory lots",
                   "penink: cli: --max-memory: expected a size such as 2G or 512M (got \"lots\")");
}

// The drainage database's build is counted only where a render would build it: with the DEM's
// caches there (`penink drainage` wrote them beside it), a budget that holds the drawing and the
// terrain cache's estimate but not the drainage build draws; once the DEM changes (its caches
// then of another DEM), the same budget refuses the render again.
TEST(HostileInputs, MaxMemoryCountsTheDrainageBuildOnlyWithoutItsCache) {
    const auto dir = fresh_dir("hostile_budget_cached");
    fs::create_directories(dir / "dem");
    fs::copy_file(volcano, dir / "dem" / "volcano.asc");
    const std::string refused = "penink: scene: dem/volcano.asc: drawing a 1000x750 image of the DEM's 61x87 nodes would "
                                "need about 125 MiB of memory, 120 MiB available (--max-memory)";
    expect_refused(dir, "render dem/volcano.asc -o out.svg --max-memory 120M", refused);
    ASSERT_EQ(run_penink("drainage dem/volcano.asc -q", dir).code, 0);
    ASSERT_TRUE(fs::exists(dir / "dem" / "volcano.asc.dv"));
    const RunResult r = run_penink("render dem/volcano.asc -o out.svg --max-memory 120M", dir);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "out.svg"));
    fs::remove(dir / "out.svg");
    {  // the DEM rewritten (another file with the same heights): its caches no longer its own
        const fs::path dem = dir / "dem" / "volcano.asc";
        fs::copy_file(dem, dir / "dem" / "copy.asc");
        fs::rename(dir / "dem" / "copy.asc", dem);
    }
    expect_refused(dir, "render dem/volcano.asc -o out.svg --max-memory 120M", refused);
}

TEST(HostileInputs, DrainageResampleBoundedByTheBudget) {
    const auto dir = fresh_dir("hostile_resample");
    fs::copy_file(volcano, dir / "volcano.asc");
    expect_refused_like(dir, "drainage volcano.asc --resample 1000",
                        "penink: drainage: volcano.asc: the drainage grid at factor 1000 (60001x86001 points) would "
                        "need about 307.6 GiB of memory, ",
                        " available (--max-memory)");
    expect_refused(dir, "drainage volcano.asc --resample 20 --max-memory 100M",
                   "penink: drainage: volcano.asc: the drainage grid at factor 20 (1201x1721 points) would need about "
                   "126 MiB of memory, 100 MiB available (--max-memory)");
    expect_refused(dir, "drainage volcano.asc --resample 1001",
                   "penink: cli: --resample: must be between 0 and 1000 (got \"1001\")");
}

TEST(HostileInputs, DashesFinerThanATenthOfAPixel) {
    const auto dir = fresh_dir("hostile_dash");
    write_text(dir / "tiny.toml", "[all]\ndash = [1e-30, 1e-30]\n");
    expect_refused(dir, "render " + volcano + " --style tiny.toml -o out.svg -o out.png",
                   "penink: style: tiny.toml: dash lengths must be 0 or at least 0.1 px (got 1e-30) (in [all])", 2.0);
}

TEST(HostileInputs, MeshCoordinatesBeyondRange) {
    const auto dir = fresh_dir("hostile_mesh");
    write_text(dir / "far.obj", "v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_refused(dir, "render far.obj -o out.svg",
                   "penink: input: far.obj: vertex 2 has coordinate 1e+308, out of range (mesh coordinates must be "
                   "finite and within +-1e9)", 2.0);
    write_text(dir / "far.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e38 0\n3 0 1 2\n");
    expect_refused(dir, "render far.off -o out.svg -o out.png",
                   "penink: input: far.off: vertex 3 has coordinate 1e+38, out of range (mesh coordinates must be "
                   "finite and within +-1e9)", 2.0);
}

TEST(HostileInputs, OutputsWrittenTogetherOrNotAtAll) {
    const auto dir = fresh_dir("hostile_outputs");
    fs::create_directory(dir / "x.png");
    expect_refused(dir, "render " + volcano + " -o first.svg -o x.png",
                   "penink: export: x.png: cannot write file (is a directory)", 2.0);
    expect_refused(dir, "render " + volcano + " -o first.svg -o b.png --dpi 5000",
                   "penink: export: b.png: PNG of 52083x39063 pixels is too large (lower --dpi)", 2.0);
    expect_refused(dir, "render " + volcano + " -o first.svg -o b.png --dpi 100000",
                   "penink: cli: --dpi: must be > 0 and at most 10000 (got \"100000\")", 2.0);
    expect_refused(dir, "render " + volcano + " -o first.svg -o b.pdf --page 100000x100000mm",
                   "penink: export: first.svg: page \"100000x100000mm\" is too large (at most 5000 mm a side)", 2.0);
    expect_refused(dir, "render " + volcano + " -o first.svg -o nodir/b.pdf",
                   "penink: export: nodir/b.pdf: cannot write file (no such directory)", 2.0);
    EXPECT_FALSE(fs::exists(dir / "first.svg"));
}

TEST(HostileInputs, ReadOnlySecondTargetLeavesNoFirst) {
    const auto dir = fresh_dir("hostile_readonly_out");
    fs::create_directory(dir / "ro");
    fs::permissions(dir, fs::perms::all);                     // anyone may write the test's folder
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                    fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
    const std::string args = "render " + volcano + " -o first.svg -o ro/b.svg";
    const std::size_t before = files_under(dir);
    const RunResult r = run_penink_unprivileged(args, dir);  // root writes anywhere
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output, "penink: export: ro/b.svg: cannot write file (Permission denied)\n");
    EXPECT_EQ(files_under(dir), before);
}

TEST(HostileInputs, ZeroOrNegativeCellSize) {
    const auto dir = fresh_dir("hostile_cellsize");
    const std::string values = "1 2 3\n4 5 6\n7 8 9\n";
    write_text(dir / "zero.asc", grid(3, 3, values, 0));
    expect_refused(dir, "render zero.asc -o out.svg", "penink: input: zero.asc: cell size must be > 0 (got 0)");
    write_text(dir / "negative.asc", grid(3, 3, values, -10));
    expect_refused(dir, "render negative.asc -o out.svg -o out.png",
                   "penink: input: negative.asc: cell size must be > 0 (got -10)");
    expect_refused(dir, "drainage negative.asc", "penink: input: negative.asc: cell size must be > 0 (got -10)");
}

TEST(HostileInputs, MessagesNameTheRealProblem) {
    const auto dir = fresh_dir("hostile_messages");
    write_text(dir / "big.asc", grid(3, 3, "1 2 3\n4 1e30 6\n7 8 9\n"));
    expect_refused(dir, "render big.asc -o out.svg",
                   "penink: input: big.asc: row 2, column 2 holds 1e+30: elevations must lie within +-1e6 (mark "
                   "missing cells with the nodata value)");
    write_text(dir / "inf.asc", grid(3, 3, "1.5 2 3\n4 inf 6\n7 8 9\n"));  // GDAL reads a float grid's inf as FLT_MAX
    expect_refused(dir, "render inf.asc -o out.svg",
                   "penink: input: inf.asc: row 2, column 2 holds 3.40282e+38: elevations must lie within +-1e6 "
                   "(mark missing cells with the nodata value)");
    write_text(dir / "one.asc", grid(3, 3, "-9999 -9999 -9999\n-9999 5 -9999\n-9999 -9999 -9999\n"));
    expect_refused(dir, "render one.asc -o out.svg",
                   "penink: input: one.asc: DEM has fewer than 2x2 valid nodes (no cell with data at its four corners)");
    const std::string dem = "[terrain]\ndem = \"" + volcano + "\"\n";
    write_text(dir / "ve.toml", dem + "vertical_exaggeration = 1e30\n");
    expect_refused(dir, "render ve.toml -o out.svg",
                   "penink: scene: ve.toml: vertical exaggeration must be > 0 and at most 1000 (got 1e+30)");
    write_text(dir / "veinf.toml", dem + "vertical_exaggeration = inf\n");
    expect_refused(dir, "render veinf.toml -o out.svg",
                   "penink: scene: veinf.toml: [terrain] vertical_exaggeration: expected a finite number");
    expect_refused(dir, "render " + volcano + " -o out.svg --vertical-exaggeration inf",
                   "penink: cli: --vertical-exaggeration: must be auto or > 0 and at most 1000 (got \"inf\")");
    write_text(dir / "light.toml", dem + "[light]\naltitude = -200\n");
    expect_refused(dir, "render light.toml -o out.svg",
                   "penink: scene: light.toml: [light] altitude must be between 0 and 90 degrees (got -200)");
    write_text(dir / "camera.toml", dem + "[camera]\naltitude = -200\n");
    expect_refused(dir, "render camera.toml -o out.svg",
                   "penink: scene: camera.toml: [camera] altitude must be between -90 and 90 degrees (got -200)");
    write_text(dir / "wide.toml", dem + "[camera]\nwidth = 2147483648\n");
    expect_refused(dir, "render wide.toml -o out.svg",
                   "penink: scene: wide.toml: [camera] width: must be an integer between -2147483647 and 16384 (got "
                   "2147483648)");
    expect_refused(dir, "render " + volcano + " -o out.svg --width 2147483648",
                   "penink: cli: --width: must be between 1 and 16384 (got \"2147483648\")");
    expect_refused(dir, "render " + volcano + " -o out.svg --dpi 0",
                   "penink: cli: --dpi: must be > 0 and at most 10000 (got \"0\")");
}

TEST(HostileInputs, FlightPathBytesThatAreNotUtf8AreEscaped) {
    const auto dir = fresh_dir("hostile_csv");
    write_text(dir / "path.csv", "position,elevation,azimuth,altitude\n\"1757270 5917440\",400,30,\xff\xfe\x01x\n");
    expect_refused(dir, "batch " + volcano + " --path path.csv --out frames",
                   "penink: batch: path.csv: line 2: altitude: not a number (\"\\xff\\xfe\\x01x\")");
    EXPECT_FALSE(fs::exists(dir / "frames"));
}

TEST(HostileInputs, SceneKeysMustBeKnown) {
    const auto dir = fresh_dir("hostile_keys");
    const std::string dem = "[terrain]\ndem = \"" + volcano + "\"\n";
    write_text(dir / "fvo.toml", dem + "[camera]\nfvo = 40\n");
    expect_refused(dir, "render fvo.toml -o out.svg",
                   "penink: scene: fvo.toml: unknown key fvo in [camera]; did you mean fov?");
    write_text(dir / "cameras.toml", dem + "[cameras]\nfov = 40\n");
    expect_refused(dir, "render cameras.toml -o out.svg",
                   "penink: scene: cameras.toml: unknown table [cameras]; did you mean [camera]?");
    write_text(dir / "scroe.toml", dem + "[creases]\nmin_scroe = 0.2\n");
    expect_refused(dir, "render scroe.toml -o out.svg",
                   "penink: scene: scroe.toml: unknown key min_scroe in [creases]; did you mean min_score?");
    write_text(dir / "zoom.toml", "zoom = 3\n" + dem);
    expect_refused(dir, "render zoom.toml -o out.svg", "penink: scene: zoom.toml: unknown key zoom");
    write_text(dir / "spacing.toml", dem + "[creases]\nspacing_px = -4\n");
    expect_refused(dir, "render spacing.toml -o out.svg",
                   "penink: scene: spacing.toml: [creases] spacing_px must be between 0 and 1000 (got -4)");
    write_text(dir / "light.toml", dem + "[light]\naltitude = 1000\n");
    expect_refused(dir, "render light.toml -o out.svg",
                   "penink: scene: light.toml: [light] altitude must be between 0 and 90 degrees (got 1000)");
    write_text(dir / "style.toml", dem + "[style]\n[style.ridges]\nwidht = 2\n");
    expect_refused(dir, "render style.toml -o out.svg",
                   "penink: style: style.toml: unknown key \"widht\" (in [ridges]); did you mean width?");
}

namespace {

// dir/ro: a copy of the volcano and its drainage cache, then made read-only (the test folder
// itself stays writable by anyone: run_penink_unprivileged's user writes there).
fs::path read_only_data(const fs::path& dir) {
    fs::create_directories(dir / "ro");
    fs::create_directories(dir / "home");
    fs::copy_file(volcano, dir / "ro" / "volcano.asc");
    const RunResult built = run_penink("drainage ro/volcano.asc -q -o ro/volcano.asc.dv", dir);
    EXPECT_EQ(built.code, 0) << built.output;
    for (const fs::path& p : {dir, dir / "home"}) fs::permissions(p, fs::perms::all);
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                    fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
    return dir / "ro";
}

std::size_t dv_files_under(const fs::path& dir) {
    std::size_t n = 0;
    for (auto& e : fs::recursive_directory_iterator(dir)) n += e.path().extension() == ".dv";
    return n;
}

}  // namespace

TEST(HostileInputs, DrainageIntoAReadOnlyFolderSaysWhy) {
    const auto dir = fresh_dir("hostile_drainage_ro");
    read_only_data(dir);
    const std::size_t before = files_under(dir);
    const RunResult r = run_penink_unprivileged("drainage ro/volcano.asc -q -o ro/other.dv", dir);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(r.output, "penink: drainage: ro/other.dv: cannot write drainage database (Permission denied)\n");
    EXPECT_EQ(files_under(dir), before);
    const RunResult nodir = run_penink("drainage ro/volcano.asc -q -o nodir/x.dv", dir);
    EXPECT_EQ(nodir.code, 2);
    EXPECT_EQ(nodir.output, "penink: drainage: nodir/x.dv: cannot write drainage database (no such directory)\n");
}

TEST(HostileInputs, DrainageOnAFullDiskSaysWhy) {
    const auto dir = fresh_dir("hostile_drainage_full");
    fs::create_directories(dir / "full");
    // a 64 KiB file system of its own (a private mount namespace: gone with the command)
    const std::string full = (dir / "full").string();
    const RunResult r = run_penink(
        "", dir,
        "unshare -m sh -c \"mount -t tmpfs -o size=64k tmpfs '" + full + "' && cp '" + volcano + "' '" + full +
            "/' && cd '" + full + "' && '" PENINK_BINARY_PATH "' drainage volcano.asc -q; echo rc=\\$?; ls\"");
    if (r.output.find("rc=") == std::string::npos) GTEST_SKIP() << "no private tmpfs here: " << r.output;
    EXPECT_EQ(r.output.substr(0, r.output.find("about")),
              "penink: drainage: volcano.asc.dv: cannot write drainage database (No space left on device: ");
    EXPECT_NE(r.output.find("needed, "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" free)\nrc=2\nvolcano.asc\n"), std::string::npos) << r.output;  // nothing else left
}

TEST(HostileInputs, CacheInAReadOnlyFolderIsReadNotRebuilt) {
    const auto dir = fresh_dir("hostile_cache_ro");
    read_only_data(dir);
    const RunResult r = run_penink_unprivileged("render ro/volcano.asc -o out.svg --width 200 --height 150 -v", dir);
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("penink: drainage: using cached ro/volcano.asc.dv ("), std::string::npos) << r.output;
    EXPECT_EQ(dv_files_under(dir / "home"), 0u) << "rebuilt into the user's cache";
    EXPECT_TRUE(fs::exists(dir / "out.svg"));
}

TEST(HostileInputs, StaleCacheThatCannotBeRewrittenIsBuiltInMemoryWithOneWarning) {
    const auto dir = fresh_dir("hostile_cache_stale");
    const fs::path ro = read_only_data(dir);
    fs::permissions(ro, fs::perms::owner_write, fs::perm_options::add);
    std::string text = read_text(ro / "volcano.asc");
    text.replace(text.find("cellsize"), 8, "cellsize 10.5\n#");  // the DEM changes: its cache is stale
    write_text(ro / "volcano.asc", text);
    fs::permissions(ro, fs::perms::owner_write, fs::perm_options::remove);
    const RunResult r = run_penink("", dir,
                                   ::geteuid() == 0
                                       ? "HOME=/nonexistent setpriv --reuid=65534 --regid=65534 --clear-groups '" PENINK_BINARY_PATH
                                         "' render ro/volcano.asc -o out.svg --width 200 --height 150"
                                       : "HOME=/nonexistent '" PENINK_BINARY_PATH "' render ro/volcano.asc -o out.svg --width 200 --height 150");
    EXPECT_EQ(r.code, 0) << r.output;
    const std::string warning = "penink: warning: drainage: /nonexistent/.cache/penink/volcano.asc-";
    ASSERT_NE(r.output.find(warning), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(warning, r.output.find(warning) + 1), std::string::npos) << "warned more than once";
    EXPECT_NE(r.output.find(".dv: cannot write the drainage cache; using the database built in memory (built again on "
                            "every run)\n"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(dir / "out.svg"));
}

TEST(HostileInputs, FuzzFindingsEndAsErrors) {
    const auto dir = fresh_dir("hostile_fuzz");
    write_text(dir / "early.ply", "ply\nformat ascii 1.0\nproperty float z\nelement vertex 1\nend_header\n0\n");
    expect_refused(dir, "render early.ply -o out.svg",
                   "penink: input: early.ply: not a mesh (PLY header: line 3: property before any element)");
    write_text(dir / "bad.toml", "[terrain]\ndem = 'v\x8b.asc'\n");
    expect_refused(dir, "render bad.toml -o out.svg",
                   "penink: scene: bad.toml: invalid TOML: not UTF-8 text (byte 19)");
}
