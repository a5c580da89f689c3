#include "support/synthetic_terrain.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace penink {

HeightFunction gaussian_hill(double height, double sigma) {
    AnalyticTerrain hill;
    hill.height = height, hill.width = sigma;
    return analytic_height(hill);
}

void cut_hole(Terrain& t, double cx, double cy, double radius) {
    for (std::size_t i = 0; i < t.size(); ++i)
        if (glm::length(glm::dvec2(t.pos[i].x - cx, t.pos[i].y - cy)) <= radius) t.valid[i] = 0;
}

Terrain holed_hills() {
    Terrain t = terrain_from_function(90, 70, 10.0, [](double x, double y) { return rough_hills(4 * x, 4 * y) * 0.2; });
    cut_hole(t, 60.0, -40.0, 55.0);
    cut_hole(t, -250.0, 200.0, 80.0);
    return t;
}

Terrain on_affine_grid(Terrain t, double cell) {
    t.origin = {512345.0, 4012345.0};
    t.crs_wkt = "PROJCS[\"WGS 84 / UTM zone 16N\"]";
    t.utm_zone = 16;
    t.geotransform = {512000.0, cell, 0.0, 4013000.0, 0.0, -cell};
    t.xy_unit = 1.0;
    AffineNodes a;
    if (!terrain_affine(t, a)) return t;
    for (int r = 0; r < t.rows; ++r)
        for (int c = 0; c < t.cols; ++c) {
            const glm::vec2 xy = affine_node_xy(a, t.origin, c, r);
            t.pos[t.index(c, r)].x = xy.x, t.pos[t.index(c, r)].y = xy.y;
        }
    return t;
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
