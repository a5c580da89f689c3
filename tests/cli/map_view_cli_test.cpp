// `penink render --map`, `--scale 1:N` and `--vertical-exaggeration auto` from the command line:
// a plan view at a scale on a page writes its files and records the view; what cannot be a map
// is one error line, exit 2, no output.
#include <gtest/gtest.h>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";
const std::string house = PENINK_SOURCE_DIR "/examples/house.toml";

}  // namespace

TEST(MapViewCli, PlanViewAtAScaleOnAPage) {
    const auto dir = fresh_dir("map_page");
    const RunResult r = run_penink("render '" + volcano + "' --map --scale 1:10000 --page A5 --dpi 100 -o m.svg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "m.svg");
    // A5 landscape at 100 dpi: 210 x 148 mm = 827 x 583 px (whole pixels); the page holds them at
    // min(210/827, 148/583) = 0.25386 mm a pixel, so 1:10 000 makes the image 2099.42 m across.
    EXPECT_NE(svg.find("altitude -90, orthographic, 2099.41"), std::string::npos);
    EXPECT_NE(svg.find(", 827x583"), std::string::npos);
    EXPECT_NE(svg.find("map scale 1:10000"), std::string::npos);
    EXPECT_NE(svg.find("vertical_exaggeration 1 (auto)"), std::string::npos);
}

TEST(MapViewCli, VerboseSaysTheChosenExaggeration) {
    const auto dir = fresh_dir("map_auto");
    const RunResult r = run_penink("render '" + volcano + "' --vertical-exaggeration auto --width 200 --height 150 -o a.svg -v", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("penink: relief 101 m over 860 m: vertical exaggeration 1 (auto)"), std::string::npos) << r.output;
    const RunResult n = run_penink("render '" + volcano + "' --vertical-exaggeration 3 --width 200 --height 150 -o n.svg -v", dir);
    ASSERT_EQ(n.code, 0) << n.output;
    EXPECT_EQ(n.output.find("(auto)"), std::string::npos);
    EXPECT_NE(read_text(dir / "n.svg").find("vertical_exaggeration 3,"), std::string::npos);
}

TEST(MapViewCli, WhatCannotBeAMapIsAnError) {
    const auto dir = fresh_dir("map_errors");
    RunResult r = run_penink("render '" + volcano + "' --scale 1:5000 -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: " + volcano +
                            ": a map scale needs an orthographic view ([camera] projection = \"orthographic\", or --map)\n");
    r = run_penink("render '" + volcano + "' --map --scale 1:abc -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("must be a map scale 1:N"), std::string::npos) << r.output;
    r = run_penink("render '" + volcano + "' --vertical-exaggeration flat -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("must be auto or > 0 and at most 1000 (got \"flat\")"), std::string::npos) << r.output;
    write_text(dir / "p.toml", "[terrain]\ndem = '" + volcano + "'\n[camera]\nprojection = 'isometric'\n");
    r = run_penink("render p.toml -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: p.toml: [camera] projection must be \"perspective\" or \"orthographic\" (got \"isometric\")\n");
    write_text(dir / "e.toml", "[terrain]\ndem = '" + volcano + "'\nvertical_exaggeration = 'lots'\n");
    r = run_penink("render e.toml -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: e.toml: [terrain] vertical_exaggeration: expected a number or \"auto\"\n");
    r = run_penink("render '" + house + "' --map -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("orthographic views are for DEMs"), std::string::npos) << r.output;
    EXPECT_EQ(file_count(dir), 2u);  // the two scene files: no output left
}
