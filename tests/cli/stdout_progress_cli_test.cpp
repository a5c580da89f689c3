// `-o -` writes the drawing to standard output in the --format given (for a pipe into a plotting
// or layout tool), the same bytes a file of that format gets, beside any files; its mistakes are
// one-line errors before anything is drawn. Progress shows on a pipe only with --progress.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_support.hpp"

namespace fs = std::filesystem;
using namespace penink::test;

namespace {

fs::path volcano_dir(const std::string& name) {
    const auto dir = fresh_dir(name);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir / "volcano.prj");
    return dir;
}

const std::string binary = "'" PENINK_BINARY_PATH "'";

}  // namespace

TEST(StdoutCli, PipedDrawingIsTheFilesBytes) {
    const auto dir = volcano_dir("stdout");
    const std::string render = binary + " render volcano.asc --width 200 --height 150";
    ASSERT_EQ(run_penink("render volcano.asc --width 200 --height 150 -o a.svg -o a.pdf", dir).code, 0);
    for (const std::string f : {"svg", "pdf"}) {
        const RunResult r = run_penink("", dir, render + " -o - --format " + f + " > piped." + f);
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_EQ(r.output, "") << f;  // nothing but the drawing, and that on stdout
        EXPECT_EQ(read_text(dir / ("piped." + f)), read_text(dir / ("a." + f))) << f;
    }
    // beside a file: both written
    const RunResult both = run_penink("", dir, render + " -o - --format eps -o b.svg > piped.eps");
    ASSERT_EQ(both.code, 0) << both.output;
    EXPECT_EQ(read_text(dir / "b.svg"), read_text(dir / "a.svg"));
    EXPECT_EQ(read_text(dir / "piped.eps").rfind("%!PS-Adobe-3.0 EPSF-3.0\n", 0), 0u);
    fs::remove_all(dir);
}

TEST(StdoutCli, MistakesAreOneLineErrorsAndWriteNothing) {
    const auto dir = volcano_dir("stdout_errors");
    const std::size_t before = std::distance(fs::directory_iterator(dir), fs::directory_iterator());
    const std::pair<std::string, std::string> cases[] = {
        {"-o -", "penink: cli: -o - writes to standard output: say its format with --format svg|ps|eps|pdf\n"},
        {"-o a.svg --format svg",
         "penink: cli: --format names the format of -o - (standard output), which is not among the outputs\n"},
        {"-o - -o /dev/stdout --format svg", "penink: cli: standard output given more than once (-o -)\n"},
    };
    for (const auto& [args, message] : cases) {
        const RunResult r = run_penink("render volcano.asc --width 200 --height 150 " + args, dir);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(r.output, message) << args;
    }
    const RunResult png = run_penink("render volcano.asc -o - --format png", dir);
    EXPECT_EQ(png.code, 2);
    EXPECT_EQ(std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator())), before);
    fs::remove_all(dir);
}

TEST(StdoutCli, ProgressOnAPipeOnlyWhenAskedFor) {
    const auto dir = volcano_dir("progress");
    // the caches are built here: long steps with progress
    const RunResult plain = run_penink("render volcano.asc --width 200 --height 150 -o a.svg", dir);
    ASSERT_EQ(plain.code, 0) << plain.output;
    EXPECT_EQ(plain.output.find("penink: building"), std::string::npos) << plain.output;
    for (const char* cache : {"volcano.asc.dv", "volcano.asc.lod"}) fs::remove(dir / cache);
    const RunResult asked = run_penink("render volcano.asc --width 200 --height 150 -o a.svg --progress", dir);
    ASSERT_EQ(asked.code, 0) << asked.output;
    EXPECT_NE(asked.output.find("penink: building terrain cache: reading the DEM 0%\n"), std::string::npos) << asked.output;
    EXPECT_NE(asked.output.find("penink: building drainage database: "), std::string::npos) << asked.output;
    EXPECT_EQ(asked.output.find('\r'), std::string::npos);
    for (const char* cache : {"volcano.asc.dv", "volcano.asc.lod"}) fs::remove(dir / cache);
    const RunResult quiet = run_penink("render volcano.asc --width 200 --height 150 -o a.svg --progress -q", dir);
    ASSERT_EQ(quiet.code, 0) << quiet.output;
    EXPECT_EQ(quiet.output, "");
    fs::remove_all(dir);
}
