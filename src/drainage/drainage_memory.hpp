// Memory (and disk) of a drainage build, estimated before anything is allocated: the points of a DEM
// resampled by a factor and the bytes a build takes at its peak (the grid, the working arrays, the
// network, the creases' index and source), checked against a budget (core/memory_budget.hpp).
#pragma once
#include <cstdint>
#include <string>

namespace penink {

// Peak resident memory of a build at factor 1 (`penink drainage DEM` under /usr/bin/time on
// jacksboro refined 10 and 29 times, the terrain cache built beside it: 571 MB at 13.86 M points,
// 2962 MB at 116.6 M; the peak is the creases' index and the source's coding beside the grid,
// directions and network): a line, which cache_build_estimate.hpp announces.
constexpr double drainage_peak_bytes_per_point = 23.27, drainage_peak_base_bytes = 249.0e6;
// What check_drainage_memory counts beyond that: at factor 1 the line with a quarter more a point
// (a rougher DEM has more stems than jacksboro, and the index holds 16 B a stem); at factor > 1,
// 64 B a point (measured about 60 on jacksboro at factor 5, the coarse nodes and the resampling's
// arrays besides the fine grid's; the automatic factor keeps such a grid under 4 M points).
constexpr double drainage_check_margin = 1.25, drainage_resampled_bytes_per_point = 64.0;

// What a render whose first crease tiles are built from a stored creases' source takes beyond
// what it holds when that build starts, which a render counts on top of its frame's own estimate
// (StoredCreases: the grid's mask, directions and stems' sources decoded whole; the blocks of
// heights, positions, in-degrees, orders and flows its walks fill; the stems built; the rest of
// the frame): 17.5 B a point measured, the largest of three new close views of jacksboro refined
// 29 times peaking at 2.37 GB with 0.33 GB held when the build started (116.6 M points;
// docs/timings.md).
constexpr double crease_tiles_bytes_per_point = 18.0;
double crease_tiles_build_bytes(double points);

// Bytes a drainage database file takes a point at least (it stores the ridges and the creases'
// source, not the network, and at factor 1 not the heights: measured 0.53 B on jacksboro refined
// to 0.6", 1.84 MB for 3.47 M points, 0.76 B on /tmp/j5.tif, 2.66 MB for 3.5 M, 4.6 B on volcano
// at its automatic factor, 0.59 MB for 130 k): the room checked for before a build.
constexpr double dv_file_bytes_per_point = 0.5;

// Points of a cols x rows node grid resampled `factor` times finer: ((cols-1)f+1)((rows-1)f+1),
// as a double (no wrap for any factor).
double drainage_points(int cols, int rows, int factor);

// Bytes a build of a cols x rows DEM at `factor` is counted to need (what check_drainage_memory
// checks against the budget): at factor 1 drainage_peak_base_bytes and drainage_check_margin
// times drainage_peak_bytes_per_point a point, else drainage_resampled_bytes_per_point a point.
double drainage_build_bytes(int cols, int rows, int factor);

// The factor a build of a cols x rows DEM uses: `resample` when > 0, else the automatic one
// (drainage_resample_factor with the default point budget).
int drainage_factor_for(int cols, int rows, int resample);

// "CxR": the points of a cols x rows node grid resampled `factor` times finer along each side.
std::string drainage_grid_size(int cols, int rows, int factor);

// Throws Error(stage, file, "the drainage grid at factor F (CxR points) would need about N of
// memory, B available (--max-memory)") when the build would not fit `budget` (0: no limit).
void check_drainage_memory(const std::string& stage, const std::string& file, int cols, int rows, int factor,
                           std::uint64_t budget);

}  // namespace penink
