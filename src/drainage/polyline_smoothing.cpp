#include "drainage/polyline_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace penink {

GaussianKernel::GaussianKernel(double sigma) : smooths_(sigma > 0.0) {
    if (!smooths_) return;
    const std::ptrdiff_t radius = std::ptrdiff_t(std::ceil(3.0 * sigma));
    w_.resize(std::size_t(radius) + 1);
    for (std::ptrdiff_t j = 0; j <= radius; ++j) {
        w_[std::size_t(j)] = std::exp(-0.5 * double(j * j) / (sigma * sigma));
        total_ += j ? 2.0 * w_[std::size_t(j)] : w_[0];
    }
}

void GaussianKernel::smooth(const std::vector<glm::dvec2>& in, std::vector<glm::dvec2>& out) const {
    const std::ptrdiff_t n = std::ptrdiff_t(in.size());
    out = in;
    if (n < 3 || !smooths_) return;
    const std::ptrdiff_t radius = std::ptrdiff_t(w_.size()) - 1;
    const std::vector<double>& w = w_;
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
        out[std::size_t(k)] = acc / total_;
    }
}

void gaussian_smooth(const std::vector<glm::dvec2>& in, double sigma, std::vector<glm::dvec2>& out) {
    GaussianKernel(sigma).smooth(in, out);
}

}  // namespace penink
