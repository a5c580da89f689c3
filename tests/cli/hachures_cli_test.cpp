// The hachures layer through `penink render`: on by default for a DEM (paths of data-kind
// "hachure" in the layer between coastline and ridges), off with [hachures] enabled = false (the
// layer still written, empty), and one-line errors for a bad [hachures] key or value.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "cli_support.hpp"

using namespace penink::test;
namespace fs = std::filesystem;

namespace {

std::size_t hachure_paths(const std::string& svg) {
    const std::size_t begin = svg.find("id=\"hachures\""), end = svg.find("id=\"ridges\"");
    if (begin == std::string::npos || end == std::string::npos || end < begin) return 0;
    const std::string layer = svg.substr(begin, end - begin);
    std::size_t n = 0;
    for (std::size_t at = layer.find("data-kind=\"hachure\""); at != std::string::npos; at = layer.find("data-kind=\"hachure\"", at + 1)) ++n;
    return n;
}

}  // namespace

TEST(HachuresCli, OnByDefaultOffWhenDisabled) {
    const auto dir = fresh_dir("hachures");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir / "volcano.prj");
    RunResult r = run_penink("render volcano.asc --map --width 300 --height 300 -o a.svg", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_GT(hachure_paths(read_text(dir / "a.svg")), 100u);  // measured 600-700 at this size
    write_text(dir / "off.toml", "[terrain]\ndem = \"volcano.asc\"\n[hachures]\nenabled = false\n");
    r = run_penink("render off.toml --map --width 300 --height 300 -o b.svg", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "b.svg");
    EXPECT_NE(svg.find("id=\"hachures\""), std::string::npos);
    EXPECT_EQ(hachure_paths(svg), 0u);
    fs::remove_all(dir);
}

TEST(HachuresCli, BadKeysAndValuesAreOneLineErrors) {
    const auto dir = fresh_dir("hachures_errors");
    const struct {
        const char* table;
        const char* message;
    } cases[] = {
        {"tone = \"dark\"", "penink: scene: s.toml: [hachures] tone must be \"light\", \"slope\" or \"blend\" (got \"dark\")"},
        {"contrst = 2", "penink: scene: s.toml: unknown key contrst in [hachures]; did you mean contrast?"},
        {"spacing_min_px = 0.1", "penink: scene: s.toml: [hachures] spacing_min_px must be between 0.5 and 1000 (got 0.1)"},
        {"spacing_max_px = 1", "penink: scene: s.toml: [hachures] spacing_max_px must be between 1.6 and 1000 (got 1)"},
        {"enabled = 1", "penink: scene: s.toml: [hachures] enabled: must be true or false"},
    };
    for (const auto& c : cases) {
        write_text(dir / "s.toml", std::string("[terrain]\ndem = \"x.asc\"\n[hachures]\n") + c.table + "\n");
        const RunResult r = run_penink("render s.toml -o a.svg", dir);
        EXPECT_EQ(r.code, 2) << c.table;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir / "a.svg"));
    }
    fs::remove_all(dir);
}
