// Tapered and weighted strokes (styles/README.md, "Weight"): the written SVG and PDF outlines
// are thin at the ends and full in the middle, the SVG keeps an editable power stroke, weights
// scale widths, and untapered styles write today's plain strokes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "core/polyline_simplify.hpp"
#include "export/export_drawing.hpp"
#include "export/rasterise.hpp"
#include "export/stroke_outline.hpp"
#include "export/styled_drawing.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;

namespace {

// One straight crease from (10, 50) to (110, 50), 100 px long.
Drawing one_crease(std::vector<float> weight = {}) {
    Drawing d;
    d.width = 120, d.height = 100;
    Stroke s = make_stroke({{10, 50}, {60, 50}, {110, 50}}, {100, 100, 100}, 0.5f, "crease");
    s.weight = std::move(weight);
    d.layer(LayerKind::creases).strokes.push_back(s);
    return d;
}

Style tapered_style() {
    Style s = default_style();
    apply_style_overrides(s, R"(
        [creases]
        width = 4.0
        taper = 10.0
        taper_min = 0.0
        weight_min = 1.0
        weight_max = 1.0
    )");
    return s;
}

std::vector<glm::vec2> numbers_as_points(const std::string& text) {
    std::vector<glm::vec2> out;
    std::istringstream in(text);
    std::string tok;
    std::vector<float> v;
    while (in >> tok) {
        if (tok == "M" || tok == "L" || tok == "Z" || tok == "m" || tok == "l" || tok == "h") continue;
        for (char& c : tok)
            if (c == 'M' || c == 'L' || c == 'Z') c = ' ';
        std::istringstream t(tok);
        float x;
        while (t >> x) v.push_back(x);
    }
    for (std::size_t i = 0; i + 1 < v.size(); i += 2) out.emplace_back(v[i], v[i + 1]);
    return out;
}

// Half the outline's thickness across x in [x0, x1]: the largest |y - 50| of its points there.
double half_width_near(const std::vector<glm::vec2>& outline, float x0, float x1) {
    double h = 0.0;
    for (const glm::vec2& p : outline)
        if (p.x >= x0 && p.x <= x1) h = std::max(h, double(std::abs(p.y - 50.0f)));
    return h;
}

// The filled outline of a tapered stroke of width 4 over 10 px: from 10 px in half the width,
// 2 px; within 1.5 px of an end (the ease 1 - (1 - u)^2 at u = 0.15 gives 0.28 of the width, and
// the round cap of a zero end adds nothing) under 0.6 px.
void expect_tapered(const std::vector<glm::vec2>& outline) {
    ASSERT_GT(outline.size(), 14u);  // caps and taper (points within 0.02 px of a chord left out)
    // the full width from 10 px in (the straight middle keeps only its ends: points within
    // 0.02 px of a chord are left out)
    EXPECT_NEAR(half_width_near(outline, 19.9f, 100.1f), 2.0, 0.01);
    EXPECT_LT(half_width_near(outline, 9.0f, 11.5f), 0.6);
    EXPECT_LT(half_width_near(outline, 108.5f, 111.0f), 0.6);
    EXPECT_GT(half_width_near(outline, 14.0f, 16.0f), 1.0);  // 5 px in: 0.75 of the width
}

}  // namespace

TEST(TaperFactor, EndsThinMiddleFull) {
    EXPECT_DOUBLE_EQ(taper_factor(0.0, 100.0, 10.0, 0.2), 0.2);
    EXPECT_DOUBLE_EQ(taper_factor(100.0, 100.0, 10.0, 0.2), 0.2);
    EXPECT_DOUBLE_EQ(taper_factor(10.0, 100.0, 10.0, 0.2), 1.0);
    EXPECT_DOUBLE_EQ(taper_factor(50.0, 100.0, 10.0, 0.2), 1.0);
    EXPECT_DOUBLE_EQ(taper_factor(5.0, 100.0, 10.0, 0.0), 0.75);  // 1 - (1 - 0.5)^2
    EXPECT_DOUBLE_EQ(taper_factor(4.0, 8.0, 10.0, 0.0), 1.0);     // a short stroke: half its length
    EXPECT_DOUBLE_EQ(taper_factor(3.0, 100.0, 0.0, 0.0), 1.0);    // no taper
}

TEST(TaperedStrokes, SvgOutlineThinAtTheEndsWithItsPowerStroke) {
    TempDir dir;
    const std::string path = (dir.path / "t.svg").string();
    export_drawing(style_drawing(one_crease(), tapered_style()), PageOptions{}, path);
    const std::string svg = read_text(path);
    // the layer fills in the pen's colour and strokes none; the path inherits both
    EXPECT_NE(svg.find("id=\"creases\" fill=\"#000000\" stroke=\"none\""), std::string::npos);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(svg, m, std::regex("<path d=\"([^\"]+)\" "
                                                     "inkscape:path-effect=\"#(powerstroke-0)\" "
                                                     "inkscape:original-d=\"([^\"]+)\"[^>]*data-kind=\"crease\"[^>]*"
                                                     "data-widths=\"([^\"]+)\"/>")));
    expect_tapered(numbers_as_points(m[1].str()));
    // the centre line: the straight stroke's two ends (its collinear middle point and the points
    // the taper inserted left out), a width at each
    const std::vector<glm::vec2> centre = numbers_as_points(m[3].str());
    ASSERT_EQ(centre.size(), 2u);
    EXPECT_EQ(centre.front(), glm::vec2(10, 50));
    EXPECT_EQ(centre.back(), glm::vec2(110, 50));
    std::istringstream widths(m[4].str());
    std::vector<double> w;
    for (double x; widths >> x;) w.push_back(x);
    EXPECT_EQ(w, (std::vector<double>{0.0, 0.0}));
    // the effect in <defs>, before the layers
    const std::size_t defs = svg.find("<defs id=\"defs\">"), effect = svg.find("effect=\"powerstroke\" id=\"powerstroke-0\"");
    ASSERT_NE(defs, std::string::npos);
    EXPECT_GT(effect, defs);
    EXPECT_LT(effect, svg.find("</defs>"));
    EXPECT_LT(svg.find("</defs>"), svg.find("inkscape:groupmode=\"layer\""));
    // its offset points carry the taper: t along the one segment (t x 100 px), the half-width of
    // the eased taper there within 0.03 px (t written to 0.0005: 0.05 px, at the ease's steepest
    // 0.4 px per px, and the half-width's 0.005), 0 at the ends (t 0.01 from them), 2 px from
    // 10 px in; knots in the taper zones and none between
    ASSERT_TRUE(std::regex_search(svg, m, std::regex("offset_points=\"([^\"]+)\"")));
    std::vector<glm::dvec2> offsets;
    std::istringstream in(m[1].str());
    for (std::string item; std::getline(in, item, '|');) {
        glm::dvec2 o;
        ASSERT_EQ(std::sscanf(item.c_str(), " %lf,%lf", &o.x, &o.y), 2) << item;
        offsets.push_back(o);
    }
    ASSERT_GE(offsets.size(), 6u);
    EXPECT_LE(offsets.size(), 10u);
    EXPECT_EQ(offsets.front(), glm::dvec2(0.01, 0.0));
    EXPECT_EQ(offsets.back(), glm::dvec2(0.99, 0.0));
    for (const glm::dvec2& o : offsets) {
        const double at = std::clamp(100.0 * o.x, 0.0, 100.0);
        EXPECT_TRUE(at <= 10.05 || at >= 89.95) << at;
        if (o.x > 0.011 && o.x < 0.989) {
            EXPECT_NEAR(o.y, 2.0 * taper_factor(at, 100.0, 10.0, 0.0), 0.03) << at;
        }
    }
}

// The outline's coordinates are rounded as finely as the page needs (within 0.02 mm): one
// decimal at 96 dpi (0.26 mm per pixel), three when the 120 px drawing fills an A0 page
// (9.9 mm per pixel); the same polygon either way, within the coarser rounding's 0.05 px.
TEST(TaperedStrokes, SvgOutlineRoundedToThePage) {
    const StyledDrawing styled = style_drawing(one_crease(), tapered_style());
    PageOptions a0;
    a0.page = "A0";
    std::vector<std::vector<glm::vec2>> outlines;
    std::vector<std::size_t> longest_fraction;
    for (const PageOptions& page : {PageOptions{}, a0}) {
        const std::string svg = export_document(styled, page, "x.svg");
        std::smatch m;
        ASSERT_TRUE(std::regex_search(svg, m, std::regex("<path d=\"([^\"]+)\" inkscape:path-effect")));
        const std::string d = m[1].str();
        std::size_t longest = 0;
        for (std::size_t i = 0; i < d.size(); ++i)
            if (d[i] == '.') longest = std::max(longest, d.find_first_not_of("0123456789", i + 1) - i - 1);
        longest_fraction.push_back(longest);
        outlines.push_back(numbers_as_points(d));
    }
    EXPECT_EQ(longest_fraction, (std::vector<std::size_t>{1, 3}));
    ASSERT_EQ(outlines[0].size(), outlines[1].size());
    for (std::size_t i = 0; i < outlines[0].size(); ++i) EXPECT_LE(glm::length(outlines[0][i] - outlines[1][i]), 0.0501f * std::sqrt(2.0f)) << i;
}

// A long wavy tapered stroke: the SVG's centre line keeps no more vertices than the stroke's own
// (the taper's inserted points left out, Douglas-Peucker at 0.05 px) and stays within 0.05 px
// of every point of the styled path.
TEST(TaperedStrokes, SvgCentreLineKeepsTheStrokesVertices) {
    Drawing d;
    d.width = 200, d.height = 100;
    std::vector<glm::vec2> pts;
    std::vector<float> depth;
    for (int i = 0; i <= 60; ++i) pts.push_back({10.0f + 3.0f * float(i), 50.0f + 20.0f * std::sin(0.1f * float(i))}), depth.push_back(100.0f);
    d.layer(LayerKind::creases).strokes.push_back(make_stroke(pts, depth, 0.5f, "crease"));
    const StyledDrawing styled = style_drawing(d, tapered_style());
    const StyledPath& p = styled.layers[static_cast<std::size_t>(LayerKind::creases)].groups[0].paths.at(0);
    EXPECT_GT(p.points.size(), pts.size());  // the taper's points inserted
    const std::string svg = export_document(styled, PageOptions{}, "x.svg");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(svg, m, std::regex("inkscape:original-d=\"([^\"]+)\"")));
    const std::vector<glm::vec2> centre = numbers_as_points(m[1].str());
    EXPECT_LE(centre.size(), pts.size());
    EXPECT_GE(centre.size(), 10u);
    for (const glm::vec2& q : p.points) {
        double best = 1e9;
        for (std::size_t i = 1; i < centre.size(); ++i) best = std::min(best, double(point_segment_distance(q, centre[i - 1], centre[i])));
        EXPECT_LE(best, 0.05 + 0.006) << q.x << " " << q.y;  // and the written 2 decimals
    }
}

TEST(TaperedStrokes, PdfAndPsFillTheSameOutline) {
    TempDir dir;
    const StyledDrawing styled = style_drawing(one_crease(), tapered_style());
    const std::string pdf_path = (dir.path / "t.pdf").string(), ps_path = (dir.path / "t.eps").string();
    export_drawings(styled, PageOptions{}, {pdf_path, ps_path});
    for (const std::string& path : {pdf_path, ps_path}) {
        const std::string doc = read_text(path);
        std::smatch m;  // the crease layer's filled path: "x y m ... h f"
        ASSERT_TRUE(std::regex_search(doc, m, std::regex("\n([-0-9. ]+ m\n(?:[-0-9. ]+ l\n)+)h\nf\n"))) << path;
        const std::vector<glm::vec2> outline = numbers_as_points(m[1].str());
        expect_tapered(outline);
        const StyledPath& p = styled.layers[static_cast<std::size_t>(LayerKind::creases)].groups[0].paths.at(0);  // the same polygon as the SVG's
        EXPECT_EQ(outline.size(), stroke_outline(p.points, p.widths).size()) << path;
    }
    EXPECT_NE(read_text(ps_path).find("/f /fill load def"), std::string::npos);
}

// The styled path of a tapered stroke: points every taper / 4 = 2.5 px from either end up to
// 10 px in, the stroke's own points, none between (the middle's width is linear already).
TEST(TaperedStrokes, TaperInsertsPointsOnlyWhereItChangesTheWidth) {
    const StyledDrawing d = style_drawing(one_crease(), tapered_style());
    const StyledPath& p = d.layers[static_cast<std::size_t>(LayerKind::creases)].groups[0].paths.at(0);
    std::vector<float> xs;
    for (const glm::vec2& q : p.points) xs.push_back(q.x);
    EXPECT_EQ(xs, (std::vector<float>{10, 12.5f, 15, 17.5f, 20, 60, 100, 102.5f, 105, 107.5f, 110}));
    ASSERT_EQ(p.widths.size(), p.points.size());
    for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_NEAR(p.widths[i], 4.0 * taper_factor(xs[i] - 10.0, 100.0, 10.0, 0.0), 1e-6) << xs[i];
}

TEST(TaperedStrokes, WeightScalesWidthBetweenItsFactors) {
    Style s = tapered_style();
    apply_style_overrides(s, "[creases]\ntaper = 0.0\nweight_min = 0.5\nweight_max = 2.0\n");
    const StyledDrawing d = style_drawing(one_crease({0.0f, 0.5f, 1.0f}), s);
    const StyledPath& p = d.layers[static_cast<std::size_t>(LayerKind::creases)].groups[0].paths.at(0);
    ASSERT_EQ(p.widths.size(), 3u);
    EXPECT_DOUBLE_EQ(p.widths[0], 2.0);   // 4 px * 0.5
    EXPECT_DOUBLE_EQ(p.widths[1], 5.0);   // 4 px * 1.25
    EXPECT_DOUBLE_EQ(p.widths[2], 8.0);   // 4 px * 2
    const WidthStats st = width_stats(d.layers[static_cast<std::size_t>(LayerKind::creases)]);
    // 50 px from 2 to 5 px and 50 px from 5 to 8 px: mean 5, mean square ((4 + 10 + 25) / 3 +
    // (25 + 40 + 64) / 3) / 2 = 28, variance 3
    EXPECT_NEAR(st.mean_width, 5.0, 1e-9);
    EXPECT_NEAR(st.cv, std::sqrt(3.0) / 5.0, 1e-9);
    EXPECT_DOUBLE_EQ(st.tapered_share, 0.0);  // thicker at one end only
}

TEST(TaperedStrokes, UntaperedPlotterOutputUnchangedByWeights) {
    // The plotter style keeps single centre-line strokes: weights and the new keys change nothing.
    const Style plotter = builtin_style("plotter");
    for (const char* ext : {"x.svg", "x.pdf", "x.ps"}) {
        const std::string plain = export_document(style_drawing(one_crease(), plotter), PageOptions{}, ext);
        const std::string weighted = export_document(style_drawing(one_crease({0.0f, 1.0f, 0.2f}), plotter), PageOptions{}, ext);
        EXPECT_EQ(plain, weighted) << ext;
        EXPECT_EQ(plain.find("powerstroke"), std::string::npos) << ext;
        EXPECT_EQ(plain.find("\nf\n"), std::string::npos) << ext;
    }
    const std::string svg = export_document(style_drawing(one_crease(), plotter), PageOptions{}, "x.svg");
    EXPECT_NE(svg.find("<path d=\"M10 50 L60 50 110 50\" data-kind=\"crease\""), std::string::npos);
}

TEST(TaperedStrokes, RasterFollowsTheOutline) {
    // Ink summed down a column of the rasterised stroke is its width there (box-filtered
    // coverage): 4 px in the middle, the eased taper near the ends (0.75 of it 5 px in).
    const RgbImage img = rasterise(style_drawing(one_crease(), tapered_style()), RasterTransform{120, 100, 1.0, 0.0, 0.0});
    const auto ink = [&](int x) {
        double sum = 0.0;
        for (int y = 40; y < 60; ++y) sum += 1.0 - img.rgb[3 * std::size_t(y * 120 + x)] / 255.0;
        return sum;
    };
    EXPECT_NEAR(ink(60), 4.0, 0.02);          // 8-bit rounding over 4-5 pixels
    // pixel 15 spans 5-6 px in: the mean of 1 - (1 - u)^2 over u in [0.5, 0.6] is 0.797 (3.19 px);
    // the widths run linearly between points 1.5 px apart: within 0.1 px
    EXPECT_NEAR(ink(15), 4.0 * 0.797, 0.1);
    EXPECT_NEAR(ink(10), 4.0 * 0.097, 0.1);   // the end pixel (u in [0, 0.1]: mean 0.097)
    EXPECT_NEAR(ink(15), ink(104), 0.02);     // symmetric ends
}
