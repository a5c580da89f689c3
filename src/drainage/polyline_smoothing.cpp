#include "drainage/polyline_smoothing.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
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

void gaussian_smooth(const std::vector<glm::dvec2>& in, double sigma, std::vector<glm::dvec2>& out) {
    const std::ptrdiff_t n = std::ptrdiff_t(in.size());
    out = in;
    if (n < 3 || !(sigma > 0.0)) return;
    const std::ptrdiff_t radius = std::ptrdiff_t(std::ceil(3.0 * sigma));
    std::vector<double> w(std::size_t(radius) + 1);
    double total = 0.0;
    for (std::ptrdiff_t j = 0; j <= radius; ++j) {
        w[std::size_t(j)] = std::exp(-0.5 * double(j * j) / (sigma * sigma));
        total += j ? 2.0 * w[std::size_t(j)] : w[0];
    }
    auto at = [&](std::ptrdiff_t j) {
        if (j < 0) return 2.0 * in[0] - in[std::size_t(std::min(-j, n - 1))];
        if (j >= n) return 2.0 * in[std::size_t(n - 1)] - in[std::size_t(std::max<std::ptrdiff_t>(2 * (n - 1) - j, 0))];
        return in[std::size_t(j)];
    };
    for (std::ptrdiff_t k = 1; k + 1 < n; ++k) {
        glm::dvec2 acc = w[0] * in[std::size_t(k)];
        if (k >= radius && k + radius < n) {  // away from the ends: no reflection
            const glm::dvec2* p = in.data() + k;
            for (std::ptrdiff_t j = 1; j <= radius; ++j) acc += w[std::size_t(j)] * (p[-j] + p[j]);
        } else {
            for (std::ptrdiff_t j = 1; j <= radius; ++j) acc += w[std::size_t(j)] * (at(k - j) + at(k + j));
        }
        out[std::size_t(k)] = acc / total;
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
