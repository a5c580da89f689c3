#include "drainage/ridge_crests.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/parallel_chunks.hpp"
#include "drainage/polyline_smoothing.hpp"

namespace penink {

namespace {

// The PN surface's z at a plan point; false off the surface.
bool surface_z(const DemDraper& draper, glm::dvec2 p, int& c, int& r, double& z) {
    DemHit hit;
    if (!draper.locate(p.x, p.y, c, r, hit)) return false;
    glm::vec3 pos, n;
    draper.position_normal(hit, pos, n);
    z = pos.z;
    return true;
}

// The offset along unit normal `n` from p to the crest within reach (see the header); false when
// a sample is off the surface.
bool crest_offset(const DemDraper& draper, glm::dvec2 p, glm::dvec2 n, const CrestOptions& o, int& c, int& r,
                  double& offset) {
    const int m = std::max(1, o.samples);
    const double h = o.reach / m;
    double z[64];
    int best = 0;
    for (int j = -m; j <= m; ++j) {
        if (!surface_z(draper, p + n * (h * j), c, r, z[j + m])) return false;
        if (z[j + m] > z[best]) best = j + m;
    }
    offset = h * (best - m);
    if (best > 0 && best < 2 * m) {  // the parabola's top through the best sample and its neighbours
        const double a = z[best - 1], b = z[best], d = z[best + 1], den = a - 2.0 * b + d;
        if (den < 0.0) offset += h * std::clamp(0.5 * (a - d) / den, -0.5, 0.5);
    }
    return true;
}

}  // namespace

CrestOptions crest_options(const DrainageGrid& g) {
    CrestOptions o;
    const int f = std::max(1, g.factor);
    const int c = std::min(g.cols - 1, f), r = std::min(g.rows - 1, f);  // one DEM cell from node (0, 0)
    const glm::dvec2 o0 = grid_xy(g, 0, 0);
    const double cell = 0.5 * (glm::length(grid_xy(g, c, 0) - o0) * f / std::max(1, c) +
                               glm::length(grid_xy(g, 0, r) - o0) * f / std::max(1, r));
    o.reach = 1.5 * cell;
    o.fade = 3 * f;
    o.sigma = std::max(2.0, double(f));
    return o;
}

void snap_to_crests(DrapedLineSet& set, const DemSurface& surface, const CrestOptions& o) {
    if (o.samples > 31 || !(o.reach > 0.0)) return;
    parallel_chunks(set.lines.size(), 1024, [&](std::size_t l0, std::size_t l1) {
        const DemDraper draper(surface);
        std::vector<glm::dvec2> p, q;
        for (std::size_t i = l0; i < l1; ++i) {
            const DrapedLine& l = set.lines[i];
            if (l.count < 3) continue;
            DrapedVertex* v = set.vertices.data() + l.first;
            p.resize(l.count);
            for (std::uint32_t k = 0; k < l.count; ++k) p[k] = {v[k].x, v[k].y};
            q = p;
            int c = -1, r = -1;
            for (std::uint32_t k = 1; k + 1 < l.count; ++k) {
                const glm::dvec2 t = p[k + 1] - p[k - 1];
                const double tl = std::sqrt(t.x * t.x + t.y * t.y);
                if (!(tl > 0.0)) continue;
                double offset;
                if (!crest_offset(draper, p[k], glm::dvec2(-t.y, t.x) / tl, o, c, r, offset)) {
                    c = r = -1;
                    continue;
                }
                const std::uint32_t from_end = std::min(k, l.count - 1 - k);
                const double fade = o.fade > 0 ? std::min(1.0, double(from_end) / o.fade) : 1.0;
                q[k] = p[k] + glm::dvec2(-t.y, t.x) / tl * (offset * fade);
            }
            gaussian_smooth(q, o.sigma, p);
            for (std::uint32_t k = 1; k + 1 < l.count; ++k) v[k].x = float(p[k].x), v[k].y = float(p[k].y);
        }
    });
}

}  // namespace penink
