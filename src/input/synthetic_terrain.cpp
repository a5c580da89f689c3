#include "input/synthetic_terrain.hpp"

#include <cmath>

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

}  // namespace penink
