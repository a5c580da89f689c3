#include "drainage/drainage_memory.hpp"

#include <cmath>
#include <cstdio>

#include "core/memory_budget.hpp"
#include "drainage/drainage_build.hpp"
#include "input/terrain.hpp"

namespace penink {

double drainage_points(int cols, int rows, int factor) {
    const double f = factor;
    return (std::max(cols - 1, 0) * f + 1.0) * (std::max(rows - 1, 0) * f + 1.0);
}

double drainage_build_bytes(int cols, int rows, int factor) {
    const double points = drainage_points(cols, rows, factor);
    if (factor == 1) return drainage_peak_base_bytes + drainage_check_margin * drainage_peak_bytes_per_point * points;
    return drainage_resampled_bytes_per_point * points;
}

double crease_tiles_build_bytes(double points) { return crease_tiles_bytes_per_point * points; }

int drainage_factor_for(int cols, int rows, int resample) {
    if (resample > 0) return resample;
    Terrain size_only;  // drainage_resample_factor reads the size alone
    size_only.cols = cols, size_only.rows = rows;
    return drainage_resample_factor(size_only, DrainageOptions{});
}

void check_drainage_memory(const std::string& stage, const std::string& file, int cols, int rows, int factor,
                           std::uint64_t budget) {
    check_memory(stage, file, "the drainage grid at factor " + std::to_string(factor) + " (" +
                                  drainage_grid_size(cols, rows, factor) + " points)",
                 drainage_build_bytes(cols, rows, factor), budget);
}

std::string drainage_grid_size(int cols, int rows, int factor) {
    const double f = factor;
    char grid[96];
    std::snprintf(grid, sizeof grid, "%.0fx%.0f", std::max(cols - 1, 0) * f + 1.0, std::max(rows - 1, 0) * f + 1.0);
    return grid;
}

}  // namespace penink
