// The furniture of `penink render --map` (lines/map_furniture.hpp, scene/map_furniture.hpp) read
// back from the files: the scale bar's length against the map scale on the page and against the
// image's metres per pixel (within 0.5 %), the north arrow against GeographicLib's meridian
// convergence at the map's centre (within 0.1 degrees; Jacksboro lies 2.85 degrees east of UTM
// 16N's central meridian, where it is 1.70 degrees), the five furniture layers in SVG, EPS and PDF
// above the drawing's, the text extractable from the PDF, and the crop said on stderr.
#include <cmath>
#include <cstdio>
#include <sstream>

#include <GeographicLib/UTMUPS.hpp>
#include <gtest/gtest.h>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

const std::string jacksboro = PENINK_SOURCE_DIR "/tests/data/jacksboro.asc";
constexpr double pi = 3.14159265358979323846;

// The points of the first <path> whose data-kind is `kind` ("M x y L x y ...").
std::vector<std::pair<double, double>> path_points(const std::string& svg, const std::string& kind) {
    const std::size_t k = svg.find("data-kind=\"" + kind + "\"");
    if (k == std::string::npos) return {};
    const std::size_t d = svg.rfind("<path d=\"", k);
    const std::size_t end = svg.find('"', d + 9);
    std::string text = svg.substr(d + 9, end - d - 9);
    for (char& c : text)
        if (c == 'M' || c == 'L' || c == 'Z') c = ' ';
    std::istringstream in(text);
    std::vector<std::pair<double, double>> pts;
    double x = 0, y = 0;
    while (in >> x >> y) pts.emplace_back(x, y);
    return pts;
}

// The text of every <text> of data-kind `kind`, in order.
std::vector<std::string> texts(const std::string& svg, const std::string& kind) {
    std::vector<std::string> out;
    const std::string key = "data-kind=\"" + kind + "\">";
    for (std::size_t k = svg.find(key); k != std::string::npos; k = svg.find(key, k + 1)) {
        const std::size_t from = k + key.size();
        out.push_back(svg.substr(from, svg.find("</text>", from) - from));
    }
    return out;
}

double number_after(const std::string& s, const std::string& key) {
    const std::size_t k = s.find(key);
    return k == std::string::npos ? NAN : std::stod(s.substr(k + key.size()));
}

std::vector<double> geotransform(const std::string& svg) {
    const std::string key = "<penink:param name=\"geotransform\">";
    const std::size_t k = svg.find(key);
    std::istringstream in(svg.substr(k + key.size()));
    std::vector<double> g(6);
    for (double& v : g) in >> v;
    return g;
}

// Metres of ground the scale bar says it is: its last label times its unit.
double bar_metres(const std::string& svg) {
    const std::vector<std::string> labels = texts(svg, "scale-label"), unit = texts(svg, "scale-unit");
    if (labels.empty() || unit.size() != 1) return NAN;
    const double u = unit[0] == "km" ? 1000.0 : unit[0] == "m" ? 1.0 : NAN;
    return std::stod(labels.back()) * u;
}

}  // namespace

TEST(MapFurnitureCli, JacksboroAtOneToOneHundredThousandOnA5) {
    const auto dir = fresh_dir("furniture_a5");
    const RunResult r = run_penink("render '" + jacksboro +
                                       "' --map --scale 1:100000 --page A5 --dpi 100 --grid map --title 'Jacksboro, Tennessee' "
                                       "-o m.svg -o m.pdf -o m.eps -q",
                                   dir);
    ASSERT_EQ(r.code, 0) << r.output;
    // 1:100 000 on A5 (210 x 148 mm = 21 x 14.8 km) crops the 30 x 32 km DEM, and says so
    EXPECT_NE(r.output.find("penink: warning: at 1:100000 the map shows part of the DEM: rows "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" (map x "), std::string::npos) << r.output;
    const std::string svg = read_text(dir / "m.svg");
    // the layers, the furniture above the drawing's, in the conventions' order
    std::size_t at = svg.find("id=\"silhouettes\"");
    ASSERT_NE(at, std::string::npos);
    for (const char* name : {"neatline", "grid", "scale-bar", "north-arrow", "title"}) {
        const std::size_t next = svg.find("inkscape:label=\"" + std::string(name) + "\" id=\"" + name + "\"");
        ASSERT_NE(next, std::string::npos) << name;
        EXPECT_GT(next, at) << name;
        at = next;
    }
    // the bar on the page: its length in SVG user units (image pixels) times mm per unit
    const double page_mm = number_after(svg, "width=\""), view_w = [&] {
        std::istringstream in(svg.substr(svg.find("viewBox=\"") + 9));
        double x, y, w;
        in >> x >> y >> w;
        return w;
    }();
    const auto bar = path_points(svg, "scale-bar");
    ASSERT_EQ(bar.size(), 2u);
    const double bar_px = bar[1].first - bar[0].first;
    const double on_page_m = bar_px * (page_mm / view_w) / 1000.0 * 100000.0;
    const double said_m = bar_metres(svg);
    EXPECT_NEAR(on_page_m / said_m, 1.0, 0.005) << bar_px << " px, " << said_m << " m";
    const std::vector<double> g = geotransform(svg);
    EXPECT_NEAR(bar_px * g[1] / said_m, 1.0, 0.005);
    EXPECT_EQ(texts(svg, "scale-ratio"), std::vector<std::string>{"1:100 000"});
    // the arrow against GeographicLib's convergence at the map's centre (the neatline's middle)
    const auto neat = path_points(svg, "neatline");
    ASSERT_EQ(neat.size(), 5u);
    const double cx = 0.5 * (neat[0].first + neat[2].first), cy = 0.5 * (neat[0].second + neat[2].second);
    const double x = g[0] + cx * g[1] + cy * g[2], y = g[3] + cx * g[4] + cy * g[5];
    double lat = 0, lon = 0, gamma = 0, k = 0;
    GeographicLib::UTMUPS::Reverse(16, true, x, y, lat, lon, gamma, k);
    EXPECT_GT(gamma, 1.5);  // well away from the central meridian
    const auto arrow = path_points(svg, "north-arrow");
    ASSERT_EQ(arrow.size(), 2u);
    const double clockwise = std::atan2(arrow[1].first - arrow[0].first, -(arrow[1].second - arrow[0].second)) * 180.0 / pi;
    EXPECT_NEAR(clockwise, -gamma, 0.1);
    EXPECT_FALSE(texts(svg, "grid-label").empty());
    EXPECT_EQ(texts(svg, "title"), std::vector<std::string>{"Jacksboro, Tennessee"});
    // EPS layers and the PDF's optional content groups, and its text
    const std::string eps = read_text(dir / "m.eps"), pdf = read_text(dir / "m.pdf");
    for (const char* name : {"neatline", "grid", "scale-bar", "north-arrow", "title"}) {
        EXPECT_NE(eps.find("%%BeginLayer: " + std::string(name) + "\n"), std::string::npos) << name;
        EXPECT_NE(pdf.find("/Type /OCG /Name (" + std::string(name) + ")"), std::string::npos) << name;
    }
    EXPECT_NE(eps.find("(Jacksboro, Tennessee) show"), std::string::npos);
    const RunResult text = run_penink("", dir, "pdftotext m.pdf -");
    ASSERT_EQ(text.code, 0) << text.output;
    for (const char* word : {"Jacksboro, Tennessee", "km", "1:100 000", "N"})
        EXPECT_NE(text.output.find(word), std::string::npos) << word << " in " << text.output;
}

TEST(MapFurnitureCli, PlanViewDefaultsOffSwitchAndObliqueViews) {
    const auto dir = fresh_dir("furniture_defaults");
    RunResult r = run_penink("render '" + jacksboro + "' --map --width 600 --height 500 -o m.svg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output, "");  // the whole DEM: nothing cropped, nothing said
    std::string svg = read_text(dir / "m.svg");
    // neatline, scale bar and north arrow on; no grid, no title; the bar against the image's
    // metres per pixel
    EXPECT_EQ(path_points(svg, "neatline").size(), 5u);
    const auto bar = path_points(svg, "scale-bar");
    ASSERT_EQ(bar.size(), 2u);
    EXPECT_NEAR((bar[1].first - bar[0].first) * geotransform(svg)[1] / bar_metres(svg), 1.0, 0.005);
    EXPECT_EQ(path_points(svg, "north-arrow").size(), 2u);
    EXPECT_EQ(svg.find("data-kind=\"grid-tick\""), std::string::npos);
    EXPECT_NE(svg.find("id=\"title\""), std::string::npos);
    EXPECT_TRUE(texts(svg, "title").empty());
    // switched off: the layers are still written, empty
    r = run_penink("render '" + jacksboro + "' --map --width 600 --height 500 --no-furniture -o n.svg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    svg = read_text(dir / "n.svg");
    EXPECT_NE(svg.find("id=\"scale-bar\""), std::string::npos);
    EXPECT_EQ(svg.find("data-kind=\"scale-bar\""), std::string::npos);
    EXPECT_EQ(svg.find("data-kind=\"neatline\""), std::string::npos);
    // a scene's [map] keys
    write_text(dir / "s.toml", "[terrain]\ndem = '" + jacksboro +
                                   "'\n[camera]\nprojection = 'orthographic'\naltitude = -90\nazimuth = 0\nwidth = 600\nheight = 500\n"
                                   "[map]\nnorth_arrow = false\ngrid = 'graticule'\ntitle = 'Caryville'\nunits = 'imperial'\n");
    r = run_penink("render s.toml -o s.svg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    svg = read_text(dir / "s.svg");
    EXPECT_EQ(svg.find("data-kind=\"north-arrow\""), std::string::npos);
    EXPECT_EQ(texts(svg, "title"), std::vector<std::string>{"Caryville"});
    const std::vector<std::string> unit = texts(svg, "scale-unit");
    ASSERT_EQ(unit.size(), 1u);
    EXPECT_TRUE(unit[0] == "mi" || unit[0] == "ft") << unit[0];
    const std::vector<std::string> grid = texts(svg, "grid-label");
    ASSERT_FALSE(grid.empty());
    for (const std::string& l : grid) EXPECT_NE(l.find("\xC2\xB0"), std::string::npos) << l;  // degrees
    write_text(dir / "bad.toml", "[terrain]\ndem = '" + jacksboro + "'\n[map]\ngrid = 'utm'\n");
    r = run_penink("render bad.toml -o b.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: bad.toml: [map] grid must be \"none\", \"map\" or \"graticule\" (got \"utm\")\n");
    // an oblique view is no map: no furniture layers
    r = run_penink("render '" + jacksboro + "' --width 200 --height 150 -o o.svg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    svg = read_text(dir / "o.svg");
    EXPECT_NE(svg.find("id=\"silhouettes\""), std::string::npos);
    EXPECT_EQ(svg.find("id=\"neatline\""), std::string::npos);
}
