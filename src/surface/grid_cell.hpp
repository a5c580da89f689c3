// The cell of a grid of nodes under a plan point, found on the grid itself (no mesh): a cols x rows
// grid of nodes (row 0 north) whose plan positions node_xy(c, r) (local metres, x east, y north)
// form convex-enough quadrilateral cells, affine or curvilinear (a geographic DEM projected to UTM).
// Cell (c, r) has the corners (c, r) .. (c + 1, r + 1). Shared by the ground height
// (grid_ground.hpp) and the drainage build's drape (drainage/dem_surface.hpp).
#pragma once
#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>

namespace penink {

// The cell the grid's outline predicts for (x, y): the bilinear frame of the corner nodes (0, 0),
// (cols - 1, 0) and (0, rows - 1), clamped to the grid; exact on an affine grid. False when the
// point is not finite in that frame. Needs cols, rows >= 2.
template <class NodeXY>
bool outline_cell(const NodeXY& node_xy, int cols, int rows, double x, double y, int& c, int& r) {
    const glm::dvec2 o(node_xy(0, 0)), ec = glm::dvec2(node_xy(cols - 1, 0)) - o, er = glm::dvec2(node_xy(0, rows - 1)) - o;
    const double det = ec.x * er.y - ec.y * er.x;
    c = r = 0;
    if (std::abs(det) > 1e-300) {
        const glm::dvec2 d = glm::dvec2(x, y) - o;
        const double u = (d.x * er.y - d.y * er.x) / det, v = (ec.x * d.y - ec.y * d.x) / det;
        if (!std::isfinite(u) || !std::isfinite(v)) return false;
        c = int(std::clamp(std::floor(u * (cols - 1)), 0.0, double(cols - 2)));
        r = int(std::clamp(std::floor(v * (rows - 1)), 0.0, double(rows - 2)));
    }
    return true;
}

// Steps from cell (c, r) across the edge (x, y) lies farthest beyond until a cell's quadrilateral
// holds it (within a millionth of the edge's length): at most cols + rows steps. False when the
// walk leaves the grid (the point is off it) or runs out of steps.
template <class NodeXY>
bool walk_to_cell(const NodeXY& node_xy, int cols, int rows, double x, double y, int& c, int& r) {
    const glm::dvec2 p(x, y);
    for (int step = 0; step <= cols + rows; ++step) {
        // corners counter-clockwise seen from above: SW, SE, NE, NW; crossing edge k (corner k to
        // k + 1) leads to the cell moved by (dc[k], dr[k])
        const glm::dvec2 q[4] = {glm::dvec2(node_xy(c, r + 1)), glm::dvec2(node_xy(c + 1, r + 1)),
                                 glm::dvec2(node_xy(c + 1, r)), glm::dvec2(node_xy(c, r))};
        constexpr int dc[4] = {0, 1, 0, -1}, dr[4] = {1, 0, -1, 0};
        int out = -1;
        double worst = 0.0;
        for (int k = 0; k < 4; ++k) {
            const glm::dvec2 e = q[(k + 1) % 4] - q[k], d = p - q[k];
            const double cross = e.x * d.y - e.y * d.x, len2 = e.x * e.x + e.y * e.y;  // cross > 0 inside
            if (!(cross < -1e-6 * len2)) continue;
            const double side = cross / std::sqrt(len2);  // the distance beyond the edge
            if (side < worst) worst = side, out = k;
        }
        if (out < 0) return true;
        const int nc = c + dc[out], nr = r + dr[out];
        if (nc < 0 || nr < 0 || nc > cols - 2 || nr > rows - 2) return false;
        c = nc, r = nr;
    }
    return false;
}

}  // namespace penink
