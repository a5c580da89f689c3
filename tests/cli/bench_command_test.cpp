// `penink bench` with a tiny sweep on volcano: bench.csv has one row per (method, level) plus
// the ten "model no more than a scene needs" rows, accuracy values in [0, 1], and the chart is an
// SVG that rsvg-convert renders; on an analytic terrain against its closed form, with the spread
// of five timed frames. Plus the chart writer's series from rows (unit).
#include <gtest/gtest.h>

#include <sstream>

#include "cli/bench_command.hpp"
#include "cli_support.hpp"

using namespace penink::test;

namespace {

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream s(text);
    for (std::string l; std::getline(s, l);) {
        rows.emplace_back();
        std::istringstream f(l);
        for (std::string c; std::getline(f, c, ',');) rows.back().push_back(c);
    }
    return rows;
}

}  // namespace

TEST(BenchCommand, TinySweepWritesCsvAndChart) {
    const auto dir = fresh_dir("bench");
    const RunResult r = run_penink("bench " PENINK_SOURCE_DIR "/examples/volcano.asc --out out --levels 1,2 "
                                   "--sizes 240x180 --tolerances 0,1 --methods toward-away,adjacency --frames 1 --warmup 0 "
                                   "--needs-size 120x90",
                                   dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto rows = csv_rows(read_text(dir / "out" / "bench.csv"));
    // Sweep: tolerance 0 (full resolution) then 1 px, each toward-away L1, L2, adjacency L1, L2.
    ASSERT_EQ(rows.size(), 1u + 8u + 10u);
    EXPECT_EQ(rows[0][0], "group");
    EXPECT_EQ(rows[0].size(), 25u);
    EXPECT_EQ(rows[0][24], "reference");
    EXPECT_EQ(rows[0][6], "tolerance_px");
    EXPECT_EQ(rows[1][4], "toward-away");
    EXPECT_EQ(rows[1][5], "1");
    EXPECT_EQ(rows[1][6], "0.000");
    EXPECT_EQ(rows[5][6], "1.000");
    EXPECT_EQ(rows[4][4], "adjacency");
    EXPECT_EQ(rows[4][5], "2");
    for (std::size_t i = 1; i < rows.size(); ++i) {
        ASSERT_EQ(rows[i].size(), 25u);
        EXPECT_EQ(rows[i][24], "ray-cast");
        EXPECT_EQ(rows[i][0], i <= 8 ? "sweep" : "needs");
        EXPECT_GT(std::stod(rows[i][11]), 0.0);  // ms per frame
        for (int c = 15; c <= 18; ++c) {
            EXPECT_GE(std::stod(rows[i][std::size_t(c)]), 0.0);
            EXPECT_LE(std::stod(rows[i][std::size_t(c)]), 1.0);
        }
    }
    EXPECT_EQ(rows[9][1], "scene");
    EXPECT_EQ(rows[14][1], "zoom4");
    // Toward/Away's silhouette pixels lie on the reference (2 px); at 240x180 at full resolution it
    // finds 0.46 of it (volcano at exaggeration 1 has few, short silhouettes: at 120x90 they are a
    // few pixels). At 1 px tolerance the coarser mesh loses the smallest bumps' silhouettes (0.24
    // measured) but what it draws still lies on the reference.
    EXPECT_GE(std::stod(rows[2][17]), 0.95);
    EXPECT_GT(std::stod(rows[2][18]), 0.3);
    EXPECT_GE(std::stod(rows[6][17]), 0.95);
    EXPECT_GT(std::stod(rows[6][18]), 0.15);
    // Zoomed in, cropping models fewer cells than the whole DEM (60 x 86 cells).
    EXPECT_LT(std::stoul(rows[14][10]), 5160u);
    EXPECT_EQ(rows[17][10], "5160");
    const std::string svg = read_text(dir / "out" / "speed_accuracy.svg");
    EXPECT_NE(svg.find("toward-away 240x180"), std::string::npos);
    EXPECT_NE(svg.find("adjacency 240x180"), std::string::npos);
    EXPECT_EQ(std::system(("rsvg-convert -o '" + (dir / "chart.png").string() + "' '" +
                           (dir / "out" / "speed_accuracy.svg").string() + "'").c_str()),
              0);
    EXPECT_GT(std::filesystem::file_size(dir / "chart.png"), 1000u);
}

TEST(BenchCommand, AnalyticTerrainAgainstItsClosedForm) {
    const auto dir = fresh_dir("bench_analytic");
    const RunResult r = run_penink("bench --analytic saddle --out out --levels 8 --sizes 200x150 --methods toward-away "
                                   "--frames 5 --warmup 1 --no-needs",
                                   dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto rows = csv_rows(read_text(dir / "out" / "bench.csv"));
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[1][24], "closed-form");
    const double ms = std::stod(rows[1][11]), lo = std::stod(rows[1][22]), hi = std::stod(rows[1][23]);
    EXPECT_GT(lo, 0.0);
    EXPECT_LE(lo, ms);
    EXPECT_LE(ms, hi);
    // Toward/Away at 2 px on the saddle's grazing view (>= 0.95 at 1.5 px at 400x300:
    // tests/scene/toward_away_accuracy_test.cpp).
    EXPECT_GE(std::stod(rows[1][17]), 0.9);
    EXPECT_GE(std::stod(rows[1][18]), 0.9);
    const std::string svg = read_text(dir / "out" / "speed_accuracy.svg");
    EXPECT_NE(svg.find("closed-form"), std::string::npos);
    EXPECT_NE(svg.find("<path d=\"M"), std::string::npos);  // the min-max bar
}

TEST(BenchCommand, NeedsADemOrAnAnalyticTerrain) {
    const auto dir = fresh_dir("bench_none");
    const RunResult r = run_penink("bench --out out", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("penink: cli: bench: give a DEM or scene file, or --analytic NAME"), std::string::npos) << r.output;
    const RunResult u = run_penink("bench --analytic mesa --out out", dir);
    EXPECT_EQ(u.code, 2);
    EXPECT_NE(u.output.find("--analytic: unknown terrain \"mesa\""), std::string::npos) << u.output;
}

TEST(BenchChart, SeriesPerMethodAndSize) {
    std::vector<penink::BenchRow> rows(3);
    rows[0].group = rows[1].group = rows[2].group = "sweep";
    rows[0].method = rows[1].method = "toward-away", rows[2].method = "adjacency";
    rows[0].width = rows[1].width = rows[2].width = 100, rows[0].height = rows[1].height = rows[2].height = 50;
    rows[0].level = 1, rows[1].level = 4, rows[2].level = 1;
    rows[0].ms = 10, rows[1].ms = 40, rows[2].ms = 12;
    rows[1].p1 = 1.0, rows[1].r1 = 0.5;
    const auto series = penink::bench_chart_series(rows);
    ASSERT_EQ(series.size(), 2u);
    EXPECT_EQ(series[0].name, "toward-away 100x50 tol 0 px");
    ASSERT_EQ(series[0].points.size(), 2u);
    EXPECT_NEAR(series[0].points[1].accuracy, 2.0 / 3.0, 1e-12);  // F1 of 1 and 0.5
    EXPECT_EQ(series[0].points[1].label, "L4");
    EXPECT_EQ(series[1].colour, "#d62728");
    rows[1].tolerance_px = 1.5;  // another tolerance: a series of its own, another dash
    const auto split = penink::bench_chart_series(rows);
    ASSERT_EQ(split.size(), 3u);
    EXPECT_EQ(split[1].name, "toward-away 100x50 tol 1.5 px");
    EXPECT_NE(split[1].dash, split[0].dash);
}
