// The coastal example (examples/coast.toml: a window of the Jacksboro DEM with the sea at 350 m)
// rendered by the command: the coastline layer sits between surface and hachures and holds the
// shore; --sea-level sets (or overrides) the sea of a bare DEM, and without one the layer is
// written empty.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "cli_support.hpp"

using namespace penink::test;
namespace fs = std::filesystem;

namespace {

// The SVG's layer ids in order, and the paths of one layer.
std::vector<std::string> layer_ids(const std::string& svg) {
    std::vector<std::string> out;
    const std::regex re("inkscape:groupmode=\"layer\" inkscape:label=\"([^\"]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
        out.push_back((*it)[1]);
    return out;
}

std::size_t paths_in_layer(const std::string& svg, const std::string& layer) {
    const std::size_t at = svg.find("id=\"" + layer + "\"");
    if (at == std::string::npos) return 0;
    const std::size_t end = svg.find("</g>", at);
    std::size_t n = 0;
    for (std::size_t p = svg.find("<path", at); p < end; p = svg.find("<path", p + 1)) ++n;
    return n;
}

fs::path coast_dir(const std::string& name) {
    const fs::path dir = fresh_dir(name);
    for (const char* f : {"coast.asc", "coast.prj", "coast.toml"})
        fs::copy_file(fs::path(PENINK_SOURCE_DIR "/examples") / f, dir / f);
    return dir;
}

}  // namespace

TEST(CoastExample, RendersItsCoastlineLayer) {
    const fs::path dir = coast_dir("coast_example");
    const RunResult r = run_penink("render coast.toml -o coast.svg --width 500 --height 375", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "coast.svg");
    EXPECT_EQ(layer_ids(svg), (std::vector<std::string>{"surface", "coastline", "hachures", "ridges", "creases", "pels",
                                                        "textures", "feature-edges", "silhouettes"}));
    EXPECT_GE(paths_in_layer(svg, "coastline"), 3u);
    EXPECT_NE(svg.find("data-kind=\"coastline\""), std::string::npos);
    EXPECT_GE(paths_in_layer(svg, "creases"), 10u);  // the land keeps its creases
    // --sea-level overrides the scene's: under the DEM's lowest node (236 m) there is no shore
    const RunResult low = run_penink("render coast.toml -o low.svg --width 300 --height 225 --sea-level 200", dir);
    ASSERT_EQ(low.code, 0) << low.output;
    EXPECT_EQ(paths_in_layer(read_text(dir / "low.svg"), "coastline"), 0u);
    // and sets one on a bare DEM
    const RunResult bare = run_penink("render coast.asc -o bare.svg --width 300 --height 225 --sea-level 350", dir);
    ASSERT_EQ(bare.code, 0) << bare.output;
    EXPECT_GE(paths_in_layer(read_text(dir / "bare.svg"), "coastline"), 3u);
}

TEST(CoastExample, NoSeaLevelEmptyLayer) {
    const fs::path dir = coast_dir("coast_dry");
    const RunResult r = run_penink("render coast.asc -o dry.svg --width 300 --height 225", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "dry.svg");
    EXPECT_NE(svg.find("id=\"coastline\""), std::string::npos);
    EXPECT_EQ(paths_in_layer(svg, "coastline"), 0u);
    const RunResult bad = run_penink("render coast.asc -o x.svg --sea-level high", dir);
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.output.find("penink: cli: --sea-level:"), std::string::npos) << bad.output;
}
