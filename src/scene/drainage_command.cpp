#include "scene/drainage_command.hpp"

#include "drainage/stored_creases.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <ostream>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/dv_format.hpp"
#include "export/atomic_file.hpp"
#include "scene/scene_inputs.hpp"
#include "scene/scene_overrides.hpp"
#include "scene/terrain_frames.hpp"
#include <fstream>
#include <future>
#include "scene/terrain_view.hpp"
#include "core/memory_budget.hpp"
#include "core/progress_bar.hpp"
#include "drainage/drainage_memory.hpp"
#include "scene/cache_build_estimate.hpp"
#include "drainage/drainage_rasters.hpp"
#include "input/dem_reader.hpp"
#include "core/ranks.hpp"
#include "drainage/tiled_fill.hpp"
#include <optional>

namespace penink {

namespace {

using Clock = std::chrono::steady_clock;

// Per-stage wall times, printed with -v or when the environment variable PENINK_DRAINAGE_TIMES is
// set (for profiling: bench/compare_grass.sh shows them).
// This process's resident and peak resident memory (MiB; /proc/self/status VmRSS, VmHWM), 0 where
// not known.
std::pair<long, long> resident_mib() {
    std::ifstream in("/proc/self/status");
    long rss = 0, peak = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("VmRSS:", 0) == 0) rss = std::atol(line.c_str() + 6) / 1024;
        if (line.rfind("VmHWM:", 0) == 0) peak = std::atol(line.c_str() + 6) / 1024;
    }
    return {rss, peak};
}

// With PENINK_DRAINAGE_TIMES set, each stage's wall and CPU time and the memory held when it ends
// and at most so far.
struct StageTimer {
    std::ostream& log;
    bool on = std::getenv("PENINK_DRAINAGE_TIMES") != nullptr;
    std::string stage = "reading the DEM";
    Clock::time_point since = Clock::now();
    double cpu0 = 0;
    void next(const std::string& name) {
        const Clock::time_point now = Clock::now();
        if (on && !stage.empty()) {
            char line[200];
            timespec ts; clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
            const double cpu = ts.tv_sec + ts.tv_nsec * 1e-9;
            const auto [rss, peak] = resident_mib();
            std::snprintf(line, sizeof line, "drainage: time %-26s %.3f s cpu %.3f, %ld MiB held, %ld at most\n",
                          stage.c_str(), std::chrono::duration<double>(now - since).count(), cpu - cpu0, rss, peak);
            cpu0 = cpu;
            log << line << std::flush;
        }
        stage = name, since = now;
    }
};

DrainageProgress progress_printer(StageProgress& progress, StageTimer& timer) {
    return [&progress, &timer](const std::string& stage, double fraction) {
        if (stage != timer.stage) timer.next(stage);  // a stage's time once, when the next begins
        progress.update(stage, fraction);
    };
}

void print_summary(std::ostream& log, const DrainageStats& s, const DrainageDb& db, double secs) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "drainage: %dx%d points (factor %d), %zu valid, %zu filled, %zu on outflow paths, "
                  "%zu tied, %zu basins, %zu branches, %zu divides, %.2f s (%.1f M points/s), "
                  "working memory %.1f B/point\n",
                  db.cols, db.rows, db.factor, s.valid, s.filled, s.outflow, s.ties, s.basins,
                  s.branches, s.divides,
                  secs, s.points / secs / 1e6, double(s.working_bytes) / double(s.points));
    log << line;
}

// The database's folder exists and may be written, `out` is not a folder, and the file system
// has room for about `bytes`; else Error("drainage", out, "cannot write drainage database
// (REASON)"), REASON the system's.
void check_database_target(const std::string& out, double bytes) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(out).parent_path();
    const std::string folder = dir.empty() ? "." : dir.string();
    auto fail = [&out](const std::string& why) {
        throw Error("drainage", out, "cannot write drainage database (" + why + ")");
    };
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) fail("no such directory");
    if (fs::is_directory(out, ec)) fail(std::strerror(EISDIR));
    if (::access(folder.c_str(), W_OK | X_OK) != 0) fail(std::strerror(errno));
    if (fs::exists(fs::symlink_status(out, ec))) {  // penink replaces only its own databases
        char head[sizeof dv::magic] = {};
        std::ifstream in(out, std::ios::binary);
        if (!fs::is_regular_file(out, ec) || !in.read(head, sizeof head) || std::memcmp(head, dv::magic, sizeof head) != 0)
            throw Error("drainage", out, "exists and is not a drainage database (penink replaces only its own .dv files)");
    }
    struct statvfs vfs {};
    if (::statvfs(folder.c_str(), &vfs) != 0) return;
    const double room = double(vfs.f_bavail) * double(vfs.f_frsize);
    if (room < bytes)
        fail(std::string(std::strerror(ENOSPC)) + ": about " + format_bytes(bytes) + " needed, " + format_bytes(room) +
             " free");
}

// The --rasters files in `dir` (none without --rasters).
std::vector<std::string> raster_paths(const std::string& dir) {
    std::vector<std::string> paths;
    if (dir.empty()) return paths;
    for (const std::string& n : drainage_raster_names()) paths.push_back((std::filesystem::path(dir) / n).string());
    return paths;
}

// The terrain cache of the render's caches built on another thread (open_stored_terrain: kept
// when valid, else built and written) while the drainage database is built. Destroyed before
// finish() (the drainage build failed), it waits for the build and removes the terrain cache when
// there was none before.
class TerrainBeside {
public:
    void start(const std::string& dem, const std::string& cache_dir, const std::string& path) {
        std::error_code ec;
        path_ = path, existed_ = std::filesystem::exists(path, ec);
        build_ = std::async(std::launch::async, [dem, cache_dir] { open_stored_terrain(dem, Log{}, cache_dir); });
    }
    // Waits for the build (its error thrown here); false when none was started.
    bool finish() {
        if (!build_.valid()) return false;
        build_.get();
        return true;
    }
    ~TerrainBeside() {
        if (!build_.valid()) return;
        try {
            build_.get();
        } catch (...) {  // the drainage build's error is the one reported
        }
        std::error_code ec;
        if (!existed_) std::filesystem::remove(path_, ec);
    }

private:
    std::future<void> build_;
    std::string path_;
    bool existed_ = true;
};

// Under an MPI launcher (mpirun, srun) the depressions are filled over every rank and the rest is
// built on rank 0: at factor 1 with priority-flood routing, the fill by row bands spread over the
// ranks (distributed_priority_flood, the same levels bit for bit), its levels handed to rank 0's
// build (DrainageOptions::fill); rank 0 alone reads the whole DEM, builds every other stage and
// writes. The other ranks open the DEM (its header alone) while rank 0 reads it, then wait for rank
// 0's word: fill with bands of `band_rows` rows, or end with exit code `code` (0 where there is
// nothing to fill: another factor or routing; rank 0's where it failed, which it alone reports).
struct RankWord {
    std::int32_t code = 0, band_rows = 0, cols = 0, rows = 0;
};
constexpr int word_tag = 3;

// Rank 0's side: the word sent to every other rank once, and whether the ranks are filling.
class FillRanks {
public:
    explicit FillRanks(Ranks* ranks) : ranks_(ranks && ranks->size() > 1 ? ranks : nullptr) {}
    bool spread() const { return ranks_ != nullptr; }
    // The summary line of a fill over the ranks ("" when there was none).
    std::string line() const {
        if (!band_rows_) return {};
        return "drainage: depressions filled over " + std::to_string(ranks_->size()) + " ranks of " +
               std::to_string(rank_threads(*ranks_)) + " threads, in bands of " + std::to_string(band_rows_) + " rows\n";
    }
    bool filling() const { return filling_; }
    // Ends the other ranks with `code` (nothing once told).
    void stop(int code) { tell({code, 0, 0, 0}); }
    // The fill of grid g (heights z) over every rank, its rows handed to `rows` in order.
    void fill(const GridShape& g, const std::vector<float>& z, const FillRowWriter& rows) {
        const int threads = rank_threads(*ranks_);
        // bands of at most about 4 M cells, at least two a rank where the grid has the rows, in
        // whole strips of 16 rows
        const int strip = height_raster_strip_rows, size = ranks_->size();
        const int most = fill_band_rows_of_cells(g.cols, strip);
        const int spread = ((g.rows + 2 * size - 1) / (2 * size) + strip - 1) / strip * strip;
        const int band_rows = std::min(std::max(std::min(most, spread), strip), g.rows);
        const FillRowReader read = [&](int y0, int y1, float* out, std::uint8_t* valid) {
            const std::size_t a = std::size_t(y0) * std::size_t(g.cols), b = std::size_t(y1) * std::size_t(g.cols);
            std::copy(z.begin() + std::ptrdiff_t(a), z.begin() + std::ptrdiff_t(b), out);
            std::copy(g.valid + a, g.valid + b, valid);
        };
        if (told_) {  // the other ranks sent away (not expected: the build fills at factor 1 alone)
            tiled_priority_flood({g.cols, g.rows, band_rows}, read, rows, threads);
            return;
        }
        tell({0, band_rows, g.cols, g.rows});
        filling_ = true, band_rows_ = band_rows;
        distributed_priority_flood({g.cols, g.rows, band_rows}, read, rows, *ranks_, threads);
        filling_ = false;
    }

private:
    void tell(RankWord w) {
        if (!ranks_ || told_) return;
        told_ = true;
        std::vector<std::uint8_t> bytes(sizeof w);
        std::memcpy(bytes.data(), &w, sizeof w);
        for (int r = 1; r < ranks_->size(); ++r) ranks_->send(r, word_tag, bytes);
    }
    Ranks* ranks_;
    bool told_ = false, filling_ = false;
    int band_rows_ = 0;
};

// A rank other than 0: the DEM opened (its header: rank 0's read checks every value, so this rank
// reads only its bands, whose valid heights are rank 0's bit for bit: a nodata node's, which the
// fill never reads, is 0 here), rank 0's word awaited, then its bands filled and sent to rank 0.
// Writes nothing; says nothing but its own failure during the fill.
int fill_for_rank_0(const DrainageCommand& cmd, Ranks& ranks, std::ostream& log) {
    std::optional<DemRows> dem;
    std::string why;
    int code = 0;
    try {
        DemOptions o;
        o.heights_only = true, o.no_xy = true, o.max_memory = memory_budget(cmd.max_memory);
        limit_gdal_block_cache(std::uint64_t(64) << 20);
        dem.emplace(cmd.dem, o, 0, false);
    } catch (const Error& e) {
        why = e.what(), code = int(e.code());
    }
    const std::vector<std::uint8_t> bytes = ranks.receive(0, word_tag);
    RankWord w;
    if (bytes.size() != sizeof w) throw std::runtime_error("rank 0's word not understood");
    std::memcpy(&w, bytes.data(), sizeof w);
    if (w.code != 0 || w.band_rows <= 0) return w.code;
    if (!dem) {
        log << why << "\n" << std::flush;
        ranks.abort(code);
    }
    try {
        const Terrain& meta = dem->meta();
        if (meta.cols != w.cols || meta.rows != w.rows)
            throw Error("drainage", cmd.dem, "the DEM differs on rank " + std::to_string(ranks.rank()) + " (" +
                                                 std::to_string(meta.cols) + "x" + std::to_string(meta.rows) + ", rank 0 " +
                                                 std::to_string(w.cols) + "x" + std::to_string(w.rows) + ")",
                        ExitCode::internal);
        distributed_priority_flood({w.cols, w.rows, w.band_rows},
                                   [&](int y0, int y1, float* z, std::uint8_t* valid) { dem->rows(y0, y1, z, valid); }, {},
                                   ranks, rank_threads(ranks));
    } catch (const std::exception& e) {
        abort_reporting(ranks, "drainage", cmd.dem, e, log);
    }
    return 0;
}

int build(const DrainageCommand& cmd, std::ostream& log, FillRanks& ranks);

// The crease tiles of the whole view a render of cmd.dem with the default scene draws
// (write_view_crease_tiles), built beside the database just written, from the build's network
// (`built`, as a render that builds the database builds its first tiles); what was written, for
// the summary. A cache for the first render, not an output: where it cannot be built (its memory),
// a line says so and the render builds them.
std::string view_crease_tiles(const DrainageCommand& cmd, std::ostream& log, StageTimer& timer, BuiltNetworkHandle built) {
    SceneOverrides o;
    o.input = cmd.dem, o.cache_dir = cmd.cache_dir, o.max_memory = cmd.max_memory;
    try {
        Scene scene = load_scene_with_overrides(o);  // (a render's memory check among its errors)
        if (drainage_routing_named(scene.terrain.drainage_routing) != cmd.routing) return {};
        timer.next("crease tiles of the whole view");
        const std::size_t n = write_view_crease_tiles(scene, Log{false, progress_mode(cmd.quiet, cmd.progress)}, std::move(built));
        if (n == 0) return {};
        return "crease tiles of the whole view: " + std::to_string(n) + " files in " +
               crease_tile_folder(drainage_cache_path(cmd.dem, cmd.cache_dir));
    } catch (const Error& e) {
        const std::string why = std::string(e.what()).substr(format_error(e.stage(), e.file(), "").size());
        if (!cmd.quiet)
            log << "penink: drainage: " << cmd.dem << ": the crease tiles of the whole view are left to the first render ("
                << why << ")\n";
        return {};
    }
}

int run(const DrainageCommand& cmd, std::ostream& log) {
    const std::unique_ptr<Ranks> world = launched_ranks();
    if (world && world->rank() != 0) return fill_for_rank_0(cmd, *world, log);
    FillRanks ranks(world.get());
    try {
        return build(cmd, log, ranks);
    } catch (const std::exception& e) {
        if (ranks.filling()) abort_reporting(*world, "drainage", cmd.dem, e, log);  // the others wait on it
        const Error* err = dynamic_cast<const Error*>(&e);
        ranks.stop(err ? int(err->code()) : int(ExitCode::internal));
        throw;
    }
}

int build(const DrainageCommand& cmd, std::ostream& log, FillRanks& ranks) {
    const auto t0 = Clock::now();
    StageTimer timer{log};
    timer.on = timer.on || cmd.verbose;
    StageProgress progress(log, progress_mode(cmd.quiet, cmd.progress), "drainage");
    if (cmd.resample < 0) throw Error("drainage", cmd.dem, "resample factor must be >= 1 (0 = automatic)");
    const std::uint64_t budget = memory_budget(cmd.max_memory);
    const DemSize size = read_dem_size(cmd.dem);  // the header alone: the build's memory before the read
    const int factor = drainage_factor_for(size.cols, size.rows, cmd.resample);
    // the other ranks fill at factor 1 with priority-flood routing, else have nothing to do
    if (factor != 1 || cmd.routing != DrainageRouting::priority_flood) ranks.stop(0);
    check_drainage_memory("drainage", cmd.dem, size.cols, size.rows, factor, budget);
    const std::string out = cmd.output.empty() ? drainage_cache_path(cmd.dem, cmd.cache_dir) : cmd.output;  // render's cache
    const double file_bytes = drainage_points(size.cols, size.rows, factor) * dv_file_bytes_per_point;
    check_database_target(out, file_bytes);  // before the build: a read-only folder or a full disk
    const std::vector<std::string> rasters = raster_paths(cmd.rasters_dir);
    {  // no output replaces the DEM or its side files, nor a raster penink did not write
        std::vector<std::string> outs = rasters;
        outs.push_back(out);
        if (out == drainage_cache_path(cmd.dem, cmd.cache_dir)) outs.push_back(terrain_cache_path(cmd.dem, cmd.cache_dir));
        check_outputs_not_inputs("drainage", outs, dem_inputs(cmd.dem));
        std::error_code ec;
        for (const std::string& r : rasters)
            if (std::filesystem::exists(std::filesystem::symlink_status(r, ec)) && !is_drainage_raster(r))
                throw Error("drainage", r, "exists and was not written by penink drainage (--rasters replaces only its own rasters)");
    }
    // a long build announced with its estimate (the automatic factor's: DEMs over 10 M cells)
    if (!cmd.quiet && factor == drainage_factor_for(size.cols, size.rows, 0))
        announce_cache_build(log, CacheKind::drainage, size.cols, size.rows);
    // The render's caches: the terrain cache too, built beside the drainage database on another
    // thread where the budget holds both builds' peaks (most drainage stages keep one core:
    // filling, flats, ties, accumulation), else after it. If the drainage build fails, a terrain
    // cache this command wrote is removed with it (the outputs of one command, together or not).
    const bool render_caches = out == drainage_cache_path(cmd.dem, cmd.cache_dir);
    // and the crease tiles of the whole view a render of the DEM draws first, where the database is
    // the one a render with the default scene reads (its factor; the routing checked there)
    const bool view_tiles = render_caches && cmd.resample == 0;
    const std::string terrain_cache = render_caches ? terrain_cache_path(cmd.dem, cmd.cache_dir) : std::string();
    TerrainBeside terrain;
    if (render_caches && cache_builds_fit_together(size.cols, size.rows, factor, budget))
        terrain.start(cmd.dem, cmd.cache_dir, terrain_cache);
    DemOptions read;
    read.heights_only = factor == 1;  // factor 1 needs no positions: heights (and a geographic grid's x, y)
    read.max_memory = budget;
    Terrain t = read_dem(cmd.dem, read);  // its positions (or heights) are released once resampled
    if (const std::string w = missing_crs_warning(t); !w.empty()) log << w << "\n";
    DrainageOptions o;
    o.resample = cmd.resample;
    o.routing = cmd.routing;
    o.cache_dir = cmd.cache_dir;
    if (ranks.spread() && factor == 1 && cmd.routing == DrainageRouting::priority_flood)
        o.fill = [&ranks](const GridShape& g, const std::vector<float>& z, const FillRowWriter& rows) { ranks.fill(g, z, rows); };
    DrainageResult res;
    DrainageGrid grid;  // as the build leaves it: with res's directions and network, the crease tiles' start
    DrainageDb db;
    const DrainageFingerprint fp = drainage_fingerprint(cmd.dem, t, o);
    // The database and the rasters are one set, placed together or not at all (atomic_file.hpp):
    // each written to a temporary beside its path, the database first (the rasters come from its
    // build).
    std::vector<std::string> paths{out};
    paths.insert(paths.end(), rasters.begin(), rasters.end());
    if (!rasters.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(cmd.rasters_dir, ec);
        if (!std::filesystem::is_directory(cmd.rasters_dir))
            throw Error("drainage", cmd.rasters_dir, "cannot create raster directory");
    }
    try {
        write_atomically_together(paths, [&](std::size_t i, const std::string& temp) {
            if (i == 0) {
                try {
                    db = build_and_write_drainage_db(t, o, fp, temp, progress_printer(progress, timer), &res,
                                                     view_tiles ? &grid : nullptr);
                } catch (const Error& e) {  // named by its place, not its temporary
                    throw Error(e.stage(), e.file() == temp ? out : e.file(),
                                std::string(e.what()).substr(format_error(e.stage(), e.file(), "").size()), e.code());
                }
                if (!rasters.empty()) timer.next("writing rasters");
                return;
            }
            // the grid's valid mask: exactly the points with a basin label
            std::vector<std::uint8_t> valid(res.net.basin.size());
            for (std::size_t k = 0; k < valid.size(); ++k) valid[k] = res.net.basin[k] != 0;
            const DrainageGeoref geo = drainage_georef(cmd.dem, t, db.factor);
            write_drainage_raster(i - 1, temp, paths[i], geo, db.cols, db.rows, valid, res);
        });
    } catch (const Error& e) {
        // The writer names no reason: the folder or the disk may tell it now (the disk filled
        // during the build), else its error stands.
        if (e.file() == out) check_database_target(out, file_bytes);
        throw;
    }
    remove_crease_tiles(out);  // the tiles of the database replaced: all of another key
    if (render_caches) {  // the terrain cache's build, or what is left of it
        timer.next("terrain cache");
        if (!terrain.finish()) open_stored_terrain(cmd.dem, Log{}, cmd.cache_dir);  // kept when valid, else built and written
    }
    timer.next("");
    const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
    // with -v, each file's size too
    const auto named = [&](const std::string& p) { return cmd.verbose ? cache_file_report(p) : p; };
    if (!cmd.quiet) print_summary(log, res.stats, db, secs), log << ranks.line() << "drainage: wrote " << named(out) << "\n";
    if (!cmd.quiet && !terrain_cache.empty() && std::filesystem::exists(terrain_cache))
        log << "drainage: terrain cache " << named(terrain_cache) << "\n";
    // the view's crease tiles, so that the first render reads them; the build's memory let go first
    if (view_tiles) {
        BuiltNetworkHandle built;
        if (db.has_crease_source())
            built.arrays = std::make_shared<BuiltNetwork>(BuiltNetwork{std::move(grid), std::move(res.dir), std::move(res.net)});
        res = DrainageResult{}, db = DrainageDb{}, t = Terrain{}, grid = DrainageGrid{};
        const auto t1 = Clock::now();
        const std::string tiles = view_crease_tiles(cmd, log, timer, std::move(built));
        timer.next("");
        if (!cmd.quiet && !tiles.empty()) {
            char took[32];
            std::snprintf(took, sizeof took, " (%.2f s)", std::chrono::duration<double>(Clock::now() - t1).count());
            log << "drainage: " << tiles << took << "\n";
        }
    }
    return 0;
}

}  // namespace

int run_drainage_command(const DrainageCommand& cmd, std::ostream& log) {
    return run_reporting_errors(log, "drainage", cmd.dem, [&] { return run(cmd, log); });
}

}  // namespace penink
