// `penink drainage DEM [-o OUT.dv] [--resample F] [--rasters DIR] [--routing R]`: builds the
// drainage vertex database of a DEM (Mower, "Concurrent Drainage Network Rendering" sec. 3) from
// its unexaggerated heights and writes it (default: the cache `render` reads,
// drainage_cache_path: `<DEM>.dv` beside a DEM in a writable folder, else in the user's cache
// folder; with the default options a render at any vertical exaggeration then uses it without
// rebuilding), optionally with GeoTIFF rasters of the drainage grid (drainage_rasters.hpp).
// Routing: priority-flood (default) or least-cost (GRASS r.watershed -s; drainage_build.hpp).
// Resample factor: F > 0 as given (1 = the DEM's own nodes); 0 = automatic: 5 (the paper's 10 m
// from 50 m) lowered until the drainage grid holds at most 4 M points.
#pragma once
#include <iosfwd>
#include <string>

#include "drainage/drainage_build.hpp"

namespace penink {

struct DrainageCommand {
    std::string dem;          // DEM path (anything read_dem reads)
    std::string output;       // .dv path; empty = drainage_cache_path(dem)
    int resample = 0;         // 0 = automatic
    std::string rasters_dir;  // empty = no rasters
    bool quiet = false;       // no progress / summary lines
    bool verbose = false;     // also each stage's wall and CPU seconds
    bool progress = false;    // progress lines also when stderr is not a terminal
    DrainageRouting routing = DrainageRouting::priority_flood;
    std::string cache_dir;  // --cache-dir; "": drainage_cache_path's default
    std::uint64_t max_memory = 0;  // --max-memory; 0 = the memory available
};

// Runs the command, printing progress (progress_mode: in place on a terminal, as lines with
// `progress`, none with `quiet`) and a summary (points, basins, branches, divides, time,
// points/s, working bytes/point; not with `quiet`) to `log`, and errors as one line `penink: ...`. Returns the exit
// code: 0 ok, 2 bad input, 1 internal failure.
int run_drainage_command(const DrainageCommand& cmd, std::ostream& log);

}  // namespace penink
