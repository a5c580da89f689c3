// `penink fill DEM -o FILLED.tif [--band-rows N] [--max-memory M]`: the DEM with every closed
// depression filled to its spill height (the drainage build's Priority-Flood at factor 1: Barnes,
// Lehman & Mulla 2014 with Zhou, Sun & Fu 2016), for a DEM of any size: read, filled and written
// a band of rows at a time (drainage/tiled_fill.hpp, after Barnes 2016), so memory holds a few
// bands, their edge rows and the label graph, never the DEM. Heights are the drainage build's
// (metres: the band's scale, offset and vertical unit applied), written as a Float32 GeoTIFF
// georeferenced like the DEM, in its CRS, row 0 north, nodata NaN (drainage_rasters.hpp). The
// surface is the one priority_flood_fill gives on the whole DEM, bit for bit (tested).
#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>

namespace penink {

struct FillCommand {
    std::string dem;
    std::string output;
    int band_rows = 0;  // 0: from the memory budget (fill_command_band_rows)
    std::uint64_t max_memory = 0;  // --max-memory; 0 = the memory available
    bool quiet = false, verbose = false, progress = false;
};

// Rows of a band for a grid of `cols` x `rows` on `threads` threads within `budget` bytes: about
// 4 M cells a band, a multiple of the raster's strips, fewer rows where the bands in flight and
// the label graph would not fit; 0 when not even one strip's band fits.
int fill_command_band_rows(int cols, int rows, int threads, std::uint64_t budget);

// Runs the command, printing progress and a summary to `log` (not with quiet) and errors as one
// line; returns the exit code (0, 2 bad input, 1 internal failure). No output is left on failure.
int run_fill_command(const FillCommand& cmd, std::ostream& log);

}  // namespace penink
