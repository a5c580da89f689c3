// Width bands and near/middle/far sublayers give the expected counts (thinning, overshoot and
// repeats are the lines stage's: tests/lines/finish_drawing_test.cpp).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "export/export_drawing.hpp"
#include "export/styled_drawing.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;

namespace {

// n strokes of two points, all at eye distance `depth` (one far stroke sets the max depth).
Drawing strokes_at(float depth, int n) {
    Drawing d;
    d.width = d.height = 100;
    for (int i = 0; i < n; ++i)
        d.layer(LayerKind::pels).strokes.push_back(
            make_stroke({{1, float(i % 90)}, {5, float(i % 90)}}, {depth, depth}, 1, "pel"));
    d.layer(LayerKind::silhouettes).strokes.push_back(make_stroke({{0, 0}, {9, 9}}, {1000, 1000}, 1, "s"));
    return d;
}

}  // namespace

TEST(StyledDrawing, TechnicalKeepsEveryStrokeAsOnePath) {
    const StyledDrawing s = style_drawing(small_drawing(), default_style());
    EXPECT_EQ(path_count(s), 5u);
    const StyledPath& ridge = s.layers[size_t(LayerKind::ridges)].groups[0].paths[0];
    // tapered over 6 px at each end: points inserted there (at most 1.5 px apart), one width each
    EXPECT_GT(ridge.points.size(), 5u);
    ASSERT_EQ(ridge.widths.size(), ridge.points.size());
    EXPECT_EQ(ridge.points.front(), glm::vec2(20, 70));
    EXPECT_EQ(ridge.points.back(), glm::vec2(180, 70));
    // a stroke without weights takes weight_max (1.65 for ridges); taper_min at the ends
    EXPECT_NEAR(ridge.widths.front(), 0.6 * 1.65 * 0.15, 1e-12);
    EXPECT_NEAR(ridge.widths.back(), 0.6 * 1.65 * 0.15, 1e-12);
    EXPECT_DOUBLE_EQ(ridge.width, 0.6 * 1.65);
    EXPECT_NEAR(ridge.depth, 540.0, 1e-9);  // mean of 100 300 500 800 1000
    EXPECT_EQ(ridge.kind, "ridge");
    EXPECT_EQ(s.layers[0].fill.size(), 2u);
}

TEST(StyledDrawing, WidthBandsShareBoundaryPoints) {
    const StyledDrawing s = style_drawing(small_drawing(), visible_style());
    // Ridge segments' mean depths 200 400 650 900 of D = 1000 -> levels 1 1 2 3 (4 bands).
    const auto& paths = s.layers[size_t(LayerKind::ridges)].groups[0].paths;
    ASSERT_EQ(paths.size(), 3u);
    EXPECT_EQ(paths[0].points.size(), 3u);
    EXPECT_EQ(paths[1].points.size(), 2u);
    EXPECT_EQ(paths[2].points.size(), 2u);
    EXPECT_EQ(paths[0].points.back(), paths[1].points.front());
    EXPECT_EQ(paths[1].points.back(), paths[2].points.front());
    EXPECT_DOUBLE_EQ(paths[0].width, 2.5);  // 3 + (1.5 - 3) / 3
    EXPECT_DOUBLE_EQ(paths[1].width, 2.0);
    EXPECT_DOUBLE_EQ(paths[2].width, 1.5);
    EXPECT_NEAR(paths[0].depth, 300.0, 1e-9);
    EXPECT_NEAR(paths[2].depth, 900.0, 1e-9);
}

TEST(StyledDrawing, KindDistanceSublayers) {
    Drawing d = strokes_at(100, 3);  // near third
    for (float depth : {400.f, 500.f, 700.f, 900.f, 950.f})
        d.layer(LayerKind::pels).strokes.push_back(make_stroke({{1, 1}, {2, 2}}, {depth, depth}, 1, "pel"));
    const StyledDrawing s = style_drawing(d, default_style(), LayerSplit::kind_distance);
    const StyledLayer& l = s.layers[size_t(LayerKind::pels)];
    ASSERT_EQ(l.groups.size(), 3u);
    EXPECT_EQ(l.groups[0].name, "pels-near");
    EXPECT_EQ(l.groups[1].name, "pels-middle");
    EXPECT_EQ(l.groups[2].name, "pels-far");
    EXPECT_EQ(l.groups[0].paths.size(), 3u);
    EXPECT_EQ(l.groups[1].paths.size(), 2u);
    EXPECT_EQ(l.groups[2].paths.size(), 3u);
    EXPECT_EQ(s.layers[0].groups.size(), 3u);  // every layer, even empty ones
}

TEST(StyledDrawing, InvisibleLayerIsWrittenEmpty) {
    Style style = default_style();
    apply_style_overrides(style, "[creases]\nvisible = false\n");
    const StyledDrawing s = style_drawing(small_drawing(), style);
    EXPECT_TRUE(s.layers[size_t(LayerKind::creases)].groups[0].paths.empty());
    EXPECT_EQ(s.layers[size_t(LayerKind::creases)].name, "creases");
    // Strokes are passed on as they are: the closed silhouette keeps its first point.
    const auto& sil = s.layers[size_t(LayerKind::silhouettes)].groups[0].paths[0];
    EXPECT_EQ(sil.points.front(), glm::vec2(10, 60));
}

TEST(StyledDrawing, PlotStats) {
    Drawing d;
    d.width = d.height = 100;
    d.layer(LayerKind::ridges).strokes.push_back(make_stroke({{0, 0}, {30, 40}}, {1, 1}, 1, "r"));
    d.layer(LayerKind::silhouettes).strokes.push_back(make_stroke({{30, 50}, {30, 60}, {40, 60}}, {1, 1, 1}, 1, "s"));
    const PlotStats st = plot_stats(style_drawing(d, default_style()));
    EXPECT_EQ(st.paths, 2u);
    // taper points are inserted along the segments in float: the length within 1e-4 px
    EXPECT_NEAR(st.length_px, 50.0 + 10.0 + 10.0, 1e-4);
    EXPECT_DOUBLE_EQ(st.travel_px, 10.0);
}

TEST(StyledDrawing, ParseLayerSplit) {
    EXPECT_EQ(parse_layer_split("kind"), LayerSplit::kind);
    EXPECT_EQ(parse_layer_split("kind+distance"), LayerSplit::kind_distance);
    try {
        parse_layer_split("depth");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: export: unknown --layers value \"depth\" (use kind or kind+distance)");
    }
}
