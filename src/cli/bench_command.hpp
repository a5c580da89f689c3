// `penink bench SCENE_OR_DEM --out DIR` or `penink bench --analytic NAME --out DIR` (a named
// analytic terrain of input/analytic_terrain.hpp with its grazing view and closed-form reference):
// speed against accuracy of the silhouette path (scene/speed_accuracy.hpp). With --flight CSV:
// instead, frame-to-frame coherence of silhouettes and creases along that flight
// (scene/flight_coherence.hpp), written to DIR/coherence.csv. Writes DIR/bench.csv, DIR/speed_accuracy.svg; prints a table.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "scene/speed_accuracy.hpp"

namespace penink {

struct BenchOptions {
    std::string input, out_dir;
    std::string analytic;  // analytic_case name instead of input
    std::string flight;    // flight path CSV: coherence instead of the sweep
    // Lists as given on the command line; "" = the sweep's defaults (SpeedAccuracyConfig).
    std::string levels, sizes, methods, tolerances, needs_size;
    SpeedAccuracyConfig config;  // frames, warmup, ref_edge_px, ref_supersample, needs
    std::string gl = "osmesa";
    LogFlags log;
};

// "1,2,4" -> {1,2,4}; "500x375,..." -> sizes. Errors: Error("cli", "", "--levels: ...").
std::vector<int> parse_int_list(const std::string& text, const std::string& option);
std::vector<std::pair<int, int>> parse_sizes(const std::string& text);
// "0,0.5,1" -> pixels in [0, 1000]. Errors: Error("cli", "", "--tolerances: ...").
std::vector<float> parse_tolerances(const std::string& text);

Subcommand add_bench_command(CLI::App& app);
int run_bench(const BenchOptions& options);

}  // namespace penink
