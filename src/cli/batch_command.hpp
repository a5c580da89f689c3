// `penink batch SCENE --path path.csv --out DIR`: an animation (Mower, "Concurrent Drainage Network Rendering", section 3). The
// terrain is read and modelled once (the union of the DEM windows every frame sees), then one
// frame per flight-path record (scene/flight_path.hpp) is drawn, styled and finished like
// `penink render` and written as DIR/frame_0001.png / .svg. `penink batch MESH_SCENE --orbit N
// --out DIR`: the same for a mesh, N frames orbiting it (scene/orbit.hpp; the walk-throughs of
// Potter et al., "NPR-Style 3D Line Textures"). Per-frame pass times (ms) go to DIR/timings.csv
// and the papers' tables (scene/timing_tables.hpp) to DIR/timings.md and standard output
// (warm-up frames in their own row, outside the means). Here: the options, parsed into a
// BatchRun (scene/batch_run.hpp: the frames and tables).
#pragma once
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "cli/scene_overrides.hpp"

namespace penink {

struct BatchOptions : SceneOverrides {
    std::string path, out_dir;
    int orbit = 0;  // a mesh scene: frames of an orbit (instead of a flight path)
    std::string formats = "png,svg";
    int warmup = 3;  // the creases paper reports its first three frames apart
    bool whole_dem = false;  // model the whole DEM instead of the union of the frames' windows
    LogFlags log;
    std::string shard;       // "K/N": draw frames K, K+N, K+2N, ... (1-based) of the flight only
};

// Shard K of N from "K/N" (1 <= K <= N); throws penink::Error (stage "cli") otherwise.
void parse_shard(const std::string& text, int& k, int& n);

Subcommand add_batch_command(CLI::App& app);
int run_batch(const BatchOptions& options);

}  // namespace penink
