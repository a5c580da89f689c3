#include "drainage/polyline_smoothing.hpp"

#include <bit>
#include <cstdint>
#include <unordered_map>

namespace penink {

namespace {

std::uint64_t xy_key(const glm::vec3& p) {
    return (std::uint64_t(std::bit_cast<std::uint32_t>(p.x)) << 32) | std::bit_cast<std::uint32_t>(p.y);
}

}  // namespace

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

void rejoin_line_ends(const std::vector<glm::vec3>& before, const std::vector<VertexRun>& runs,
                      std::vector<glm::vec3>& positions) {
    std::unordered_map<std::uint64_t, std::uint32_t> interior;
    for (const VertexRun& r : runs)
        for (std::uint32_t k = 1; k + 1 < r.count; ++k) interior.emplace(xy_key(before[r.first + k]), r.first + k);
    for (const VertexRun& r : runs) {
        if (r.count < 2) continue;
        for (const std::uint32_t end : {r.first, r.first + r.count - 1}) {
            const auto it = interior.find(xy_key(before[end]));
            if (it == interior.end()) continue;
            positions[end].x = positions[it->second].x;
            positions[end].y = positions[it->second].y;
        }
    }
}

}  // namespace penink
