#include "support/synthetic_terrain.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace penink {

Terrain terrain_from_function(int cols, int rows, double spacing, const HeightFunction& f) {
    Terrain t;
    t.cols = cols, t.rows = rows;
    t.source = "synthetic";
    t.pos.resize(t.size());
    t.valid.assign(t.size(), 1);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            const double x = (c - (cols - 1) * 0.5) * spacing, y = ((rows - 1) * 0.5 - r) * spacing;
            t.pos[t.index(c, r)] = glm::vec3(float(x), float(y), float(f(x, y)));
        }
    }
    return t;
}

HeightFunction gaussian_hill(double height, double sigma) {
    return [=](double x, double y) { return height * std::exp(-(x * x + y * y) / (2.0 * sigma * sigma)); };
}

HeightFunction analytic_height(const AnalyticTerrain& s) {
    const double h = s.height, w = s.width;
    switch (s.shape) {
        case AnalyticShape::plain: return [](double, double) { return 0.0; };
        case AnalyticShape::gaussian_hill: return gaussian_hill(h, w);
        case AnalyticShape::hemisphere:
            return [=](double x, double y) { return std::sqrt(std::max(0.0, w * w - x * x - y * y)); };
        case AnalyticShape::cliff: return [=](double, double y) { return y <= 0.0 ? h : 0.0; };
        case AnalyticShape::ridge: return [=](double x, double) { return h * std::exp(-x * x / (2.0 * w * w)); };
    }
    return [](double, double) { return 0.0; };
}

Terrain analytic_grid(const AnalyticTerrain& shape, double spacing) {
    const int n = 2 * int(std::lround(shape.half_extent / spacing)) + 1;
    Terrain t = terrain_from_function(n, n, spacing, analytic_height(shape));
    t.source = "synthetic";
    for (const glm::vec3& p : t.pos) {
        t.elevation_min = std::min(t.elevation_min, double(p.z));
        t.elevation_max = std::max(t.elevation_max, double(p.z));
    }
    return t;
}

void cut_hole(Terrain& t, double cx, double cy, double radius) {
    for (std::size_t i = 0; i < t.size(); ++i)
        if (glm::length(glm::dvec2(t.pos[i].x - cx, t.pos[i].y - cy)) <= radius) t.valid[i] = 0;
}

double rough_hills(double x, double y) {
    struct Hill {
        double x, y, h, s;
    };
    static const Hill hs[] = {{-900, -700, 420, 520}, {800, 600, 360, 380}, {300, -1100, 250, 260},
                              {-1200, 900, 300, 700}, {1300, -900, 180, 160}, {0, 200, 120, 90}};
    double z = 50.0;
    for (const Hill& h : hs) z += h.h * std::exp(-((x - h.x) * (x - h.x) + (y - h.y) * (y - h.y)) / (2 * h.s * h.s));
    double lambda = 1024.0;
    for (int k = 0; k < 9; ++k, lambda *= 0.5) {
        const double a = 0.7 + 2.1 * k, w = 2.0 * M_PI / lambda;
        const double u = x * std::cos(a) + y * std::sin(a), v = -x * std::sin(a) + y * std::cos(a);
        z += 0.015 * lambda * std::sin(w * u + 1.3 * k) * std::cos(w * 0.8 * v + 0.4 * k);
    }
    return z;
}

}  // namespace penink
