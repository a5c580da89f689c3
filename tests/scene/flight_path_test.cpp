// Flight path CSV parsing (cli/flight_path.hpp) and the progress text of batch/bench: named
// columns in any order, quoting, optional columns, and the exact one-line errors.
#include <gtest/gtest.h>

#include "scene/flight_frames.hpp"
#include "scene/flight_path.hpp"
#include "scene/scene.hpp"
#include "core/progress_bar.hpp"
#include "core/error.hpp"

using namespace penink;

namespace {

std::string error_of(const std::string& text) {
    try {
        parse_flight_path(text, "path.csv");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(FlightPath, NamedColumnsQuotingAndOptionalValues) {
    const auto r = parse_flight_path(
        "# comment\nAltitude,position,elevation,azimuth,min_score,light_azimuth\n"
        "-20,\"174.76,-36.88\",400,45,0.2,300\n\n-15.5, 1757000 5917000 ,350.5,90,,\n",
        "path.csv");
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].line, 3);
    EXPECT_EQ(r[0].position, "174.76,-36.88");
    EXPECT_DOUBLE_EQ(r[0].elevation, 400.0);
    EXPECT_DOUBLE_EQ(r[0].azimuth, 45.0);
    EXPECT_DOUBLE_EQ(r[0].altitude, -20.0);
    EXPECT_DOUBLE_EQ(*r[0].min_score, 0.2);
    EXPECT_DOUBLE_EQ(*r[0].light_azimuth, 300.0);
    EXPECT_FALSE(r[0].light_altitude.has_value());
    EXPECT_EQ(r[1].line, 5);
    EXPECT_EQ(r[1].position, "1757000 5917000");
    EXPECT_DOUBLE_EQ(r[1].elevation, 350.5);
    EXPECT_FALSE(r[1].min_score.has_value());  // empty cell: the scene's value
}

// The per-frame columns of examples/volcano_min_score.csv and volcano_light.csv (the creases
// paper's Figures 15 and 16) reach the frame's scene; an empty cell keeps the scene's value, and
// what no column names (the weights, the normalisation, ridges) stays as the scene has it.
TEST(FlightPath, RecordValuesReachTheFrameScene) {
    const std::string text =
        "position,elevation,azimuth,altitude,light_azimuth,light_altitude,min_score\n"
        "\"1 2\",400,45,-20,,,0.19\n\"1 2\",400,45,-20,120,25,\n";
    const auto r = parse_flight_path(text, "path.csv");
    ASSERT_EQ(r.size(), 2u);
    Scene scene;
    scene.view.light.azimuth = 315, scene.view.light.altitude = 40;
    scene.lines.creases.min_score = 0.8, scene.lines.creases.normalisation = ScoreNormalisation::paper;
    const Scene a = frame_scene(scene, r[0]), b = frame_scene(scene, r[1]);
    EXPECT_DOUBLE_EQ(a.lines.creases.min_score, 0.19);
    EXPECT_DOUBLE_EQ(a.view.light.azimuth, 315.0);
    EXPECT_DOUBLE_EQ(a.view.light.altitude, 40.0);
    EXPECT_DOUBLE_EQ(b.lines.creases.min_score, 0.8);
    EXPECT_DOUBLE_EQ(b.view.light.azimuth, 120.0);
    EXPECT_DOUBLE_EQ(b.view.light.altitude, 25.0);
    for (const Scene* s : {&a, &b}) {
        EXPECT_EQ(s->lines.creases.normalisation, ScoreNormalisation::paper);
        EXPECT_DOUBLE_EQ(s->lines.ridges.min_score, scene.lines.ridges.min_score);
    }
}

TEST(FlightPath, SplitsQuotedFields) {
    std::vector<std::string> f;
    ASSERT_TRUE(split_csv_line("a,\"b,\"\"c\"\"\",,d", f));
    ASSERT_EQ(f.size(), 4u);
    EXPECT_EQ(f[1], "b,\"c\"");
    EXPECT_EQ(f[2], "");
    EXPECT_FALSE(split_csv_line("\"open,1", f));
    EXPECT_FALSE(split_csv_line("\"a\"b,1", f));
}

TEST(FlightPath, ExactErrors) {
    const std::string head = "position,elevation,azimuth,altitude\n";
    EXPECT_EQ(error_of("position,azimuth,altitude\n\"1 2\",3,4\n"),
              "penink: batch: path.csv: line 1: missing column \"elevation\"");
    EXPECT_EQ(error_of("position,elevation,azimuth,altitude,roll\n"), "penink: batch: path.csv: line 1: unknown column \"roll\"");
    EXPECT_EQ(error_of(head + "\"1 2\",400,abc,-10\n"), "penink: batch: path.csv: line 2: azimuth: not a number (\"abc\")");
    EXPECT_EQ(error_of(head + "\"1 2\",400,10\n"), "penink: batch: path.csv: line 2: 3 fields, header has 4");
    EXPECT_EQ(error_of(head + "\"1 2\",400,10,-95\n"),
              "penink: batch: path.csv: line 2: altitude: must be between -90 and 90 degrees");
    EXPECT_EQ(error_of(head + "\"1 2,400,10,-5\n"), "penink: batch: path.csv: line 2: unterminated or misplaced quote");
    EXPECT_EQ(error_of(head), "penink: batch: path.csv: no records (a header row and one line per frame expected)");
}

TEST(ProgressText, PlainLinesWhenNotATerminal) {
    EXPECT_EQ(progress_text("batch", 2, 3, "frame_0002", 41.6, 1.0, false), "penink: batch: 2/3 frame_0002 42 ms\n");
    EXPECT_EQ(progress_text("bench", 1, 4, "L1", 10.0, 0.5, true, 8), "\rbench [##      ] 1/4 L1 2.0 per s\x1b[K");
}
