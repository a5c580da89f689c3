// The plotter style's SVG is what a pen plotter needs: strokes only (no fill anywhere: the
// surface mask is gone), one pen per layer (a stroke colour on each layer's group, a different
// one for each, none on a path), and pen widths in millimetres on the page whatever its size.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include "cli_support.hpp"

namespace fs = std::filesystem;
using namespace penink::test;

TEST(PlotterStyleCli, StrokesOnlyOnePenPerLayerWidthsInMillimetres) {
    const auto dir = fresh_dir("plotter");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir / "volcano.prj");
    const std::map<std::string, double> pen_mm = {{"surface", 0.3}, {"coastline", 0.4}, {"hachures", 0.3}, {"ridges", 0.3}, {"creases", 0.3}, {"silhouettes", 0.5}};
    for (const std::string page : {"A4", "A3"}) {
        const RunResult r = run_penink("render volcano.asc --style plotter -o p.svg --page " + page, dir);
        ASSERT_EQ(r.code, 0) << r.output;
        const std::string svg = read_text(dir / "p.svg");
        EXPECT_EQ(svg.find("fill=\"#"), std::string::npos) << page << ": something is filled";
        std::smatch m;
        ASSERT_TRUE(std::regex_search(svg, m, std::regex("width=\"([0-9.]+)mm\" height=\"([0-9.]+)mm\" viewBox=\"[-0-9.]+ [-0-9.]+ ([0-9.]+) ")))
            << page;
        const double mm_per_unit = std::stod(m[1]) / std::stod(m[3]);
        std::set<std::string> colours;
        std::size_t layers = 0;
        const std::regex group("inkscape:label=\"([a-z-]+)\" id=\"[a-z-]+\" fill=\"none\" stroke=\"(#[0-9a-f]{6})\" stroke-width=\"([0-9.]+)\"");
        for (auto it = std::sregex_iterator(svg.begin(), svg.end(), group); it != std::sregex_iterator(); ++it) {
            ++layers;
            colours.insert((*it)[2]);
            const auto pen = pen_mm.find((*it)[1]);
            if (pen != pen_mm.end()) {
                EXPECT_NEAR(std::stod((*it)[3]) * mm_per_unit, pen->second, 0.001) << page << " " << (*it)[1];
            }
        }
        EXPECT_EQ(layers, 9u) << page;
        EXPECT_EQ(colours.size(), 9u) << page << ": one pen colour per layer";
        EXPECT_FALSE(std::regex_search(svg, std::regex("<path [^>]*stroke=\""))) << page << ": a path with its own pen";
        EXPECT_FALSE(std::regex_search(svg, std::regex("<path [^>]*stroke-width="))) << page << ": a path with its own width";
    }
    fs::remove_all(dir);
}
