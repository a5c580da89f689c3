#include "surface/grid_ground.hpp"

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>

#include "surface/grid_cell.hpp"

namespace penink {

namespace {

// Barycentric coordinates of p in the plan triangle (a, b, c); false for a degenerate one.
bool barycentric(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, double w[3]) {
    const double det = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
    if (std::abs(det) < 1e-300) return false;
    w[0] = ((b.y - c.y) * (p.x - c.x) + (c.x - b.x) * (p.y - c.y)) / det;
    w[1] = ((c.y - a.y) * (p.x - c.x) + (a.x - c.x) * (p.y - c.y)) / det;
    w[2] = 1.0 - w[0] - w[1];
    return true;
}

glm::dvec2 plan(const GridNodes& t, int c, int r) { return glm::dvec2(t.at(c, r)); }

}  // namespace

bool grid_ground_height(const Terrain& t, double x, double y, double& z) {
    if (t.pos.size() != t.size() || t.valid.size() != t.size()) return false;
    return grid_ground_height(grid_nodes(t), x, y, z);
}

bool grid_ground_height(const GridNodes& t, double x, double y, double& z) {
    if (t.cols < 2 || t.rows < 2 || !t.pos || !std::isfinite(x) || !std::isfinite(y)) return false;
    const auto xy = [&](int c, int r) { return plan(t, c, r); };
    int c = 0, r = 0;
    if (!outline_cell(xy, t.cols, t.rows, x, y, c, r) || !walk_to_cell(xy, t.cols, t.rows, x, y, c, r)) return false;
    // One of the cell's two triangles, {NW, SW, SE} or {NW, SE, NE}: the one the point lies
    // deepest inside (either, on the diagonal).
    const glm::dvec2 p(x, y);
    const int ic[2][3] = {{c, c, c + 1}, {c, c + 1, c + 1}};
    const int ir[2][3] = {{r, r + 1, r + 1}, {r, r + 1, r}};
    int best_k = 0;
    double best = -1e300, best_w[3] = {0, 0, 0};
    for (int k = 0; k < 2; ++k) {
        double w[3];
        if (!barycentric(p, plan(t, ic[k][0], ir[k][0]), plan(t, ic[k][1], ir[k][1]), plan(t, ic[k][2], ir[k][2]), w))
            continue;
        const double lowest = std::min({w[0], w[1], w[2]});
        if (lowest > best) best = lowest, best_k = k, std::copy(w, w + 3, best_w);
    }
    if (best == -1e300) return false;
    z = 0.0;
    for (int j = 0; j < 3; ++j) {
        const std::size_t n = t.index(ic[best_k][j], ir[best_k][j]);
        if (!t.has_data(n)) return false;
        z += best_w[j] * double(t.at(n).z);
    }
    return true;
}

}  // namespace penink
