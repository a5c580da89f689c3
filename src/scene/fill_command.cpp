#include "scene/fill_command.hpp"

#include <algorithm>
#include <cstring>
#include <optional>
#include <chrono>
#include <cstdio>
#include <ostream>

#include "core/error.hpp"
#include "core/memory_budget.hpp"
#include "core/progress_bar.hpp"
#include "core/ranks.hpp"
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

// Bytes the fill of a grid of cols x rows holds at most with bands of band_rows rows, `threads` in
// flight at once.
std::uint64_t fill_need_bytes(int cols, int rows, int band_rows, int threads) {
    const int bands = (rows + band_rows - 1) / band_rows;
    return std::uint64_t(std::min(threads, bands)) * fill_band_bytes(cols, band_rows) + fill_fixed_bytes(cols, bands);
}

// The band rows to use on a budget: --band-rows, checked, or fill_command_band_rows; Error when
// not one band fits.
int choose_band_rows(const FillCommand& cmd, const DemSize& size, int threads, std::uint64_t budget) {
    int band_rows = cmd.band_rows ? cmd.band_rows : fill_command_band_rows(size.cols, size.rows, threads, budget);
    if (band_rows > 0 && cmd.band_rows && fill_need_bytes(size.cols, size.rows, band_rows, threads) > budget) band_rows = 0;
    if (band_rows <= 0)
        throw Error("fill", cmd.dem,
                    "filling the DEM's " + std::to_string(size.cols) + "x" + std::to_string(size.rows) +
                        " nodes would need about " +
                        format_bytes(double(fill_band_bytes(size.cols, cmd.band_rows ? cmd.band_rows : height_raster_strip_rows))) +
                        " a band, " + format_bytes(double(budget)) + " available (--max-memory; fewer --band-rows)");
    return std::min(band_rows, size.rows);
}

// Under an MPI launcher: rank 0's outcome of the opening (its exit code, 0 when it went well, and
// the band rows it chose) to every rank. A rank whose own opening failed where rank 0's did not
// says why and ends the run.
struct Opening {
    std::int32_t code = 0;
    std::int32_t band_rows = 0;
};
// Sent rank by rank rather than broadcast: a rank waiting for a message sleeps (Ranks::receive), while
// one in a broadcast spins a core through rank 0's check of the whole DEM.
constexpr int opening_tag = 3;
Opening agree_on_opening(Ranks& ranks, Opening mine, const std::string& why, std::ostream& log) {
    std::vector<std::uint8_t> bytes(sizeof mine);
    std::memcpy(bytes.data(), &mine, sizeof mine);
    if (ranks.rank() == 0)
        for (int r = 1; r < ranks.size(); ++r) ranks.send(r, opening_tag, bytes);
    else
        bytes = ranks.receive(0, opening_tag);
    Opening root;
    if (bytes.size() != sizeof root) throw std::runtime_error("fill: rank 0's opening not understood");
    std::memcpy(&root, bytes.data(), sizeof root);
    if (ranks.rank() != 0 && root.code == 0 && mine.code != 0) {
        log << why << "\n" << std::flush;
        ranks.abort(mine.code);
    }
    return root;
}

int fill_bands(const FillCommand& cmd, std::ostream& log, Ranks* ranks, DemRows& dem, int band_rows, int threads,
               Clock::time_point t0);

int run(const FillCommand& cmd, std::ostream& log) {
    const auto t0 = Clock::now();
    if (cmd.output.empty()) throw Error("fill", cmd.dem, "no output: name the filled DEM with -o FILLED.tif");
    if (cmd.band_rows < 0) throw Error("fill", cmd.dem, "band rows must be >= 1 (0 = automatic)");
    check_outputs_not_inputs("fill", {cmd.output}, dem_inputs(cmd.dem));
    // started by mpirun (or srun): this process is one rank of the run; rank 0 checks every value,
    // chooses the bands and writes, the others fill their bands
    const std::unique_ptr<Ranks> ranks = launched_ranks();
    const bool root = !ranks || ranks->rank() == 0;
    const int threads = rank_threads(ranks.get());
    const std::uint64_t budget = memory_budget(cmd.max_memory);
    DemOptions o;
    o.heights_only = true, o.no_xy = true, o.max_memory = budget;
    std::optional<DemRows> dem;
    int band_rows = 0;
    Opening mine;
    std::string why;
    try {
        band_rows = choose_band_rows(cmd, read_dem_size(cmd.dem), threads, budget);
        // read band by band: the opening pass (rank 0's) checks every value (read_dem's errors) and
        // finds the lowest valid one, which the nodata nodes take (written as NaN)
        limit_gdal_block_cache(std::uint64_t(64) << 20);
        dem.emplace(cmd.dem, o, 0, root);
        mine.band_rows = band_rows;
    } catch (const Error& e) {
        if (!ranks) throw;
        mine.code = std::int32_t(e.code()), why = e.what();
    }
    if (ranks) {  // every rank ends as rank 0 does, it alone saying why
        const Opening agreed = agree_on_opening(*ranks, mine, why, log);
        if (agreed.code != 0) {
            if (root) log << why << "\n";
            return agreed.code;
        }
        band_rows = agreed.band_rows;
    }
    try {
        return fill_bands(cmd, log, ranks.get(), *dem, band_rows, threads, t0);
    } catch (const std::exception& e) {
        // under an MPI launcher a failure here (a write, a read, a message) leaves the other ranks
        // waiting: it is reported, then every rank ends (MPI_Abort)
        if (!ranks) throw;
        abort_reporting(*ranks, "fill", cmd.dem, e, log);
    }
}

// The fill itself once the DEM is open (`ranks`: this process's place in a distributed run, or null).
int fill_bands(const FillCommand& cmd, std::ostream& log, Ranks* ranks, DemRows& dem, int band_rows, int threads,
               Clock::time_point t0) {
    const bool root = !ranks || ranks->rank() == 0;
    const Terrain& meta = dem.meta();
    const FillBands bands{meta.cols, meta.rows, band_rows};
    const FillRowReader read = [&](int y0, int y1, float* z, std::uint8_t* valid) { dem.rows(y0, y1, z, valid); };
    StageProgress progress(log, progress_mode(cmd.quiet || !root, cmd.progress), "fill");
    const auto tell = [&](int done, int total) {
        progress.update(done * 2 <= total ? "surveying bands" : "filling bands", double(done) / double(total));
    };
    TiledFillStats st;
    if (!root) {
        distributed_priority_flood(bands, read, {}, *ranks, threads, tell);
        return 0;
    }
    const DrainageGeoref geo = drainage_georef(cmd.dem, meta, 1);
    write_atomically_together({cmd.output}, [&](std::size_t, const std::string& temp) {
        HeightRasterWriter out(temp, cmd.output, geo, meta.cols, meta.rows, "fill");
        const FillRowWriter write = [&](int y0, int y1, const float* z, const std::uint8_t* valid) {
            out.write_rows(y0, y1, z, valid);
        };
        st = ranks ? distributed_priority_flood(bands, read, write, *ranks, threads, tell)
                   : tiled_priority_flood(bands, read, write, threads, tell);
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
        if (ranks) log << "fill: " << ranks->size() << " ranks of " << threads << " threads\n";
        if (cmd.verbose)
            log << "fill: a band in flight holds at most " << format_bytes(double(st.band_bytes)) << ", " << threads
                << " at once" << (ranks ? " a rank" : "") << "\n";
        log << "fill: wrote " << cmd.output << "\n";
    }
    return 0;
}

}  // namespace

int fill_command_band_rows(int cols, int rows, int threads, std::uint64_t budget) {
    const int strip = height_raster_strip_rows;
    int band_rows = fill_band_rows_of_cells(cols, strip);
    band_rows = std::min(band_rows, (rows + strip - 1) / strip * strip);
    for (; band_rows >= strip; band_rows -= strip)
        if (fill_need_bytes(cols, rows, band_rows, threads) <= budget) return band_rows;
    return 0;
}

int run_fill_command(const FillCommand& cmd, std::ostream& log) {
    return run_reporting_errors(log, "fill", cmd.dem, [&] { return run(cmd, log); });
}

}  // namespace penink
