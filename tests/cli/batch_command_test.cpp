// `penink batch` end to end on volcano at a tiny size: one frame file per record and format,
// timings.csv with the named columns and one row per frame (warm-up flagged), timings.md and
// standard output with the creases paper's Tables 3 and 4, plain progress lines with --progress
// when stderr is not a terminal (none without), and exact CSV / camera errors that leave no
// output directory behind. On a mesh scene (wuson): an orbit's frames, the walkthrough paper's
// Table 1, byte-identical frames when sharded, and the errors of a flight that does not fit.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";
const std::string head = "position,elevation,azimuth,altitude,light_azimuth,light_altitude,min_score\n";

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream s(text);
    for (std::string l; std::getline(s, l);) out.push_back(l);
    return out;
}

// Runs `run` + "sharded --shard 1/2" and "2/2" in `dir` and expects frames 1..n the same bytes as
// the whole run's in dir/all.
void expect_shards_draw_the_whole_runs_bytes(const std::string& run, const std::filesystem::path& dir, int n) {
    for (const char* shard : {"1/2", "2/2"}) {
        const RunResult r = run_penink(run + "sharded --shard " + shard, dir);
        ASSERT_EQ(r.code, 0) << r.output;
    }
    for (int frame = 1; frame <= n; ++frame) {
        const std::string name = "frame_000" + std::to_string(frame) + ".svg";
        EXPECT_EQ(read_text(dir / "sharded" / name), read_text(dir / "all" / name)) << name;
    }
}

}  // namespace

TEST(BatchCommand, ThreeFramesAndTimings) {
    const auto dir = fresh_dir("batch3");
    write_text(dir / "path.csv", head + "\"1756568 5916728\",400,45,-20,300,40,\n"
                                        "\"1756409 5916935\",400,60,-20,,,0.3\n"
                                        "\"1756309 5917176\",400,75,-20,320,30,\n");
    const RunResult r = run_penink(
        "batch " + volcano + " --path path.csv --out frames --width 160 --height 120 --progress --warmup 1", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* f : {"frame_0001.png", "frame_0001.svg", "frame_0002.png", "frame_0002.svg", "frame_0003.png",
                          "frame_0003.svg"})
        EXPECT_TRUE(std::filesystem::file_size(dir / "frames" / f) > 100) << f;
    EXPECT_EQ(file_count(dir / "frames"), 8u);  // 6 frames + timings.csv + timings.md
    const auto csv = lines_of(read_text(dir / "frames" / "timings.csv"));
    ASSERT_EQ(csv.size(), 4u);
    EXPECT_EQ(csv[0], "frame,warmup,tft,aft,dm,sil,ridges,lay,readback,trace,total");
    EXPECT_EQ(csv[1].rfind("1,1,", 0), 0u);
    EXPECT_EQ(csv[3].rfind("3,0,", 0), 0u);
    EXPECT_EQ(std::count(csv[2].begin(), csv[2].end(), ','), 10);
    const std::string md = read_text(dir / "frames" / "timings.md");
    EXPECT_NE(md.find("| warm-up | 1 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| after warm-up | 2 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| frames | n | TFT | AFT | DM | SIL | RIDGES | LAY | TOTAL | read-back | trace | frame |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| frames | n | CREASEfps | SILHfps | TOTALfps | FRAMEfps |"), std::string::npos) << md;
    EXPECT_NE(md.find("the first 1 frames"), std::string::npos) << md;
    // Each table has its warm-up row and its other row: four rows in all.
    std::size_t rows = 0;
    for (const std::string& l : lines_of(md)) rows += l.rfind("| warm-up | 1 |", 0) == 0 || l.rfind("| after warm-up | 2 |", 0) == 0;
    EXPECT_EQ(rows, 4u) << md;
    EXPECT_NE(r.output.find(md), std::string::npos) << "the tables go to standard output too";
    // --progress, not a terminal: one plain progress line per frame, no carriage returns.
    EXPECT_NE(r.output.find("penink: batch: 1/3 frame_0001 "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("penink: batch: 3/3 frame_0003 "), std::string::npos);
    EXPECT_EQ(r.output.find('\r'), std::string::npos);
    // Without --progress (stderr not a terminal), or with -q: no progress at all.
    for (const char* flags : {"", " -q", " -q --progress"}) {
        const RunResult quiet = run_penink(
            "batch " + volcano + " --path path.csv --out again --width 160 --height 120" + std::string(flags), dir);
        ASSERT_EQ(quiet.code, 0) << quiet.output;
        EXPECT_EQ(quiet.output.find("penink: batch: "), std::string::npos) << flags << quiet.output;
    }
}

TEST(BatchCommand, BadCsvWritesNothing) {
    const auto dir = fresh_dir("batchbad");
    write_text(dir / "path.csv", head + "\"1756568 5916728\",400,45,-20,,,\n\"1756409 5916935\",400,sixty,-20,,,\n");
    RunResult r = run_penink("batch " + volcano + " --path path.csv --out frames --width 160 --height 120", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: batch: path.csv: line 3: azimuth: not a number (\"sixty\")\n");
    EXPECT_FALSE(std::filesystem::exists(dir / "frames"));
    write_text(dir / "up.csv", head + "\"1756568 5916728\",400,45,-20,,,\n\"1756568 5916728\",400,45,80,,,\n");
    r = run_penink("batch " + volcano + " --path up.csv --out frames --width 160 --height 120", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: batch: up.csv: line 3: the camera sees no part of the DEM\n");
    EXPECT_FALSE(std::filesystem::exists(dir / "frames"));
    write_text(dir / "low.csv", head + "\"1757270 5917440\",120,45,-20,,,\n");
    r = run_penink("batch " + volcano + " --path low.csv --out frames", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: batch: low.csv: line 2: camera is inside the terrain (elevation 120 m, ground 159.5 m)\n");
}

// Sharded runs (one per machine or job) draw frames K, K+N, ... of the flight, each the same
// bytes as the unsharded run's; their timings do not overwrite each other's; a bad K/N is refused
// before anything is drawn.
TEST(BatchCommand, ShardsDrawTheUnshardedFramesBytes) {
    const auto dir = fresh_dir("batch_shard");
    std::string csv = head;
    for (int i = 0; i < 5; ++i)
        csv.append("\"").append(std::to_string(1756568 - 40 * i) + " " + std::to_string(5916728 + 60 * i) + "\",400," +
                                 std::to_string(45 + 8 * i) + ",-20,,,\n");
    write_text(dir / "path.csv", csv);
    const std::string run = "batch " + volcano + " --path path.csv --width 160 --height 120 --formats svg --out ";
    ASSERT_EQ(run_penink(run + "all", dir).code, 0);
    expect_shards_draw_the_whole_runs_bytes(run, dir, 5);
    EXPECT_EQ(file_count(dir / "sharded"), 5u + 4u);  // 5 frames, two timings pairs
    EXPECT_EQ(lines_of(read_text(dir / "sharded" / "timings_1-of-2.csv")).size(), 4u);  // frames 1, 3, 5
    EXPECT_EQ(lines_of(read_text(dir / "sharded" / "timings_2-of-2.csv")).size(), 3u);  // frames 2, 4
    // Warm-up: the first three frames each run draws (default --warmup 3).
    const auto all = lines_of(read_text(dir / "all" / "timings.csv"));
    ASSERT_EQ(all.size(), 6u);
    EXPECT_EQ(all[3].rfind("3,1,", 0), 0u);
    EXPECT_EQ(all[4].rfind("4,0,", 0), 0u);
    const auto first = lines_of(read_text(dir / "sharded" / "timings_1-of-2.csv"));
    EXPECT_EQ(first[3].rfind("5,1,", 0), 0u);
    const RunResult third = run_penink(run + "third --shard 3/3", dir);
    ASSERT_EQ(third.code, 0) << third.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "third" / "frame_0003.svg"));
    EXPECT_FALSE(std::filesystem::exists(dir / "third" / "frame_0001.svg"));
    for (const char* bad : {"0/3", "4/3", "3", "a/b", "2/", "/2"}) {
        const RunResult r = run_penink(run + "bad --shard " + bad, dir);
        EXPECT_EQ(r.code, 2) << bad;
        EXPECT_EQ(r.output, std::string("penink: cli: --shard must be K/N with 1 <= K <= N <= 1000000, got \"") + bad +
                                "\"\n")
            << bad;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad")) << bad;
    }
}

namespace {

const std::string wuson = PENINK_SOURCE_DIR "/examples/wuson.toml";

}  // namespace

// A mesh scene orbited: one frame per step, the walkthrough paper's Table 1 (warm-up apart), the
// per-frame CSV of the mesh steps; each shard's frames the same bytes as the whole run's.
TEST(BatchCommand, MeshOrbitFramesAndTable) {
    const auto dir = fresh_dir("batch_mesh");
    const std::string run = "batch " + wuson + " --orbit 5 --width 160 --height 120 --formats svg --out ";
    const RunResult r = run_penink(run + "all", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(file_count(dir / "all"), 5u + 2u);  // 5 frames + timings.csv + timings.md
    for (int frame = 1; frame <= 5; ++frame) {
        const std::string svg = read_text(dir / "all" / ("frame_000" + std::to_string(frame) + ".svg"));
        EXPECT_NE(svg.find("inkscape:label=\"silhouettes\""), std::string::npos) << frame;
    }
    // The orbit starts at the scene's camera: frame 1 is what `penink render` draws.
    ASSERT_EQ(run_penink("render " + wuson + " --width 160 --height 120 -o one.svg", dir).code, 0);
    EXPECT_EQ(read_text(dir / "one.svg"), read_text(dir / "all" / "frame_0001.svg"));
    // The orbit turns: the frames differ.
    EXPECT_NE(read_text(dir / "all" / "frame_0001.svg"), read_text(dir / "all" / "frame_0002.svg"));
    const auto csv = lines_of(read_text(dir / "all" / "timings.csv"));
    ASSERT_EQ(csv.size(), 6u);
    EXPECT_EQ(csv[0],
              "frame,warmup,tft,aft,sil,readback,normals,pel_geometry,pel,silhouettes,features,textures,visibility,"
              "lines,sketch,export,total");
    EXPECT_EQ(csv[3].rfind("3,1,", 0), 0u);
    EXPECT_EQ(csv[4].rfind("4,0,", 0), 0u);
    const std::string md = read_text(dir / "all" / "timings.md");
    EXPECT_NE(md.find("| model | triangles | frames | n | TFT | SIL | read-back | normals | PEL geometry | PEL |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| wuson | 3732 | warm-up | 3 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| wuson | 3732 | after warm-up | 2 |"), std::string::npos) << md;
    EXPECT_NE(r.output.find(md), std::string::npos);
    expect_shards_draw_the_whole_runs_bytes(run, dir, 5);
    EXPECT_EQ(lines_of(read_text(dir / "sharded" / "timings_2-of-2.csv")).size(), 3u);  // frames 2, 4
}

TEST(BatchCommand, FlightMustFitTheScene) {
    const auto dir = fresh_dir("batch_fit");
    write_text(dir / "path.csv", head + "\"1756568 5916728\",400,45,-20,,,\n");
    const std::pair<std::string, std::string> cases[] = {
        {"batch " + wuson + " --path path.csv --out f",
         "penink: batch: path.csv: a flight path flies over a terrain; a mesh scene takes --orbit N\n"},
        {"batch " + wuson + " --out f",
         "penink: batch: " + wuson + ": a mesh scene needs --orbit N (frames around the model)\n"},
        {"batch " + volcano + " --orbit 3 --out f",
         "penink: batch: " + volcano + ": --orbit flies around a mesh; a terrain takes --path CSV\n"},
        {"batch " + volcano + " --out f", "penink: batch: " + volcano + ": a terrain needs --path CSV (the flight path)\n"},
    };
    for (const auto& [args, message] : cases) {
        const RunResult r = run_penink(args, dir);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(r.output, message) << args;
        EXPECT_FALSE(std::filesystem::exists(dir / "f")) << args;
    }
}
