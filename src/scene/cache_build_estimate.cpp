#include "scene/cache_build_estimate.hpp"

#include <cmath>
#include <cstdio>

#include "drainage/drainage_memory.hpp"
#include "scene/scene_memory.hpp"
#include "surface/terrain_lod.hpp"

namespace penink {

namespace {

// Fitted to cold and warm renders of jacksboro refined 5 and 10 times (3.47 M and 13.86 M nodes,
// bench/scale_curve.sh; docs/timings.md, "Scale"): CPU seconds (user + system; about the wall
// time on an idle machine of 2 cores, less where the build runs on both) and peak resident
// memory of the cold render less the warm one's, with and without creases and ridges.
// The terrain cache's coding (terrain_cache.hpp) added 1.35 s to the 1.39 s that cold render took
// over the warm one in the same run (the cache of x10 alone, drainage database present), so 2.3 s
// where the fit gave 1.15.
constexpr double terrain_s_per_node = 0.166e-6;  // 2.3 s at 13.86 M nodes
// Held while the cache is built (terrain_cache.hpp, build_terrain_cache), over the process's own
// (terrain_base_bytes): the window of DEM rows a strip of the pyramid reads (5 B a node of its
// rows and margins, lod_strip_rows), lod_errors' strips (lod_errors_bytes), the pyramid's
// blocks held coded until written (a 24 B entry and 2 x 12 B of header lists each block of 256
// nodes' errors: terrain_bytes_per_error_block) and their bytes with the flags', the coarse nodes'
// and the node lattice's coded (about terrain_bytes_per_node), and the node lattice, held whole
// (36 B every 64 nodes): fitted to the build alone (bench/terrain_cache_build_bench.cpp under
// /usr/bin/time -v) of jacksboro refined 5, 10 and 29 times (2015x1720, 4030x3440, 11687x9976
// nodes), 103.4, 172.5 and 504.7 MB: the base and the bytes a node fitted to the last two before
// the lattice (98.9, 157.2, 402.2 MB), the lattice's coded bytes and the coarse nodes' to the
// last (0.31 B a node more: ×10 then 3 MB under; the first about 27 MB over, its own DEM's
// roughness codes to more bytes a node than the others').
constexpr double terrain_bytes_per_node = 0.899, terrain_base_bytes = 98.7e6, terrain_bytes_per_error_block = 48.0;
// The drainage database (`penink drainage DEM -o x.dv`: the network, the ridges and the creases'
// source; the crease tiles come later, built by the renders that need them, with their own
// progress): 3.25 s at 13.86 M points (jacksboro refined 10 times) and 42.6 s at 116.6 M (29
// times), 2 cores at a load under 2: a power law, exponent ln(42.6/3.25)/ln(116.6/13.86) = 1.209.
constexpr double drainage_s_at_reference = 3.25, drainage_reference_points = 13.86e6, drainage_exponent = 1.209;
// Peak resident memory: drainage_memory.hpp's line (drainage_peak_bytes_per_point).
// The terrain cache written (terrain_cache.hpp, coded: its size follows the DEM's smoothness; x, y
// derived on projected and geographic DEMs, with the node lattice and the coarse nodes): 1.35 B a
// node on jacksboro refined 10 times (18.7 MB), header included (0.98 refined 29 times, 1.75
// refined 5 times; before the lattice about 2 on the volcano, 2.8 on jacksboro itself, up to 6 on
// a synthetic DEM of noise; 17 B as floats).
constexpr double terrain_disk_bytes_per_node = 1.35;
// The file written: 1.84 and 1.83 B a point (25.5 and 213.1 MB), of which the network the creases'
// source stores (crease_source.hpp) about 0.16.
constexpr double drainage_disk_bytes_per_point = 1.83;

}  // namespace

CacheBuildEstimate terrain_cache_estimate(int cols, int rows) {
    const double nodes = double(cols) * double(rows);
    CacheBuildEstimate e;
    e.seconds = terrain_s_per_node * nodes;
    const double window_rows = double(lod_strip_rows() + 2);  // the strip's rows and the flags' dilation
    e.peak_bytes = terrain_base_bytes + 5.0 * double(cols) * std::min(window_rows, double(rows)) +
                   lod_errors_bytes(cols, rows) + terrain_bytes_per_node * nodes +
                   terrain_bytes_per_error_block * nodes / 256.0 +
                   double(sizeof(LatticeNode)) * double(lattice_size(cols)) * double(lattice_size(rows));  // held whole
    e.disk_bytes = terrain_disk_bytes_per_node * nodes;
    return e;
}

CacheBuildEstimate drainage_cache_estimate(int cols, int rows) {
    const double points = drainage_points(cols, rows, drainage_factor_for(cols, rows, 0));
    CacheBuildEstimate e;
    e.seconds = drainage_s_at_reference * std::pow(points / drainage_reference_points, drainage_exponent);
    e.peak_bytes = drainage_peak_base_bytes + drainage_peak_bytes_per_point * points;
    e.disk_bytes = drainage_disk_bytes_per_point * points;
    return e;
}

std::string describe_cache_estimate(const std::string& what, const std::string& cache, int cols, int rows,
                                    const CacheBuildEstimate& e) {
    char disk[32], line[256];
    if (e.disk_bytes < 0.95e9) std::snprintf(disk, sizeof disk, "%.0f MB", e.disk_bytes * 1e-6);  // a coded terrain cache
    else std::snprintf(disk, sizeof disk, "%.1f GB", e.disk_bytes * 1e-9);
    std::snprintf(line, sizeof line,
                  "penink: %s: building the %s of a %dx%d DEM (%.1f M cells): about %.0f s, %.1f GB of memory at peak, "
                  "%s on disk (estimate)",
                  what.c_str(), cache.c_str(), cols, rows, double(cols - 1) * double(rows - 1) * 1e-6, e.seconds,
                  e.peak_bytes * 1e-9, disk);
    return line;
}

bool cache_builds_fit_together(int cols, int rows, int factor, std::uint64_t budget) {
    return budget == 0 ||
           drainage_build_bytes(cols, rows, factor) + terrain_cache_estimate(cols, rows).peak_bytes <= double(budget);
}

void announce_cache_build(std::ostream& out, CacheKind kind, int cols, int rows) {
    if (!(double(cols - 1) * double(rows - 1) > estimate_from_cells)) return;
    if (kind == CacheKind::terrain)
        out << describe_cache_estimate("terrain", "terrain cache", cols, rows, terrain_cache_estimate(cols, rows)) << "\n";
    else
        out << describe_cache_estimate("drainage", "drainage database", cols, rows, drainage_cache_estimate(cols, rows))
            << "\n";
}

}  // namespace penink
