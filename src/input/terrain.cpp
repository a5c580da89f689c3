#include "input/terrain.hpp"

#include <algorithm>
#include <limits>

#include <glm/common.hpp>

namespace penink {

Terrain crop_terrain(const Terrain& t, GridWindow w) {
    w.c0 = std::clamp(w.c0, 0, t.cols), w.c1 = std::clamp(w.c1, w.c0, t.cols);
    w.r0 = std::clamp(w.r0, 0, t.rows), w.r1 = std::clamp(w.r1, w.r0, t.rows);
    Terrain out = t;
    out.cols = w.cols(), out.rows = w.rows();
    out.source_col0 = t.source_col0 + w.c0, out.source_row0 = t.source_row0 + w.r0;
    out.pos.clear(), out.valid.clear();
    out.pos.reserve(out.size()), out.valid.reserve(out.size());
    for (int r = w.r0; r < w.r1; ++r) {
        const std::size_t i0 = t.index(w.c0, r);
        out.pos.insert(out.pos.end(), t.pos.begin() + i0, t.pos.begin() + (i0 + w.cols()));
        out.valid.insert(out.valid.end(), t.valid.begin() + i0, t.valid.begin() + (i0 + w.cols()));
    }
    return out;
}

glm::dvec2 affine_node_world(const std::array<double, 6>& gt, double unit, int c, int r) {
    const double x = c + 0.5, y = r + 0.5;
    return {(gt[0] + x * gt[1] + y * gt[2]) * unit, (gt[3] + x * gt[4] + y * gt[5]) * unit};
}

glm::vec2 affine_node_xy(const AffineNodes& a, glm::dvec2 origin, int c, int r) {
    return glm::vec2(affine_node_world(a.gt, a.unit, c + a.col0, r + a.row0) - origin);
}

bool terrain_affine(const Terrain& t, AffineNodes& out) {
    if (!(t.xy_unit > 0.0)) return false;
    out = {t.geotransform, t.xy_unit, t.source_col0, t.source_row0};
    return true;
}

bool terrain_bounds(const Terrain& t, glm::dvec3& lo, glm::dvec3& hi) {
    // Floats compared as stored (exact), widened to double once at the end.
    glm::vec3 l(std::numeric_limits<float>::infinity()), h(-std::numeric_limits<float>::infinity());
    bool any = false;
    for (std::size_t i = 0; i < t.size(); ++i) {
        if (!t.valid[i]) continue;
        l = glm::min(l, t.pos[i]), h = glm::max(h, t.pos[i]);
        any = true;
    }
    if (any) lo = glm::dvec3(l), hi = glm::dvec3(h);
    return any;
}

}  // namespace penink
