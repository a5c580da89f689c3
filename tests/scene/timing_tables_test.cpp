// The batch timing tables (scene/timing_tables.hpp) from known per-frame times: warm-up frames
// in a row of their own, every time the mean over the row's frames, TOTAL with LAY in it, and
// each fps the mean over frames of 1000 / t_i (which differs from 1000 / mean t when the frames
// differ); the markdown and CSV carry those numbers.
#include <gtest/gtest.h>

#include "scene/timing_tables.hpp"

using namespace penink;

namespace {

FrameTiming frame(int n, bool warmup, double tft, double dm, double sil, double finish, double write) {
    FrameTiming f;
    f.frame = n, f.warmup = warmup;
    f.times.tft = tft, f.times.dm = dm, f.times.sil = sil, f.times.ridges = 1.0, f.times.readback = 2.0;
    f.finish = finish, f.write = write;
    f.trace = 3.0;
    f.total = tft + dm + sil + 1.0 + 2.0 + 3.0 + finish + write;
    return f;
}

// Five frames, the first three warm-up (as the creases paper reports them).
std::vector<FrameTiming> five_frames() {
    return {frame(1, true, 90, 10, 30, 5, 5), frame(2, true, 50, 10, 20, 4, 4), frame(3, true, 40, 10, 20, 3, 3),
            frame(4, false, 8, 2, 10, 1, 1), frame(5, false, 38, 2, 30, 3, 1)};
}

}  // namespace

TEST(TimingTables, PassTotalIncludesLay) {
    const FrameTiming f = frame(1, false, 8, 2, 10, 1.5, 0.5);
    // TFT + AFT + DM + SIL + RIDGES + LAY; read-back and trace are not passes of the paper.
    EXPECT_DOUBLE_EQ(passes_total(f), 8 + 0 + 2 + 10 + 1 + (1.5 + 0.5));
}

TEST(TimingTables, FirstThreeApartAndMeans) {
    const std::vector<TimingRow> rows = timing_rows(five_frames());
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].frames, "warm-up");
    EXPECT_EQ(rows[0].n, 3);
    EXPECT_EQ(rows[1].frames, "after warm-up");
    EXPECT_EQ(rows[1].n, 2);
    // Means over each row's own frames only (exact in binary up to the division: 1e-12).
    EXPECT_NEAR(rows[0].mean.times.tft, (90.0 + 50 + 40) / 3, 1e-12);
    EXPECT_NEAR(rows[1].mean.times.tft, (8.0 + 38) / 2, 1e-12);
    EXPECT_NEAR(rows[1].mean.lay(), (2.0 + 4) / 2, 1e-12);
    EXPECT_NEAR(passes_total(rows[1].mean), ((8 + 2 + 10 + 1 + 2.0) + (38 + 2 + 30 + 1 + 4.0)) / 2, 1e-12);
}

TEST(TimingTables, FpsIsTheMeanOfPerFrameRates) {
    const std::vector<TimingRow> rows = timing_rows(five_frames());
    ASSERT_EQ(rows.size(), 2u);
    const TimingRow& r = rows[1];
    // Frames 4 and 5: TFT+DM = 10 and 40 ms -> (100 + 25) / 2 = 62.5 fps, not 1000 / 25 = 40.
    EXPECT_NEAR(r.crease_fps, (1000.0 / 10 + 1000.0 / 40) / 2, 1e-9);
    EXPECT_GT(r.crease_fps, 1000.0 / (r.mean.times.tft + r.mean.times.dm) + 20);
    EXPECT_NEAR(r.silh_fps, (1000.0 / 18 + 1000.0 / 68) / 2, 1e-9);
    EXPECT_NEAR(r.total_fps, (1000.0 / 23 + 1000.0 / 75) / 2, 1e-9);
    EXPECT_NEAR(r.frame_fps, (1000.0 / 28 + 1000.0 / 80) / 2, 1e-9);
    EXPECT_NEAR(rows[0].crease_fps, (1000.0 / 100 + 1000.0 / 60 + 1000.0 / 50) / 3, 1e-9);
}

TEST(TimingTables, FramesWithoutAPassAreLeftOutOfItsRate) {
    std::vector<FrameTiming> frames = five_frames();
    for (FrameTiming& f : frames) f.warmup = false, f.times.tft = 0, f.times.dm = 0;
    frames[4].times.dm = 4;  // only frame 5 ran a crease pass
    const std::vector<TimingRow> rows = timing_rows(frames);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].n, 5);
    EXPECT_NEAR(rows[0].crease_fps, 1000.0 / 4, 1e-9);
    frames[4].times.dm = 0;
    EXPECT_EQ(timing_rows(frames)[0].crease_fps, 0.0);
    EXPECT_TRUE(timing_rows({}).empty());
}

TEST(TimingTables, MarkdownCarriesTablesThreeAndFour) {
    BatchSummary b;
    b.scene = "volcano.toml", b.warmup = 3, b.width = 160, b.height = 120;
    const std::string md = timings_markdown(five_frames(), b);
    EXPECT_NE(md.find("| frames | n | TFT | AFT | DM | SIL | RIDGES | LAY | TOTAL | read-back | trace | frame |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| frames | n | CREASEfps | SILHfps | TOTALfps | FRAMEfps |"), std::string::npos);
    // Table 3 after warm-up: TFT 23.0, DM 2.0, SIL 20.0, RIDGES 1.0, LAY 3.0, TOTAL 49.0.
    EXPECT_NE(md.find("| after warm-up | 2 | 23.0 | 0.0 | 2.0 | 20.0 | 1.0 | 3.0 | 49.0 | 2.0 | 3.0 | 54.0 |"),
              std::string::npos)
        << md;
    // Table 4 after warm-up: CREASEfps 62.5 (the mean of 100 and 25).
    EXPECT_NE(md.find("| after warm-up | 2 | 62.5 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| warm-up | 3 |"), std::string::npos);
    EXPECT_NE(md.find("the first 3 frames"), std::string::npos);
}

TEST(TimingTables, MeshTableAndCsv) {
    std::vector<FrameTiming> frames = five_frames();
    for (FrameTiming& f : frames) f.lines.pel = 7, f.lines.visibility = 1;
    BatchSummary b;
    b.scene = "examples/bunny.toml", b.mesh = true, b.triangles = 58784, b.warmup = 3;
    const std::string md = timings_markdown(frames, b);
    EXPECT_NE(md.find("| model | triangles | frames | n | TFT | SIL | read-back | normals | PEL geometry | PEL |"),
              std::string::npos)
        << md;
    // After warm-up: frame ms 54.0 (mean of 28 and 80), fps the mean of 1000/28 and 1000/80 = 24.1.
    EXPECT_NE(md.find("| bunny | 58784 | after warm-up | 2 | 23.0 | 20.0 | 2.0 | 0.0 | 0.0 | 7.0 |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| 54.0 | 24.1 |"), std::string::npos) << md;
    const std::string csv = timings_csv(frames, true);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "frame,warmup,tft,aft,sil,readback,normals,pel_geometry,pel,silhouettes,features,textures,visibility,"
              "lines,sketch,export,total");
    EXPECT_NE(csv.find("\n4,0,8.000,0.000,10.000,2.000,0.000,0.000,7.000,0.000,0.000,0.000,1.000,3.000,1.000,1.000,"
                       "28.000\n"),
              std::string::npos)
        << csv;
    const std::string terrain = timings_csv(frames, false);
    EXPECT_EQ(terrain.substr(0, terrain.find('\n')), "frame,warmup,tft,aft,dm,sil,ridges,lay,readback,trace,total");
    EXPECT_NE(terrain.find("\n4,0,8.000,0.000,2.000,10.000,1.000,2.000,2.000,3.000,28.000\n"), std::string::npos) << terrain;
}
