// Map furniture geometry (lines/map_furniture.hpp): nice lengths, the scale bar's length against
// the ground it stands for, true north through a geotransform, ticks where coordinates cross
// multiples of an interval, labels, and the layers a map gets.
#include <cmath>

#include <gtest/gtest.h>

#include "core/helvetica_metrics.hpp"
#include "lines/map_furniture.hpp"

using namespace penink;

namespace {

constexpr double pi = 3.14159265358979323846;

// Degrees clockwise from the image's up of an image direction (y down).
double clockwise_from_up(glm::dvec2 d) { return std::atan2(d.x, -d.y) * 180.0 / pi; }

FurnitureFrame frame_10m() {  // 1000 x 750 px, 10 m a pixel, north up, 96 dpi
    FurnitureFrame f;
    f.width = 1000, f.height = 750;
    f.geotransform = {500000.0, 10.0, 0.0, 4000000.0, 0.0, -10.0};
    f.mm_per_px = 25.4 / 96.0;
    f.scale_text_px = 10.0, f.arrow_text_px = 12.0, f.title_text_px = 18.0, f.grid_text_px = 8.0;
    return f;
}

const Stroke* stroke_of(const Layer& l, const std::string& kind) {
    for (const Stroke& s : l.strokes)
        if (s.kind == kind) return &s;
    return nullptr;
}

}  // namespace

TEST(MapFurniture, NiceLengthsAreOneTwoOrFiveTimesAPowerOfTen) {
    EXPECT_DOUBLE_EQ(nice_length(1.0), 1.0);
    EXPECT_DOUBLE_EQ(nice_length(1.99), 1.0);
    EXPECT_DOUBLE_EQ(nice_length(2.0), 2.0);
    EXPECT_DOUBLE_EQ(nice_length(4.99), 2.0);
    EXPECT_DOUBLE_EQ(nice_length(5.0), 5.0);
    EXPECT_DOUBLE_EQ(nice_length(9.99), 5.0);
    EXPECT_DOUBLE_EQ(nice_length(1000.0), 1000.0);
    EXPECT_NEAR(nice_length(0.037), 0.02, 1e-15);
    EXPECT_DOUBLE_EQ(nice_length(123456.0), 100000.0);
    EXPECT_EQ(nice_length(0.0), 0.0);
}

TEST(MapFurniture, ScaleBarIsTheLongestNiceLengthThatFits) {
    // 10 m a pixel, at most 151 px: 1510 m, so 1 km in 5 divisions, 100 px
    ScaleBarLength b = scale_bar_length(10.0, 151.0, false);
    EXPECT_EQ(b.unit, "km");
    EXPECT_DOUBLE_EQ(b.length, 1.0);
    EXPECT_EQ(b.divisions, 5);
    EXPECT_DOUBLE_EQ(b.length_px, 100.0);
    // 1 m a pixel, at most 450 px: 200 m in 4 divisions
    b = scale_bar_length(1.0, 450.0, false);
    EXPECT_EQ(b.unit, "m");
    EXPECT_DOUBLE_EQ(b.length, 200.0);
    EXPECT_EQ(b.divisions, 4);
    EXPECT_DOUBLE_EQ(b.length_px, 200.0);
    // imperial: 100 m = 328 ft, so 200 ft = 60.96 m = 60.96 px at 1 m a pixel
    b = scale_bar_length(1.0, 100.0, true);
    EXPECT_EQ(b.unit, "ft");
    EXPECT_DOUBLE_EQ(b.length, 200.0);
    EXPECT_NEAR(b.length_px, 60.96, 1e-9);
    // 10 km = 6.2 miles: 5 mi = 8046.72 m
    b = scale_bar_length(100.0, 100.0, true);
    EXPECT_EQ(b.unit, "mi");
    EXPECT_DOUBLE_EQ(b.length, 5.0);
    EXPECT_NEAR(b.length_px, 80.4672, 1e-9);
}

TEST(MapFurniture, TrueNorthIsGridNorthTurnedAnticlockwiseByTheConvergence) {
    const std::array<double, 6> north_up{0.0, 2.0, 0.0, 0.0, 0.0, -2.0};
    EXPECT_NEAR(clockwise_from_up(true_north_direction(north_up, 0.0)), 0.0, 1e-12);
    EXPECT_NEAR(clockwise_from_up(true_north_direction(north_up, 1.7)), -1.7, 1e-12);
    EXPECT_NEAR(clockwise_from_up(true_north_direction(north_up, -3.0)), 3.0, 1e-12);
    // a view turned to azimuth 30: the image's up is bearing 30 and its right bearing 120, so a
    // column step is s (sin 120, cos 120) on the map (east, north), a row step -s (sin 30, cos 30),
    // and grid north lies 30 degrees anticlockwise of up
    const double a = 30.0 * pi / 180.0, s = 2.0;
    const std::array<double, 6> turned{0.0, s * std::cos(a), -s * std::sin(a), 0.0, -s * std::sin(a), -s * std::cos(a)};
    EXPECT_NEAR(clockwise_from_up(true_north_direction(turned, 0.0)), -30.0, 1e-9);
    EXPECT_NEAR(clockwise_from_up(true_north_direction(turned, 1.5)), -31.5, 1e-9);
}

TEST(MapFurniture, EdgeTicksLieWhereTheCoordinateCrossesTheInterval) {
    const auto ticks = edge_ticks({0.0, 0.0}, {100.0, 0.0}, {{0.0, 7.0}, {1000.0, 7.0}}, 0, 250.0);
    ASSERT_EQ(ticks.size(), 5u);
    for (std::size_t i = 0; i < ticks.size(); ++i) {
        EXPECT_NEAR(ticks[i].at.x, 25.0 * double(i), 1e-12);
        EXPECT_DOUBLE_EQ(ticks[i].value, 250.0 * double(i));
    }
    // sampled, decreasing, not linear as a whole: linear between samples, no tick twice at a sample
    const auto t2 = edge_ticks({0.0, 0.0}, {0.0, 40.0}, {{0, 10.0}, {0, 8.0}, {0, 4.0}}, 1, 2.0);
    ASSERT_EQ(t2.size(), 4u);  // 10, 8, 6, 4
    EXPECT_NEAR(t2[0].at.y, 0.0, 1e-12);
    EXPECT_NEAR(t2[1].at.y, 20.0, 1e-12);
    EXPECT_NEAR(t2[2].at.y, 30.0, 1e-12);
    EXPECT_NEAR(t2[3].at.y, 40.0, 1e-12);
}

TEST(MapFurniture, GraticuleIntervalsAndLabels) {
    EXPECT_DOUBLE_EQ(graticule_interval_deg(0.1), 5.0 / 60);
    EXPECT_DOUBLE_EQ(graticule_interval_deg(0.6), 0.5);
    EXPECT_DOUBLE_EQ(graticule_interval_deg(3.0), 2.0);
    EXPECT_EQ(lon_lat_label(-84.0 - 10.0 / 60, true), "84\xC2\xB0" "10'W");
    EXPECT_EQ(lon_lat_label(36.5, false), "36\xC2\xB0" "30'N");
    EXPECT_EQ(lon_lat_label(-12.0, false), "12\xC2\xB0S");
    EXPECT_EQ(lon_lat_label(1.0 + 1.0 / 60 + 30.0 / 3600, true), "1\xC2\xB0" "1'30\"E");
}

// The whole furniture of a 1000 x 750 px map at 10 m a pixel: the scale bar's baseline is its
// nice length exactly (float coordinates: within 1e-4 of it), the arrow points to true north, the
// neatline is the image border moved in by the inset, every piece has its panel and labels.
TEST(MapFurniture, AMapGetsItsFurnitureInItsLayers) {
    FurnitureFrame f = frame_10m();
    f.convergence_deg = 1.7;
    f.neatline_inset_px = 0.75;
    f.map_scale = 37795.0;  // 10 m a pixel of 0.2646 mm
    MapFurnitureOptions o;
    o.title = "Jacksboro";
    o.grid = MapGrid::map;
    Drawing d;
    d.width = f.width, d.height = f.height;
    add_map_furniture(d, f, o);
    EXPECT_TRUE(d.furniture);
    const Stroke* neat = stroke_of(d.layer(LayerKind::neatline), "neatline");
    ASSERT_NE(neat, nullptr);
    ASSERT_EQ(neat->points.size(), 5u);
    EXPECT_EQ(neat->points.front(), neat->points.back());
    EXPECT_FLOAT_EQ(neat->points[0].x, 0.75f);
    EXPECT_FLOAT_EQ(neat->points[2].x, 999.25f);
    // the bar: at most 40 mm = 151 px = 1512 m, so 1 km = 100 px
    const Stroke* bar = stroke_of(d.layer(LayerKind::scale_bar), "scale-bar");
    ASSERT_NE(bar, nullptr);
    ASSERT_EQ(bar->points.size(), 2u);
    EXPECT_NEAR(double(bar->points[1].x - bar->points[0].x) * 10.0, 1000.0, 1e-4 * 1000.0);
    bool unit = false, ratio = false;
    for (const Label& l : d.layer(LayerKind::scale_bar).labels) {
        unit = unit || (l.kind == "scale-unit" && l.text == "km");
        ratio = ratio || (l.kind == "scale-ratio" && l.text == "1:37 795");
    }
    EXPECT_TRUE(unit);
    EXPECT_TRUE(ratio);
    EXPECT_EQ(d.layer(LayerKind::scale_bar).fill.size(), 1u);
    // the panel holds the bar and lies inside the frame
    for (const glm::vec2& p : d.layer(LayerKind::scale_bar).fill[0]) {
        EXPECT_GE(p.x, 0.75f);
        EXPECT_LE(p.y, 749.25f);
    }
    const Stroke* arrow = stroke_of(d.layer(LayerKind::north_arrow), "north-arrow");
    ASSERT_NE(arrow, nullptr);
    EXPECT_NEAR(clockwise_from_up(glm::dvec2(arrow->points[1] - arrow->points[0])), -1.7, 1e-3);
    ASSERT_EQ(d.layer(LayerKind::title).labels.size(), 1u);
    EXPECT_EQ(d.layer(LayerKind::title).labels[0].text, "Jacksboro");
    // grid: 10 km across, ticks every 2 km (nice 10000 / 4 = 2000) on the top side at x 0, 200, ...
    int top = 0;
    for (const Stroke& s : d.layer(LayerKind::grid).strokes)
        if (s.points[0].y < 1.0f) {
            ++top;
            EXPECT_NEAR(std::fmod(double(s.points[0].x), 200.0), 0.0, 1e-3);
        }
    EXPECT_EQ(top, 4);  // x = 200, 400, 600, 800 (0 and 1000 are too near the corners)
}

TEST(MapFurniture, NothingAskedLeavesTheLayersEmptyButWritten) {
    const FurnitureFrame f = frame_10m();
    MapFurnitureOptions o;
    o.neatline = o.scale_bar = o.north_arrow = false;
    Drawing d;
    add_map_furniture(d, f, o);
    EXPECT_TRUE(d.furniture);
    for (LayerKind k : all_layers) {
        EXPECT_TRUE(d.layer(k).strokes.empty());
        EXPECT_TRUE(d.layer(k).labels.empty());
    }
}

TEST(HelveticaMetrics, WidthsAndLatin1) {
    EXPECT_DOUBLE_EQ(helvetica_advance_em("0"), 0.556);
    EXPECT_DOUBLE_EQ(helvetica_advance_em("km"), 0.5 + 0.833);
    EXPECT_EQ(latin1_text("caf\xC3\xA9 \xE2\x82\xAC"), "caf\xE9 ?");  // é kept, the euro sign is not Latin-1
    EXPECT_EQ(latin1_text("a\nb\x01"), "a b?");
    EXPECT_DOUBLE_EQ(helvetica_advance_em("\xC2\xB0"), 0.4);  // the degree sign
}
