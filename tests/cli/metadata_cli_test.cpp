// What every output says about itself: `penink --version`; the version in the metadata; a title
// and description from the scene (SVG <title>/<desc> and Dublin Core, PDF /Title and /Subject, PS
// %%Title); an EPS whose bounding box is the ink plus the margin (checked against Ghostscript's
// bbox device, which measures the ink); a perspective view saying, in every format, that it is not
// georeferenced.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>

#include "cli_support.hpp"

namespace fs = std::filesystem;
using namespace penink::test;

namespace {

// The four numbers of a "%%HiResBoundingBox:" line in `text`.
bool hires_box(const std::string& text, double box[4]) {
    const std::size_t at = text.find("%%HiResBoundingBox:");
    return at != std::string::npos &&
           std::sscanf(text.c_str() + at, "%%%%HiResBoundingBox: %lf %lf %lf %lf", &box[0], &box[1], &box[2], &box[3]) == 4;
}

// A fresh folder holding the volcano DEM and its .prj.
fs::path volcano_dir(const std::string& name) {
    const auto dir = fresh_dir(name);
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.asc", dir / "volcano.asc");
    fs::copy_file(PENINK_SOURCE_DIR "/examples/volcano.prj", dir / "volcano.prj");
    return dir;
}

}  // namespace

TEST(MetadataCli, VersionFlag) {
    const auto dir = fresh_dir("version");
    const RunResult r = run_penink("--version", dir);
    EXPECT_EQ(r.code, 0);
    EXPECT_TRUE(std::regex_match(r.output, std::regex("penink [0-9]+\\.[0-9]+\\.[0-9]+\n"))) << r.output;
}

TEST(MetadataCli, TitleDescriptionAndVersionInEveryFormat) {
    const auto dir = volcano_dir("metadata");
    const std::string version = run_penink("--version", dir).output.substr(0, run_penink("--version", dir).output.size() - 1);
    const RunResult r = run_penink("render volcano.asc --width 300 --height 225 -o a.svg -o a.pdf -o a.ps", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string title = "volcano.asc: pen-and-ink drawing";
    const std::string svg = read_text(dir / "a.svg");
    EXPECT_NE(svg.find("<title id=\"title\">" + title + "</title>"), std::string::npos);
    EXPECT_NE(svg.find("<desc id=\"desc\">Pen-and-ink drawing of the DEM volcano.asc by " + version), std::string::npos);
    EXPECT_NE(svg.find("<dc:title>" + title + "</dc:title>"), std::string::npos);
    EXPECT_NE(svg.find("<penink:param name=\"generator\">" + version + "</penink:param>"), std::string::npos);
    for (const char* ns : {"xmlns:rdf=", "xmlns:cc=", "xmlns:dc=", "xmlns:penink="}) EXPECT_NE(svg.find(ns), std::string::npos) << ns;
    const std::string pdf = read_text(dir / "a.pdf");
    EXPECT_NE(pdf.find("/Title (" + title + ")"), std::string::npos);
    EXPECT_NE(pdf.find("/Subject (Pen-and-ink drawing of the DEM volcano.asc"), std::string::npos);
    EXPECT_NE(pdf.find("/Creator (" + version + ")"), std::string::npos);
    const std::string ps = read_text(dir / "a.ps");
    EXPECT_NE(ps.find("%%Title: " + title + "\n"), std::string::npos);
    EXPECT_NE(ps.find("%%Creator: " + version + "\n"), std::string::npos);
    fs::remove_all(dir);
}

TEST(MetadataCli, EpsBoundingBoxIsTheInkPlusTheMargin) {
    const auto dir = volcano_dir("eps_bbox");
    const RunResult r = run_penink("render volcano.asc -o a.eps -o a.ps --page A4 --margin 5", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    double box[4], page[4], ink[4];
    ASSERT_TRUE(hires_box(read_text(dir / "a.eps"), box));
    ASSERT_TRUE(hires_box(read_text(dir / "a.ps"), page));
    EXPECT_NEAR(page[2], 841.89, 0.01);  // the PostScript page stays the A4 page (landscape)
    const RunResult gs = run_penink("", dir, "gs -q -dNOPAUSE -dBATCH -dSAFER -sDEVICE=bbox a.eps");
    ASSERT_EQ(gs.code, 0) << gs.output;
    ASSERT_TRUE(hires_box(gs.output, ink)) << gs.output;
    // the ink (Ghostscript measures what is painted) plus 5 mm (14.17 pt) on every side, within
    // a point (line caps, the white surface fill's pixel edges)
    const double margin = 5.0 * 72.0 / 25.4;
    EXPECT_NEAR(ink[0] - box[0], margin, 1.0);
    EXPECT_NEAR(ink[1] - box[1], margin, 1.0);
    EXPECT_NEAR(box[2] - ink[2], margin, 1.0);
    EXPECT_NEAR(box[3] - ink[3], margin, 1.0);
    EXPECT_LT(box[2] - box[0], page[2] - 100.0);  // much less than the page: the drawing is smaller
    fs::remove_all(dir);
}

// Inkscape (the editor the layered SVG is for) opens it without a warning and keeps penink's
// metadata and layers when it saves it again. Skipped where Inkscape is not installed (scripts/
// test.sh installs it).
TEST(MetadataCli, InkscapeOpensTheSvgWithoutWarnings) {
    if (std::system("command -v inkscape > /dev/null 2>&1") != 0) GTEST_SKIP() << "inkscape not installed";
    const auto dir = volcano_dir("inkscape");
    ASSERT_EQ(run_penink("render volcano.asc --width 300 --height 225 -o a.svg", dir).code, 0);
    const RunResult r = run_penink("", dir, "HOME='" + dir.string() + "' inkscape a.svg --export-type=svg --export-filename=b.svg");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("WARNING: unknown type"), std::string::npos) << r.output;
    const std::string saved = read_text(dir / "b.svg");
    EXPECT_NE(saved.find("name=\"generator\">penink "), std::string::npos);
    EXPECT_NE(saved.find("<dc:title>volcano.asc: pen-and-ink drawing</dc:title>"), std::string::npos);
    for (const char* layer : {"surface", "ridges", "creases", "silhouettes"})
        EXPECT_NE(saved.find(std::string("inkscape:label=\"") + layer + "\""), std::string::npos) << layer;
    fs::remove_all(dir);
}

TEST(MetadataCli, PerspectiveViewSaysItIsNotGeoreferencedAndWritesNoSideFiles) {
    const auto dir = volcano_dir("not_georeferenced");
    const RunResult r = run_penink("render volcano.asc --width 200 --height 150 -o a.svg -o a.pdf -o a.eps -o a.png", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string no = "no (perspective view)";
    EXPECT_NE(read_text(dir / "a.svg").find("<penink:param name=\"georeferenced\">" + no + "</penink:param>"), std::string::npos);
    const std::string pdf = read_text(dir / "a.pdf");
    EXPECT_NE(pdf.find("/penink_georeferenced (" + std::string("no \\(perspective view\\)") + ")"), std::string::npos);
    EXPECT_EQ(pdf.find("/VP"), std::string::npos);
    EXPECT_NE(read_text(dir / "a.eps").find("\n% penink georeferenced: " + no + "\n"), std::string::npos);
    for (const char* side : {"a.pgw", "a.wld", "a.png.aux.xml"}) EXPECT_FALSE(fs::exists(dir / side)) << side;
    fs::remove_all(dir);
}
