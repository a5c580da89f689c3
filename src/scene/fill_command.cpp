#include "scene/fill_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <thread>

#include "core/error.hpp"
#include "core/memory_budget.hpp"
#include "core/progress_bar.hpp"
#include "drainage/drainage_rasters.hpp"
#include "drainage/tiled_fill.hpp"
#include "export/atomic_file.hpp"
#include "input/dem_reader.hpp"
#include "scene/scene_inputs.hpp"

namespace penink {

namespace {

using Clock = std::chrono::steady_clock;

// Bytes the fill holds besides its bands in flight: per band, its survey (two edge rows of labels,
// levels and flags, and its spills: about six a column of each edge row, 12 B each) and its
// water levels (two labels a column, 4 B each).
std::uint64_t fill_fixed_bytes(int cols, int bands) {
    return std::uint64_t(bands) * std::uint64_t(cols) * (2 * 9 + 2 * 6 * 12 + 2 * 4);
}

int run(const FillCommand& cmd, std::ostream& log) {
    const auto t0 = Clock::now();
    if (cmd.output.empty()) throw Error("fill", cmd.dem, "no output: name the filled DEM with -o FILLED.tif");
    if (cmd.band_rows < 0) throw Error("fill", cmd.dem, "band rows must be >= 1 (0 = automatic)");
    check_outputs_not_inputs("fill", {cmd.output}, dem_inputs(cmd.dem));
    const std::uint64_t budget = memory_budget(cmd.max_memory);
    const int threads = int(std::clamp<unsigned>(std::thread::hardware_concurrency(), 1, 16));
    DemOptions o;
    o.heights_only = true, o.no_xy = true, o.max_memory = budget;
    const DemSize size = read_dem_size(cmd.dem);
    int band_rows = cmd.band_rows ? cmd.band_rows : fill_command_band_rows(size.cols, size.rows, threads, budget);
    if (band_rows > 0 && cmd.band_rows) {
        const int bands = (size.rows + band_rows - 1) / band_rows;
        const std::uint64_t need = std::uint64_t(std::min(threads, bands)) * fill_band_bytes(size.cols, band_rows) +
                                   fill_fixed_bytes(size.cols, bands);
        if (need > budget) band_rows = 0;
    }
    if (band_rows <= 0)
        throw Error("fill", cmd.dem,
                    "filling the DEM's " + std::to_string(size.cols) + "x" + std::to_string(size.rows) +
                        " nodes would need about " +
                        format_bytes(double(fill_band_bytes(size.cols, cmd.band_rows ? cmd.band_rows : height_raster_strip_rows))) +
                        " a band, " + format_bytes(double(budget)) + " available (--max-memory; fewer --band-rows)");
    // read band by band: the opening pass checks every value (read_dem's errors) and finds the
    // lowest valid one, which the nodata nodes take (written as NaN)
    limit_gdal_block_cache(std::uint64_t(64) << 20);
    DemRows dem(cmd.dem, o);
    const Terrain& meta = dem.meta();
    band_rows = std::min(band_rows, meta.rows);
    const FillBands bands{meta.cols, meta.rows, band_rows};
    const DrainageGeoref geo = drainage_georef(cmd.dem, meta, 1);
    StageProgress progress(log, progress_mode(cmd.quiet, cmd.progress), "fill");
    TiledFillStats st;
    write_atomically_together({cmd.output}, [&](std::size_t, const std::string& temp) {
        HeightRasterWriter out(temp, cmd.output, geo, meta.cols, meta.rows, "fill");
        st = tiled_priority_flood(
            bands, [&](int y0, int y1, float* z, std::uint8_t* valid) { dem.rows(y0, y1, z, valid); },
            [&](int y0, int y1, const float* z, const std::uint8_t* valid) { out.write_rows(y0, y1, z, valid); }, threads,
            [&](int done, int total) {
                progress.update(done * 2 <= total ? "surveying bands" : "filling bands", double(done) / double(total));
            });
        out.close();
    });
    const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
    if (!cmd.quiet) {
        char line[300];
        std::snprintf(line, sizeof line,
                      "fill: %dx%d nodes, %zu raised, in %d bands of %d rows (%zu watersheds from their edges, %zu spills), %.2f s (%.1f M nodes/s)\n",
                      meta.cols, meta.rows, st.raised, st.bands, band_rows, st.labels, st.spills, secs,
                      double(meta.size()) / secs / 1e6);
        log << line;
        if (cmd.verbose)
            log << "fill: a band in flight holds at most " << format_bytes(double(st.band_bytes)) << ", " << threads
                << " at once\n";
        log << "fill: wrote " << cmd.output << "\n";
    }
    return 0;
}

}  // namespace

int fill_command_band_rows(int cols, int rows, int threads, std::uint64_t budget) {
    const int strip = height_raster_strip_rows;
    int band_rows = std::max(strip, int(std::uint64_t(4) << 20) / std::max(cols, 1) / strip * strip);
    band_rows = std::min(band_rows, (rows + strip - 1) / strip * strip);
    for (; band_rows >= strip; band_rows -= strip) {
        const int bands = (rows + band_rows - 1) / band_rows;
        const std::uint64_t need = std::uint64_t(std::min(threads, bands)) * fill_band_bytes(cols, band_rows) +
                                   fill_fixed_bytes(cols, bands);
        if (need <= budget) return band_rows;
    }
    return 0;
}

int run_fill_command(const FillCommand& cmd, std::ostream& log) {
    try {
        return run(cmd, log);
    } catch (const Error& e) {
        log << e.what() << "\n";
        return int(e.code());
    } catch (const std::exception& e) {
        log << format_error("fill", cmd.dem, e.what()) << "\n";
        return int(ExitCode::internal);
    }
}

}  // namespace penink
