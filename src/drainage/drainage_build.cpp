#include "drainage/drainage_build.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <future>
#include <iostream>
#include <limits>
#include <memory>

#include <unistd.h>

#include "core/error.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel_chunks.hpp"
#include "drainage/branches.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/d8_ties.hpp"
#include "drainage/dem_surface.hpp"
#include "drainage/depression_drainage.hpp"
#include "drainage/drainage_memory.hpp"
#include "drainage/draped_lines.hpp"
#include "drainage/fill_directions.hpp"
#include "drainage/flat_resolution.hpp"
#include "drainage/least_cost_routing.hpp"
#include "drainage/stem_reach.hpp"
#include "drainage/stored_creases.hpp"
#include "input/dem_reader.hpp"

namespace penink {

std::optional<DrainageRouting> drainage_routing_named(const std::string& name) {
    if (name == "priority-flood") return DrainageRouting::priority_flood;
    if (name == "least-cost") return DrainageRouting::least_cost;
    return std::nullopt;
}

int drainage_resample_factor(const Terrain& t, const DrainageOptions& o) {
    if (o.resample > 0) return o.resample;
    int f = 5;
    while (f > 1 && resampled_size(t, f) > o.max_points) --f;
    return f;
}

namespace {

void report(const DrainageProgress& p, const char* stage, double fraction) {
    if (p) p(stage, fraction);
}

template <class... V> std::size_t bytes_of(const V&... v) {
    return (std::size_t(0) + ... + (v.capacity() * sizeof(typename V::value_type)));
}

// Accumulation (upstream to downstream) and basin labels (downstream walks) read only the
// directions and write different arrays: one on a second thread, which then traces the divides
// into `divides` when given (they need the basins only). A cycle throws from either.
void accumulate_and_label(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const GridShape& shape,
                          FlowNetwork& net, DrainageDb* divides) {
    run_beside(
        [&] {
            label_basins(dir, shape, net);
            if (divides) build_divides(g, net, *divides);
        },
        [&] { accumulate_flow(dir, shape, net); });
}

// Priority-flood routing: fill, D8, rims, flats, depressions, ties; g.z restored afterwards.
// The raised cells' original z and the fill's labels then the flat gradient borrow net.acc and
// net.basin, which get their own content later; the fill state is let go on return, before the
// accumulation allocates the orders.
void priority_flood_directions(DrainageGrid& g, const GridShape& shape, const DrainageProgress& progress,
                               DrainageResult& res, const ExternalFill& fill) {
    FlowNetwork& net = res.net;
    std::vector<std::uint8_t> flags;
    CellWords& orig = net.acc;
    report(progress, "filling depressions, flow directions", 0.0);
    std::vector<std::uint32_t> ties;
    const RoutingGrid grid{shape, g.dx, g.dy};
    RoutingArrays arrays{g.z, flags, orig, res.dir, ties};
    res.stats.filled = (fill ? fill_with_directions(grid, arrays, fill) : fill_with_directions(grid, arrays, net.basin)).raised;
    report(progress, "draining into depressions", 0.35);
    drain_rims_into_depressions(grid, arrays);
    report(progress, "resolving flats", 0.45);
    // raised cells get their codes from drain_depressions
    res.stats.unresolved_flats = resolve_flats(shape, arrays, net.basin, false);
    report(progress, "draining depressions, breaking ties", 0.5);
    res.stats.outflow = drain_depressions(grid, arrays, net.basin);
    break_d8_ties(grid, arrays, net.basin);
    res.stats.ties = ties.size();  // deduplicated by break_d8_ties
    res.stats.working_bytes = bytes_of(res.dir, flags, orig, net.basin);
    swap_raised(g.z, flags, orig);
}

// Where a factor-1 build of the DEM file at `dem_path`, read as `t` (whole, or its grid and
// georeference), reads its heights and x, y again (crease_source.hpp: the creases' source then
// refers to them); none at another factor or for a Terrain not read from a file.
std::optional<DemHeightsRef> heights_ref(const std::string& dem_path, const Terrain& t, int factor) {
    std::error_code ec;
    if (factor != 1 || dem_path.empty() || !std::filesystem::is_regular_file(dem_path, ec)) return std::nullopt;
    return DemHeightsRef{absolute_dem_path(dem_path), t.source_geographic ? t.utm_zone : 0, t.north};
}

// A cached database whose fingerprint matched the DEM at `dem_path`, which its creases' source
// may refer to at another path (moved with its DEM, or the same DEM copied with its time):
// the source's heights then read at `dem_path` (the same bytes, and checked by the source's block
// hashes as they are read). The path it stored where it moved, else "".
std::string follow_moved_dem(DrainageDb& db, const std::string& dem_path) {
    const std::string stored = crease_source_dem(crease_source_bytes(db)), now = absolute_dem_path(dem_path);  // its first page alone
    if (stored.empty() || stored == now) return {};
    db.crease_source_dem = now;
    return stored;
}

// A database of `g`'s size, factor and origin, nothing in it yet.
DrainageDb grid_database(const DrainageGrid& g) {
    DrainageDb db;
    db.cols = g.cols, db.rows = g.rows, db.factor = g.factor, db.origin = g.origin;
    return db;
}

// Progress of the stages after the directions (drainage_build.hpp).
constexpr double tracing_at = 0.7, draping_from = 0.72, writing_at = 0.9;

void drape_lines(const DrainageGrid& g, const DrainageResult& res, DrainageDb& db, const DrainageProgress& progress) {
    report(progress, "draping creases and ridges", draping_from);
    build_draped_lines(g, res.dir, res.net, db, [&](double f) {
        report(progress, "draping creases and ridges", draping_from + (writing_at - draping_from) * f);
    });
}

using WriteNetwork = std::function<void(const DrainageDb& meta, const DvBranchSource& branches)>;

// The streamed build from a resampled grid: network, divides and lines into the returned
// database (no branches or vertices), which `write` gets with the network's branches.
// `dem`: where the grid's heights and x, y are read again (factor 1), which the creases' source
// then refers to instead of storing them (crease_source.hpp); null: stored.
DrainageDb build_streamed(DrainageGrid& g, const std::string& crs_wkt, const DrainageOptions& options,
                          const DrainageFingerprint& fp, const WriteNetwork& write, const DrainageProgress& progress,
                          DrainageResult* keep, const DemHeightsRef* dem) {
    DrainageDb meta = grid_database(g);
    meta.crs_wkt = crs_wkt, meta.fingerprint = fp;
    // Of the creases, what a render builds those a frame needs from (crease_source.hpp): each
    // array coded on other threads as soon as it is final, beside the stages still running, most
    // of which keep one core (the grid's arrays and z beside the directions, z from a copy taken
    // before the fill changes it; the directions beside the ridges and the index). A DEM without
    // relief has no creases. The threads own what they read but g, which outlives them.
    const bool relief = has_relief(g);
    std::array<std::future<CodedSourceArray>, source_array_count> coded;
    auto code = [&](SourceArray a, DrainageGrid copy = {}, std::vector<std::uint8_t> dir = {}) {
        coded[std::size_t(a)] = std::async(std::launch::async, [&g, copy = std::move(copy), dir = std::move(dir), a]() mutable {
            CodedSourceArray c = code_source_array(a == SourceArray::z ? copy : g, dir, a);
            copy = {}, dir = {};  // freed now, not when the result is taken
            return c;
        });
    };
    DemArraysHash arrays_hash;  // of z and coarse_xy, which the source refers to the DEM for
    if (relief) {
        if (dem) {
            arrays_hash = dem_arrays_hash(g);  // before the fill changes z
            for (SourceArray a : {SourceArray::z, SourceArray::coarse_xy})
                coded[std::size_t(a)] = std::async(std::launch::deferred, [] { return CodedSourceArray{}; });
        } else {
            DrainageGrid z;
            z.z = g.z;
            code(SourceArray::z, std::move(z)), code(SourceArray::coarse_xy);
        }
        for (SourceArray a : {SourceArray::valid, SourceArray::coarse_valid, SourceArray::coarse_z}) code(a);
    }
    // The least-cost search keeps one core and leaves the heights as they are: the surface the
    // ridges are draped on and the height the creases stay under (both of g alone) are made beside
    // it. (Priority-Flood fills z in place while its directions are found.)
    struct OfGrid {
        std::unique_ptr<DemSurface> surface;
        float z_top = std::numeric_limits<float>::quiet_NaN();
    };
    // A geographic DEM's node x, y (8 B a point, made again bit for bit: drainage_grid.hpp) let go
    // while the Priority-Flood directions are found, which read none of them (compute_drainage
    // makes them again for the divides), and while the creases' source is assembled (again for the
    // branches written); not where they are coded (no `dem`) or the least-cost search's surface
    // reads them beside it.
    const bool xy_released = dem && options.routing == DrainageRouting::priority_flood && release_node_xy(g);
    std::future<OfGrid> of_grid;
    if (options.routing == DrainageRouting::least_cost)
        of_grid = std::async(std::launch::async, [&g, relief] {
            OfGrid o;
            o.surface = std::make_unique<DemSurface>(g);
            if (relief) o.z_top = drape_height_top(g);
            return o;
        });
    DrainageResult res = compute_drainage(g, progress, options.routing, &meta, options.fill);
    const OfGrid made = of_grid.valid() ? of_grid.get() : OfGrid{};
    if (relief) code(SourceArray::dir, {}, res.dir);
    report(progress, "tracing branches and divides", tracing_at);
    const NetworkBranches branches(g, res.dir, res.net);
    res.stats.branches = branches.branch_count(), res.stats.divides = meta.divides.size();
    // The creases' index on another thread while the ridges are draped here (each reads the
    // network and the grid only; "indexing creases" is then what is left of it). The index's walk
    // over every stem first finds the junctions' mains into the network (which nothing else reads
    // meanwhile), kept with it for the crease tiles a render builds next.
    // The network, with the mains, coded for the source beside the index (both only read it): on
    // jacksboro refined 10 times 0.6-0.8 s beside the index's walk.
    std::future<CodedCreaseIndex> indexing;
    std::future<CodedSourceNetwork> network_coded;
    if (relief)
        indexing = std::async(std::launch::async, [&] {
            res.net.mains = main_upstream_bits(g, res.dir, res.net);
            network_coded = std::async(std::launch::async, [&] { return code_source_network(g, res.dir, res.net); });
            return coded_crease_tile_index(g, res.dir, res.net, 256, made.z_top);
        });
    report(progress, "draping ridges", draping_from);
    build_draped_ridges(
        g, meta,
        [&](double f) { report(progress, "draping ridges", draping_from + (writing_at - draping_from) * 0.5 * f); },
        made.surface.get());
    report(progress, "indexing creases", draping_from + (writing_at - draping_from) * 0.5);
    if (relief) {
        const CodedCreaseIndex index = indexing.get();
        if (xy_released) release_node_xy(g);
        report(progress, "coding the creases' source", draping_from + (writing_at - draping_from) * 0.75);
        std::vector<CodedSourceArray> arrays;
        for (auto& a : coded) arrays.push_back(a.get());
        const CodedSourceNetwork network = network_coded.get();
        meta.crease_source = assemble_crease_source(g, index, arrays, dem, arrays_hash, &network);
    }
    report(progress, "writing the database", writing_at);
    readable_node_xy(g);  // the branches' vertices
    write(meta, branches);
    // kept (BuiltNetwork) for the crease tiles, which make them again when they first build a stem
    if (xy_released) release_node_xy(g);
    report(progress, "done", 1.0);
    if (keep) *keep = std::move(res);
    return meta;
}

}  // namespace

DrainageResult compute_drainage(DrainageGrid& g, const DrainageProgress& progress, DrainageRouting routing,
                                DrainageDb* divides, const ExternalFill& fill) {
    DrainageResult res;
    const GridShape shape{g.cols, g.rows, g.valid.data()};
    res.stats.points = g.size();
    res.stats.valid = std::size_t(std::count(g.valid.begin(), g.valid.end(), 1));
    if (routing == DrainageRouting::least_cost) {
        report(progress, "least-cost search", 0.05);
        res.dir = least_cost_directions(g.z, shape, g.dx, g.dy);
        // the directions, and the search's padded copy: 4 B of elevation key and 1 of state a cell
        // (least_cost_routing.hpp; the queue aside)
        res.stats.working_bytes = 6 * res.dir.size();
    } else {
        priority_flood_directions(g, shape, progress, res, fill);
    }
    FlowNetwork& net = res.net;
    report(progress, "accumulating flow and basins", 0.55);
    if (divides) readable_node_xy(g);  // the divides' vertices read the x, y (release_node_xy)
    accumulate_and_label(g, res.dir, shape, net, divides);
    res.stats.basins = net.outlet.size();
    // accumulation holds dir, in-degree, acc, order and (allocated) basin at once
    res.stats.working_bytes = std::max(res.stats.working_bytes,
                                       bytes_of(res.dir, net.acc, net.order, net.basin) + g.size());
    return res;
}

DrainageDb drainage_db_from_grid(DrainageGrid& g, const DrainageProgress& progress,
                                 DrainageResult* keep, DrainageRouting routing) {
    DrainageDb db = grid_database(g);
    DrainageResult res = compute_drainage(g, progress, routing, &db);
    report(progress, "tracing branches and divides", tracing_at);
    build_branches(g, res.dir, res.net, db);
    res.stats.branches = db.branches.size(), res.stats.divides = db.divides.size();
    drape_lines(g, res, db, progress);
    report(progress, "done", 1.0);
    if (keep) *keep = std::move(res);
    return db;
}

DrainageDb build_and_write_drainage_db(Terrain& t, const DrainageOptions& options, const DrainageFingerprint& fp,
                                       const std::string& path, const DrainageProgress& progress, DrainageResult* keep,
                                       DrainageGrid* grid) {
    report(progress, "resampling the PN surface", 0.0);
    const int factor = drainage_resample_factor(t, options);
    const std::optional<DemHeightsRef> dem = heights_ref(t.source, t, factor);
    DrainageGrid g = resample_pn_releasing(t, factor);  // memory back
    DrainageDb meta = build_streamed(
        g, t.crs_wkt, options, fp,
        [&](const DrainageDb& built, const DvBranchSource& branches) { write_drainage_db(path, built, branches); },
        progress, keep, dem ? &*dem : nullptr);
    if (grid) *grid = std::move(g);
    return meta;
}

DrainageDb build_drainage_db(const Terrain& t, const DrainageOptions& options,
                             const DrainageProgress& progress, DrainageResult* keep) {
    const int f = drainage_resample_factor(t, options);
    report(progress, "resampling the PN surface", 0.0);
    DrainageGrid g = resample_pn(t, f);
    DrainageDb db = drainage_db_from_grid(g, progress, keep, options.routing);
    db.crs_wkt = t.crs_wkt;
    db.fingerprint.resample = std::uint32_t(f);
    return db;
}

DrainageFingerprint drainage_fingerprint(const std::string& dem_path, const Terrain& terrain,
                                         const DrainageOptions& options) {
    const int factor = drainage_resample_factor(terrain, options);
    DrainageFingerprint fp = options.dem ? *options.dem : dem_fingerprint(dem_path, factor);
    fp.resample = std::uint32_t(factor), fp.routing = std::uint32_t(options.routing);
    return fp;
}

std::string cache_file_in(const std::string& folder, const std::string& dem_path) {
    const std::string absolute = std::filesystem::absolute(dem_path).lexically_normal().string();
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash64(absolute.data(), absolute.size())));
    const std::string name = std::filesystem::path(dem_path).filename().string();
    return (std::filesystem::path(folder) / (name + "-" + hex + ".dv")).string();
}

std::string drainage_cache_path(const std::string& dem_path, bool folder_usable, const std::string& user_cache) {
    if (folder_usable || user_cache.empty()) return dem_path + ".dv";
    return cache_file_in((std::filesystem::path(user_cache) / "penink").string(), dem_path);
}

bool under_install_prefix(const std::string& folder, const std::string& prefix) {
    if (prefix.empty()) return false;
    std::error_code ec;
    auto resolved = [&](const std::string& p) {
        const std::filesystem::path c = std::filesystem::weakly_canonical(std::filesystem::absolute(p, ec), ec);
        return (ec ? std::filesystem::absolute(p, ec) : c).lexically_normal();
    };
    const std::filesystem::path f = resolved(folder), p = resolved(prefix);
    if (p == p.root_path()) return false;
    auto fi = f.begin();
    for (auto pi = p.begin(); pi != p.end(); ++pi, ++fi) {
        if (pi->empty()) continue;  // a trailing separator
        if (fi == f.end() || *fi != *pi) return false;
    }
    return true;
}

#ifndef PENINK_INSTALL_PREFIX
#define PENINK_INSTALL_PREFIX ""
#endif

namespace {

// Where penink is installed: CMake's prefix, and P for a running binary at P/bin/penink beside
// P/share/penink (the Debian package's /usr, whatever prefix the build had).
std::vector<std::string> install_prefixes() {
    std::vector<std::string> prefixes{PENINK_INSTALL_PREFIX};
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::filesystem::path prefix = exe.parent_path().parent_path();
    if (!ec && exe.parent_path().filename() == "bin" && std::filesystem::is_directory(prefix / "share" / "penink", ec))
        prefixes.push_back(prefix.string());
    return prefixes;
}

}  // namespace

std::string drainage_cache_path(const std::string& dem_path, const std::string& cache_dir, bool make_folders) {
    std::error_code ec;  // a folder that cannot be made shows up as a failed write, logged
    if (!cache_dir.empty()) {
        if (make_folders) std::filesystem::create_directories(cache_dir, ec);
        return cache_file_in(cache_dir, dem_path);
    }
    std::filesystem::path folder = std::filesystem::path(dem_path).parent_path();
    if (folder.empty()) folder = ".";
    bool usable = ::access(folder.c_str(), W_OK) == 0;
    for (const std::string& prefix : install_prefixes()) usable = usable && !under_install_prefix(folder.string(), prefix);
    std::string user_cache;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) user_cache = xdg;
    else if (const char* home = std::getenv("HOME"); home && *home) user_cache = std::string(home) + "/.cache";
    const std::string path = drainage_cache_path(dem_path, usable, user_cache);
    if (make_folders && !usable && !user_cache.empty())
        std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    return path;
}

bool occupied_by_other_than_file(const std::string& path) {
    std::error_code ec;
    const std::filesystem::file_status s = std::filesystem::symlink_status(path, ec);
    if (ec || !std::filesystem::exists(s)) return false;
    return !std::filesystem::is_regular_file(std::filesystem::status(path, ec));
}

std::string cache_file_size(const std::string& path) {
    std::error_code ec;
    const std::uintmax_t n = std::filesystem::file_size(path, ec);
    return ec ? std::string() : format_bytes(double(n));
}

std::string cache_file_report(const std::string& path) {
    std::error_code ec;
    const std::uintmax_t n = std::filesystem::file_size(path, ec);
    return ec ? path : path + " (" + format_bytes(double(n)) + ")";
}

DrainageDb load_or_build_drainage(const std::string& dem_path, const Terrain& terrain,
                                  const DrainageOptions& options, const DrainageLog& log,
                                  const DrainageProgress& progress, DvLineVertices* in_file, std::string* file_used) {
    if (file_used) file_used->clear();
    const std::string cache = drainage_cache_path(dem_path, options.cache_dir);
    const DrainageFingerprint fp = drainage_fingerprint(dem_path, terrain, options);
    auto say = [&](const std::string& m) { if (log) log(m); };
    if (const std::string beside = dem_path + ".dv"; cache != beside && std::filesystem::exists(beside)) {
        try {  // a read-only folder's cache: read when valid (a stale one is rebuilt in the user's cache)
            DrainageDb db = in_file ? read_drainage_line_index(beside, &fp, *in_file)
                                    : read_drainage_db(beside, &fp, DvParts::lines);
            const std::string moved = follow_moved_dem(db, dem_path);
            say("drainage: using cached " + cache_file_report(beside) + (moved.empty() ? "" : " (its DEM moved from " + moved + ")"));
            if (file_used) *file_used = beside;
            return db;
        } catch (const Error& e) {
            say(std::string(e.what()) + "; trying " + cache);
        }
    }
    try {
        DrainageDb db = in_file ? read_drainage_line_index(cache, &fp, *in_file)
                                : read_drainage_db(cache, &fp, DvParts::lines);
        const std::string moved = follow_moved_dem(db, dem_path);
        say("drainage: using cached " + cache_file_report(cache) + (moved.empty() ? "" : " (its DEM moved from " + moved + ")"));
        if (file_used) *file_used = cache;
        return db;
    } catch (const Error& e) {
        say(std::string(e.what()) + "; rebuilding");
    }
    const int factor = drainage_resample_factor(terrain, options);
    // A database there that did not read: the render's memory check counted none to build
    // (scene_drainage_cached), so the build is checked here, against the memory available.
    std::error_code ec;
    if (std::filesystem::exists(dem_path + ".dv", ec) || std::filesystem::exists(cache, ec))
        check_drainage_memory("drainage", dem_path, terrain.cols, terrain.rows, factor, memory_budget(0));
    std::optional<DemHeightsRef> dem;  // of the Terrain the grid is made from (its UTM zone: the one read)
    report(progress, "resampling the PN surface", 0.0);
    DrainageGrid g;
    std::string crs = terrain.crs_wkt;
    if (terrain.vertical_exaggeration == 1.0 && terrain.pos.size() == terrain.size() &&
        terrain.valid.size() == terrain.size()) {
        dem = heights_ref(dem_path, terrain, factor);
        g = resample_pn(terrain, factor);
    } else {  // the heights unexaggerated, as `penink drainage` reads them (or only the grid's size was given)
        DemOptions read;
        read.heights_only = factor == 1;
        read.utm_zone = terrain.source_geographic ? terrain.utm_zone : 0, read.north = terrain.north;
        Terrain flat = read_dem(dem_path, read);
        if (flat.cols != terrain.cols || flat.rows != terrain.rows)
            throw Error("drainage", dem_path, "DEM changed while it was read");
        crs = flat.crs_wkt;
        dem = heights_ref(dem_path, flat, factor);
        g = resample_pn_releasing(flat, factor);
    }
    DrainageResult res;
    DrainageDb meta = build_streamed(
        g, crs, options, fp,
        [&](const DrainageDb& built, const DvBranchSource& branches) {
            if (occupied_by_other_than_file(cache)) {  // a FIFO, a folder: neither read nor replaced
                std::cerr << "penink: warning: drainage: " << cache << ": not a regular file; the drainage cache is "
                          << "neither read nor written (the database is built in memory)\n";
                return;
            }
            try {
                write_drainage_db(cache, built, branches);
                say("drainage: wrote " + cache_file_report(cache));
                remove_crease_tiles(cache);
                if (file_used) *file_used = cache;
            } catch (const Error& e) {  // said once a run, verbose or not: every run builds it again
                std::cerr << "penink: warning: drainage: " << cache << ": cannot write the drainage cache; using the "
                          << "database built in memory (built again on every run)\n";
                say(std::string(e.what()) + "; using the drainage database built in memory");
            }
        },
        progress, &res, dem ? &*dem : nullptr);
    // the grid, directions and network kept for the creases' tiles: a render's first frame builds
    // its stems from them (not from the source decoded, the DEM read again, the network made again)
    if (meta.has_crease_source()) {
        keep_normalised_flow(res.net);  // what the stems' walks read: 4 B a point less held
        meta.built_network.arrays =
            std::make_shared<BuiltNetwork>(BuiltNetwork{std::move(g), std::move(res.dir), std::move(res.net)});
    }
    return drainage_lines_only(std::move(meta));
}

}  // namespace penink
