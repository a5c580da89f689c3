// What `penink batch` draws and writes once its options are parsed (cli/batch_command.hpp): the
// terrain read and modelled once (the union of the DEM windows every frame sees, or the whole DEM)
// and one frame per flight-path record (scene/flight_path.hpp), or a mesh and the N frames of an
// orbit around it (scene/orbit.hpp); each frame styled and finished like `penink render` and
// written as OUT/frame_0001.png / .svg ..., per-frame pass times (ms) to OUT/timings.csv and the
// papers' tables (scene/timing_tables.hpp) to OUT/timings.md. The flight and every camera are
// checked before the first frame is drawn, and no output replaces an input.
#pragma once
#include <string>
#include <vector>

#include "core/log.hpp"
#include "core/stopwatch.hpp"
#include "render/gl_context.hpp"
#include "scene/scene.hpp"

namespace penink {

struct BatchRun {
    std::string input;               // the scene or DEM as given (named in the tables and errors)
    std::string path;                // a terrain's flight path CSV ("" for an orbit)
    int orbit = 0;                   // a mesh: frames of an orbit
    std::string out_dir;             // created when missing
    std::vector<std::string> formats = {"png", "svg"};  // frame formats (extensions, checked)
    int warmup = 3;                  // first frames this run draws, timed apart
    bool whole_dem = false;          // model the whole DEM instead of the frames' windows
    int shard = 1, shards = 1;       // draw frames shard, shard + shards, ... (1-based)
    GlBackend gl = GlBackend::osmesa;
};

// OUT/frame_NNNN.EXT of frame `frame` (1-based), one path per format.
std::vector<std::string> batch_frame_paths(const std::string& out_dir, int frame, const std::vector<std::string>& formats);

// Draws and writes the run's frames and timing tables; returns the tables' markdown (the command
// prints it). `scene`: loaded and validated (a terrain's vertical exaggeration is resolved here);
// `start`: when the command began (the tables' set-up time counts from it). Errors:
// Error("batch", ...) when --path / --orbit / --whole-dem do not fit the scene or the output
// folder cannot be made, the flight path's and the writers' own.
std::string run_batch_frames(Scene& scene, const BatchRun& run, Clock::time_point start, const Log& log);

}  // namespace penink
