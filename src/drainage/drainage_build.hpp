// The drainage build pipeline (Mower, "Concurrent Drainage Network Rendering" sec. 3): PN resampling -> flow directions -> accumulation +
// Strahler -> basins -> branches and divides -> creases and ridges smoothed and draped on the PN
// surface of the full-resolution DEM (draped_lines.hpp) -> DrainageDb. Heights are taken as the
// Terrain holds them; the cache (load_or_build_drainage) is built from the DEM's unexaggerated
// heights, so one file serves every vertical exaggeration. Directions by one of two routings:
// priority_flood (default): Priority-Flood filling (Zhou et
// al. 2016 variant; the grid's z holds the filled surface until the directions are set, then the
// original again) and D8 on the filled
// surface on two threads (fill_directions.hpp),
// re-aimed into depressions on the original one -> Barnes flat resolution -> raised cells down
// the original slopes (depression_drainage.hpp) -> ties broken downstream (d8_ties.hpp);
// least_cost: GRASS r.watershed's least-cost search on the unfilled grid (least_cost_routing.hpp).
// Plus the cache next to the DEM
// (`<dem>.dv`), rebuilt when missing, stale or corrupt.
// Working memory beyond the grid (z 4 B + valid 1 B per point), counted in DrainageStats:
// fill/directions/flats 10 B per point (directions 1, fill state 1, original z of raised
// points 4 (lent by accumulation), flat gradient 4 (lent by basin)); accumulation 11 B
// (directions 1, in-degree 1, accumulation 4, order 1, basin 4); plus queues along depression
// rims and flat edges. The creases and ridges take 28 B a vertex (about one a point) and 28 B a
// line, plus a table of line ends while they are smoothed (draped_lines.hpp). An in-memory
// database's vertices (16 B each) and branches (32 B) come on top; `penink drainage` and the
// render's cache stream them to the file instead (build_and_write_drainage_db).
// Progress (DrainageProgress): fractions rise monotonically from 0 to 1 (1 once, with "done"):
// directions and accumulation up to 0.55, branches and divides 0.7, draping 0.72 to 0.9,
// writing the file 0.9.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "drainage/drainage_db.hpp"
#include "drainage/drainage_grid.hpp"
#include "drainage/fill_directions.hpp"
#include "drainage/flow_network.hpp"
#include "input/terrain.hpp"

namespace penink {

// Called with a stage name and the fraction of the whole build done, in [0, 1].
using DrainageProgress = std::function<void(const std::string& stage, double fraction)>;
using DrainageLog = std::function<void(const std::string& message)>;

// How flow directions are found: priority_flood = fill + D8 + Barnes flats + tie and depression
// passes (the default); least_cost = least-cost search as GRASS r.watershed -s does it
// (least_cost_routing.hpp). The value is stored in the DV fingerprint.
enum class DrainageRouting : std::uint32_t { priority_flood = 0, least_cost = 1 };

// The routing named "priority-flood" or "least-cost" (CLI --routing, scene [drainage] routing);
// nullopt for any other name.
std::optional<DrainageRouting> drainage_routing_named(const std::string& name);

struct DrainageOptions {
    int resample = 0;                      // fine nodes per DEM cell side; 0 = automatic
    std::size_t max_points = 4'000'000;    // automatic factor: largest <= 5 within this budget
    DrainageRouting routing = DrainageRouting::priority_flood;
    std::string cache_dir;  // where the caches go (--cache-dir, [cache] dir); "": drainage_cache_path's default
    // The DEM's size, mtime and content hash when the caller made them for this run (the terrain
    // cache's key: dem_fingerprint of the same file), so the file is not read and hashed again;
    // none: drainage_fingerprint makes them.
    std::optional<DrainageFingerprint> dem;
    // The depression filling made elsewhere (fill_directions.hpp: over the ranks of a distributed
    // run, `penink drainage` under mpirun) where the build fills with priority-flood routing;
    // empty: made here. The same database either way.
    ExternalFill fill;
};

// The automatic resample factor: 5 (Mower, "Concurrent Drainage Network Rendering": 10 m from 50 m) lowered until the resampled grid
// holds at most max_points (never below 1); an explicit options.resample > 0 is returned as is.
int drainage_resample_factor(const Terrain& t, const DrainageOptions& options);

struct DrainageStats {
    std::size_t points = 0, valid = 0, filled = 0, unresolved_flats = 0;
    std::size_t outflow = 0;  // cells on depressions' outflow paths (depression_drainage.hpp)
    std::size_t ties = 0;     // cells reported with tied steepest neighbours (d8_ties.hpp)
    std::size_t basins = 0, branches = 0, divides = 0;
    std::size_t working_bytes = 0;  // peak bytes of the per-point working arrays beyond z and valid (no queues)
};

// Per-point results on the drainage grid (for rasters and tests).
struct DrainageResult {
    std::vector<std::uint8_t> dir;  // resolved ESRI D8 codes (0 at outlets)
    FlowNetwork net;
    DrainageStats stats;
};

// Runs directions (priority_flood: fill, D8, flats, depressions, ties; least_cost: the search
// alone, the stats it does not use stay 0), accumulation and basins on `g` (g.z is filled during
// a priority_flood run and restored before returning). With `divides`, the basin divides are
// traced into it (build_divides) on the basins' thread while the accumulation finishes. With
// `fill` (not empty), the priority-flood fill is the one it makes (DrainageOptions::fill).
DrainageResult compute_drainage(DrainageGrid& g, const DrainageProgress& progress = {},
                                DrainageRouting routing = DrainageRouting::priority_flood,
                                DrainageDb* divides = nullptr, const ExternalFill& fill = {});

// Everything from an already resampled grid: network, branches and divides.
DrainageDb drainage_db_from_grid(DrainageGrid& g, const DrainageProgress& progress = {},
                                 DrainageResult* keep = nullptr,
                                 DrainageRouting routing = DrainageRouting::priority_flood);

// Resamples `t`, builds the database with options.routing (fingerprint left to the caller).
DrainageDb build_drainage_db(const Terrain& t, const DrainageOptions& options,
                             const DrainageProgress& progress = {}, DrainageResult* keep = nullptr);

// What `penink drainage` does: the build of build_drainage_db with fingerprint `fp`, written to
// `path` (write_drainage_db: temp file, renamed) straight from the network (NetworkBranches,
// branches.hpp: no vertex array held; the same bytes). t.pos and t.z are released (emptied) once
// the grid is resampled (resample_pn_releasing: `t` may be a heights-only read at factor 1), the
// rest of `t` kept. Returns the database without its branches and vertices
// (grid, origin, CRS, fingerprint, divides, creases, ridges); `keep` as build_drainage_db;
// `grid` (when given) gets the drainage grid as the build leaves it (what a BuiltNetwork holds
// with the directions and network of `keep`).
DrainageDb build_and_write_drainage_db(Terrain& t, const DrainageOptions& options, const DrainageFingerprint& fp,
                                       const std::string& path, const DrainageProgress& progress = {},
                                       DrainageResult* keep = nullptr, DrainageGrid* grid = nullptr);

// Fingerprint of the DEM file (options.dem's, when given) plus the build options: the resample
// factor and the routing (not the vertical exaggeration: the database holds unexaggerated
// heights; `options` is 0).
DrainageFingerprint drainage_fingerprint(const std::string& dem_path, const Terrain& terrain,
                                         const DrainageOptions& options);

// Where the drainage cache of a DEM lives (the terrain cache is the same path with .lod):
// - with a cache folder (`cache_dir`: --cache-dir, [cache] dir): `<cache_dir>/<file name>-<16
//   hex digits of a hash of the DEM's absolute path>.dv` (the folder is made when missing);
// - else beside the DEM (`<dem>.dv`) when its folder is writable and not under an install
//   prefix (CMake's CMAKE_INSTALL_PREFIX, and P for a binary running as P/bin/penink with
//   P/share/penink: the examples installed with penink are not written to);
// - else in the user's cache folder `<user_cache>/penink/<file name>-<16 hex>.dv`, user_cache =
//   $XDG_CACHE_HOME, else $HOME/.cache ("" when neither is set: beside the DEM after all, and a
//   write that fails is logged).
// make_folders false: the path alone, no folder made (where a check looks for a cache).
std::string drainage_cache_path(const std::string& dem_path, const std::string& cache_dir = "", bool make_folders = true);
std::string drainage_cache_path(const std::string& dem_path, bool folder_usable, const std::string& user_cache);
// `<folder>/<file name>-<16 hex>.dv` for the DEM at dem_path.
std::string cache_file_in(const std::string& folder, const std::string& dem_path);
// Whether `folder` is `prefix` or inside it (both made absolute and normal first; symbolic links
// resolved where they exist). False for an empty prefix or "/".
bool under_install_prefix(const std::string& folder, const std::string& prefix);
// "PATH (SIZE)" of a cache file as -v reports it (format_bytes), "PATH" when it cannot be stat'ed;
// cache_file_size: SIZE alone ("" then).
std::string cache_file_report(const std::string& path);
std::string cache_file_size(const std::string& path);
// Whether something other than a regular file (after symbolic links) is at `path`: a FIFO, a
// folder, a device, a dangling link. A cache there is neither read nor replaced.
bool occupied_by_other_than_file(const std::string& path);

// The cache of a render (drainage_cache_path): its lines part read (DvParts::lines) when its
// fingerprint matches the DEM and options, else rebuilt as `penink drainage` builds it (the same
// bytes) and written atomically; when it cannot be written the database built in memory is used
// and a warning line goes to stderr. A valid `<dem>.dv` beside the DEM is read first when the
// cache path is elsewhere (a read-only or installed folder, a cache folder): a cache in a
// read-only folder is still read. The cache folder is options.cache_dir. Something other than a
// regular file at the cache path (a FIFO, a folder) is neither read nor replaced: a warning line,
// and the database built in memory.
// Returns what a lines-only read gives (drainage_lines_only) either way. `terrain` is the DEM
// read with any vertical exaggeration, or only its grid and georeference (no node arrays, as the
// terrain cache gives them), or only its size (cols, rows: all a build that reads the DEM needs):
// unless it holds the heights unexaggerated, a build reads the DEM again at 1 (heights only at
// factor 1, in the standard UTM zone of a geographic DEM's centre unless `terrain` names another)
// and takes its georeference from that read. Every decision is reported through `log`.
// With `in_file`, a valid cache is read without its lines' vertices (read_drainage_line_index:
// its records and index checked, the same errors and rebuild) and *in_file says
// where they are; after a build in_file->file stays empty and the database holds them.
// With `file_used`, it gets the path of the database file read or written (empty when the
// database lives in memory only): where its crease tiles are kept (stored_creases.hpp).
DrainageDb load_or_build_drainage(const std::string& dem_path, const Terrain& terrain,
                                  const DrainageOptions& options, const DrainageLog& log = {},
                                  const DrainageProgress& progress = {}, DvLineVertices* in_file = nullptr,
                                  std::string* file_used = nullptr);

}  // namespace penink
