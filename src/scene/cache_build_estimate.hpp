// What building a DEM's caches costs, estimated from its size before the build starts: wall
// time, peak resident memory and bytes on disk of the terrain cache (surface/terrain_cache.hpp)
// and of the drainage database (drainage/drainage_build.hpp), fitted to the cold renders of
// bench/scale_curve.sh (jacksboro refined to 3.47 M and 13.86 M nodes, 2 cores; docs/timings.md,
// "Scale"; the constants and their sources in cache_build_estimate.cpp), the terrain cache's
// memory to its build alone (bench/terrain_cache_build_bench.cpp). Printed on stderr before a build of a DEM of more than
// estimate_from_cells cells, so a long wait is announced with what it will take.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>

namespace penink {

// DEMs above this many cells get the estimate line before their caches are built.
inline constexpr double estimate_from_cells = 10e6;

struct CacheBuildEstimate {
    double seconds = 0.0;
    double peak_bytes = 0.0;  // resident memory at the build's peak (the whole process)
    double disk_bytes = 0.0;  // the cache file written
};

// The terrain cache of a cols x rows DEM: reading its heights, building the pyramid in strips
// of the padded square (2^levels + 1 a side), coding and writing the file (build_terrain_cache).
CacheBuildEstimate terrain_cache_estimate(int cols, int rows);
// The drainage database of a cols x rows DEM built at the automatic resampling factor.
CacheBuildEstimate drainage_cache_estimate(int cols, int rows);

// "penink: <what>: building the <cache> of a CxR DEM (N M cells): about S s, M GB of memory at
// peak, D GB on disk (estimate)".
std::string describe_cache_estimate(const std::string& what, const std::string& cache, int cols, int rows,
                                    const CacheBuildEstimate& e);

// Whether `budget` bytes (0: unknown, no limit) hold both caches' builds at once: the drainage
// build at `factor` as check_drainage_memory counts it (drainage_build_bytes) and the terrain
// cache's estimated peak. Where they do, the drainage database and the terrain cache are built
// side by side (penink drainage; a render's first drawing, scene/terrain_keep.hpp).
bool cache_builds_fit_together(int cols, int rows, int factor, std::uint64_t budget);

enum class CacheKind { terrain, drainage };
// Writes the estimate line of the `kind` cache of a cols x rows DEM (its estimate and
// describe_cache_estimate) to `out`, when the DEM has more than estimate_from_cells cells.
void announce_cache_build(std::ostream& out, CacheKind kind, int cols, int rows);

}  // namespace penink
