#include "surface/grid_ground.hpp"

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>

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

glm::dvec2 plan(const Terrain& t, int c, int r) { return glm::dvec2(t.pos[t.index(c, r)]); }

}  // namespace

bool grid_ground_height(const Terrain& t, double x, double y, double& z) {
    if (t.cols < 2 || t.rows < 2 || t.pos.size() != t.size()) return false;
    const glm::dvec2 p(x, y);
    // Start: the cell the corner nodes predict (bilinear frame of the grid's outline).
    const glm::dvec2 o = plan(t, 0, 0), ec = plan(t, t.cols - 1, 0) - o, er = plan(t, 0, t.rows - 1) - o;
    const double det = ec.x * er.y - ec.y * er.x;
    int c = 0, r = 0;
    if (std::abs(det) > 1e-300) {
        const glm::dvec2 d = p - o;
        const double u = (d.x * er.y - d.y * er.x) / det, v = (ec.x * d.y - ec.y * d.x) / det;
        if (!std::isfinite(u) || !std::isfinite(v)) return false;
        c = int(std::clamp(std::floor(u * (t.cols - 1)), 0.0, double(t.cols - 2)));
        r = int(std::clamp(std::floor(v * (t.rows - 1)), 0.0, double(t.rows - 2)));
    }
    constexpr double eps = 1e-9;  // metres: points on a shared edge belong to either side
    for (int step = 0; step <= t.cols + t.rows; ++step) {
        // The cell's corners counter-clockwise seen from above: SW, SE, NE, NW; crossing edge k
        // (from corner k to k + 1) leads to the cell moved by (dc[k], dr[k]).
        const glm::dvec2 q[4] = {plan(t, c, r + 1), plan(t, c + 1, r + 1), plan(t, c + 1, r), plan(t, c, r)};
        constexpr int dc[4] = {0, 1, 0, -1}, dr[4] = {1, 0, -1, 0};
        int out = -1;
        double worst = -eps;
        for (int k = 0; k < 4; ++k) {
            const glm::dvec2 e = q[(k + 1) % 4] - q[k], d = p - q[k];
            const double len = std::hypot(e.x, e.y);
            const double side = len > 0.0 ? (e.x * d.y - e.y * d.x) / len : 0.0;  // > 0 inside
            if (side < worst) worst = side, out = k;
        }
        if (out < 0) {  // inside the cell: one of its two triangles, {NW, SW, SE} or {NW, SE, NE}
            const int ic[2][3] = {{c, c, c + 1}, {c, c + 1, c + 1}};
            const int ir[2][3] = {{r, r + 1, r + 1}, {r, r + 1, r}};
            int best_k = 0;
            double best = -1e300, best_w[3] = {0, 0, 0};
            for (int k = 0; k < 2; ++k) {
                double w[3];
                if (!barycentric(p, plan(t, ic[k][0], ir[k][0]), plan(t, ic[k][1], ir[k][1]),
                                 plan(t, ic[k][2], ir[k][2]), w))
                    continue;
                const double lowest = std::min({w[0], w[1], w[2]});
                if (lowest > best) best = lowest, best_k = k, std::copy(w, w + 3, best_w);
            }
            if (best == -1e300) return false;
            z = 0.0;
            for (int j = 0; j < 3; ++j) {
                const std::size_t n = t.index(ic[best_k][j], ir[best_k][j]);
                if (!t.valid[n]) return false;
                z += best_w[j] * double(t.pos[n].z);
            }
            return true;
        }
        const int nc = c + dc[out], nr = r + dr[out];
        if (nc < 0 || nr < 0 || nc > t.cols - 2 || nr > t.rows - 2) return false;
        c = nc, r = nr;
    }
    return false;
}

}  // namespace penink
