// Ink coverage against a target tone (hachure_coverage.hpp).
#include "lines/hachure_coverage.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace penink {

InkCoverage::InkCoverage(int width, int height, float cell) : cell_(std::max(cell, 1.0f)) {
    cols_ = std::max(1, int(std::ceil(std::max(width, 1) / cell_)));
    rows_ = std::max(1, int(std::ceil(std::max(height, 1) / cell_)));
    const std::size_t n = std::size_t(cols_) * rows_;
    terrain_.assign(n, 0.0), tone_sum_.assign(n, 0.0), tone_n_.assign(n, 0.0), ink_.assign(n, 0.0), fixed_.assign(n, 0.0), gain_.assign(n, 1.0);
}

int InkCoverage::index(glm::vec2 px) const {
    // floor(px / cell) within [0, cols) x [0, rows): truncation where the quotient is >= 0
    const float fx = px.x / cell_, fy = px.y / cell_;
    if (!(fx >= 0.0f && fy >= 0.0f && fx < float(cols_) && fy < float(rows_))) return -1;
    const int cx = std::min(int(fx), cols_ - 1), cy = std::min(int(fy), rows_ - 1);
    return cy * cols_ + cx;
}

void InkCoverage::set_terrain(const DepthImage& depth) {
    if (is_empty(depth)) return;
    counted_terrain_ = true;
    std::fill(terrain_.begin(), terrain_.end(), 0.0);
    // index()'s cell of each pixel centre, per column and per row (counts: exact in any order)
    std::vector<int> cell_x(std::size_t(depth.width));
    for (int x = 0; x < depth.width; ++x) cell_x[std::size_t(x)] = int(std::floor((float(x) + 0.5f) / cell_));
    for (int y = 0; y < depth.height; ++y) {
        const int cy = int(std::floor((float(y) + 0.5f) / cell_));
        if (cy >= rows_) break;
        const float* row = depth.depth.data() + std::size_t(y) * depth.width;
        double* cells = terrain_.data() + std::size_t(cy) * cols_;
        for (int x = 0; x < depth.width; ++x)
            if (std::isfinite(row[x]) && cell_x[std::size_t(x)] < cols_) cells[cell_x[std::size_t(x)]] += 1.0;
    }
}

void InkCoverage::add_target(glm::vec2 px, double tone, double weight) {
    const int i = index(px);
    if (i < 0 || !(weight > 0.0)) return;
    tone_sum_[std::size_t(i)] += weight * tone, tone_n_[std::size_t(i)] += weight;
    if (!counted_terrain_) terrain_[std::size_t(i)] = double(cell_) * cell_;
}

void InkCoverage::add_ink(glm::vec2 a, glm::vec2 b, double width, bool fixed) {
    std::vector<double>& to = fixed ? fixed_ : ink_;
    const double len = double(glm::length(b - a));
    const int n = std::max(1, int(std::ceil(len)));
    for (int k = 0; k < n; ++k) {
        const int i = index(a + (b - a) * ((float(k) + 0.5f) / float(n)));
        if (i >= 0) to[std::size_t(i)] += len / n * width;
    }
}

void InkCoverage::clear_ink() { std::fill(ink_.begin(), ink_.end(), 0.0); }

void InkCoverage::update(double max_gain) {
    for (int cy = 0; cy < rows_; ++cy)
        for (int cx = 0; cx < cols_; ++cx) {
            double w = 0.0, k = 0.0;
            for (int y = std::max(0, cy - 1); y <= std::min(rows_ - 1, cy + 1); ++y)
                for (int x = std::max(0, cx - 1); x <= std::min(cols_ - 1, cx + 1); ++x) {
                    const std::size_t i = std::size_t(y) * cols_ + x;
                    if (tone_n_[i] > 0.0) w += wanted(i), k += laid(i);
                }
            double g = 1.0;
            if (k > 0.0) g = std::min(max_gain, w / k);
            else if (w > 0.0) g = max_gain;  // a target and no ink around: as much as the pen gives
            gain_[std::size_t(cy) * cols_ + cx] = g;
        }
}

double InkCoverage::gain(glm::vec2 px, double max_gain) const {
    // bilinear between cell centres, clamped at the border cells
    const double fx = std::clamp(double(px.x) / cell_ - 0.5, 0.0, double(cols_ - 1));
    const double fy = std::clamp(double(px.y) / cell_ - 0.5, 0.0, double(rows_ - 1));
    const int x0 = std::min(int(fx), cols_ - 1), y0 = std::min(int(fy), rows_ - 1);
    const int x1 = std::min(x0 + 1, cols_ - 1), y1 = std::min(y0 + 1, rows_ - 1);
    const double a = fx - x0, b = fy - y0;
    const auto g = [&](int x, int y) { return gain_[std::size_t(y) * cols_ + x]; };
    const double v = (1 - a) * (1 - b) * g(x0, y0) + a * (1 - b) * g(x1, y0) + (1 - a) * b * g(x0, y1) + a * b * g(x1, y1);
    return std::clamp(v, 0.0, max_gain);
}

double InkCoverage::ink_share() const {
    double want = 0.0, ink = 0.0;
    for (std::size_t i = 0; i < terrain_.size(); ++i)
        if (tone_n_[i] > 0.0) want += wanted(i), ink += laid(i);
    return want > 0.0 ? ink / want : 0.0;
}

}  // namespace penink
