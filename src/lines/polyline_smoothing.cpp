#include "lines/polyline_smoothing.hpp"

namespace penink {

void smooth_runs_xy(std::vector<glm::vec3>& positions, const std::vector<VertexRun>& runs, int iterations) {
    std::vector<glm::vec3> prev;
    for (const VertexRun& run : runs) {
        if (run.count < 3) continue;
        for (int it = 0; it < iterations; ++it) {
            prev.assign(positions.begin() + run.first, positions.begin() + run.first + run.count);
            for (std::uint32_t k = 1; k + 1 < run.count; ++k) {
                glm::vec3& p = positions[run.first + k];
                const glm::vec3 mean = (prev[k - 1] + prev[k + 1]) * 0.5f;
                p.x = 0.5f * (prev[k].x + mean.x);
                p.y = 0.5f * (prev[k].y + mean.y);
            }
        }
    }
}

}  // namespace penink
