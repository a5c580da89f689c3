// Memory (and disk) of a drainage build, estimated before anything is allocated: the points of a DEM
// resampled by a factor and the bytes each takes at the build's peak (the grid, the working
// arrays, the creases and ridges: measured about 60 B a point on jacksboro at factor 5), checked
// against a budget (core/memory_budget.hpp).
#pragma once
#include <cstdint>
#include <string>

namespace penink {

constexpr double drainage_bytes_per_point = 64.0;

// Bytes a drainage database file takes a point at least (it stores the ridges and the creases'
// source, not the network, and at factor 1 not the heights: measured 0.53 B on jacksboro refined
// to 0.6", 1.84 MB for 3.47 M points, 0.76 B on /tmp/j5.tif, 2.66 MB for 3.5 M, 4.6 B on volcano
// at its automatic factor, 0.59 MB for 130 k): the room checked for before a build.
constexpr double dv_file_bytes_per_point = 0.5;

// Points of a cols x rows node grid resampled `factor` times finer: ((cols-1)f+1)((rows-1)f+1),
// as a double (no wrap for any factor).
double drainage_points(int cols, int rows, int factor);

// Bytes a build of a cols x rows DEM at `factor` is counted to need: drainage_points times
// drainage_bytes_per_point (what check_drainage_memory checks against the budget).
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
