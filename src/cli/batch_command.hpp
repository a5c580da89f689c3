// `penink batch SCENE --path path.csv --out DIR`: an animation (Mower, "Concurrent Drainage Network Rendering", section 3). The
// terrain is read and modelled once (the union of the DEM windows every frame sees), then one
// frame per flight-path record (cli/flight_path.hpp) is drawn, styled and finished like
// `penink render` and written as DIR/frame_0001.png / .svg. Per-frame pass times (ms) go to
// DIR/timings.csv and a summary in the form of the paper's Tables 1-4 to DIR/timings.md
// (warm-up frames in their own row, outside the means).
#pragma once
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "scene/frame_source.hpp"
#include "cli/scene_overrides.hpp"
#include "export/style.hpp"

namespace penink {

struct BatchOptions : SceneOverrides {
    std::string path, out_dir;
    std::string formats = "png,svg";
    int warmup = 1;
    bool whole_dem = false;  // model the whole DEM instead of the union of the frames' windows
    bool verbose = false;
    bool quiet = false;      // no progress
    bool progress = false;   // progress lines also when stderr is not a terminal
    std::string shard;       // "K/N": draw frames K, K+N, K+2N, ... (1-based) of the flight only
};

// Shard K of N from "K/N" (1 <= K <= N); throws penink::Error (stage "cli") otherwise.
void parse_shard(const std::string& text, int& k, int& n);

struct FrameTiming {
    int frame = 0;         // 1-based
    bool warmup = false;
    PassTimings times;     // GPU passes, ms
    double trace = 0;      // CPU: images -> polylines, ms
    double lay = 0;        // CPU: finish, style and export of the frame's files, ms
    double total = 0;      // wall time of the whole frame, ms
};

// "frame,warmup,tft,aft,dm,sil,ridges,lay,readback,trace,total" and one row per frame.
std::string timings_csv(const std::vector<FrameTiming>& frames);

struct BatchSummary {
    std::string machine, scene;
    int width = 0, height = 0;
    std::size_t cells = 0, dem_cells = 0;
    double setup_s = 0, warmup_wall_s = 0, frames_wall_s = 0;
};

// Markdown: the run's context and one table (mean ms per pass, CREASEfps = 1000/(TFT+DM),
// SILHfps = 1000/(TFT+AFT+SIL), TOTALfps = frames / wall s), warm-up row first.
std::string timings_markdown(const std::vector<FrameTiming>& frames, const BatchSummary& summary);

// Finishes (sketch, thinning, plotter order), styles and writes one drawing to every path, as
// `penink render` does; returns the wall time in ms.
double export_frame(Drawing& drawing, const Style& style, std::uint64_t seed, const std::vector<std::string>& paths);

Subcommand add_batch_command(CLI::App& app);
int run_batch(const BatchOptions& options);

}  // namespace penink
