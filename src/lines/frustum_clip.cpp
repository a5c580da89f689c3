#include "lines/frustum_clip.hpp"

#include <glm/vec4.hpp>

namespace penink {

namespace {

// Distances of a clip-space point to the six planes (>= 0 inside).
void plane_distances(const glm::dvec4& c, double k, double d[6]) {
    d[0] = k * c.w + c.x, d[1] = k * c.w - c.x;
    d[2] = k * c.w + c.y, d[3] = k * c.w - c.y;
    d[4] = c.w + c.z, d[5] = c.w - c.z;
}

// Parameter range [t0, t1] of segment a-b inside all planes; false when empty.
bool clip_segment(const glm::dvec4& a, const glm::dvec4& b, double k, double& t0, double& t1) {
    double da[6], db[6];
    plane_distances(a, k, da), plane_distances(b, k, db);
    t0 = 0.0, t1 = 1.0;
    for (int i = 0; i < 6; ++i) {
        if (da[i] < 0 && db[i] < 0) return false;
        if (da[i] < 0) t0 = std::max(t0, da[i] / (da[i] - db[i]));
        else if (db[i] < 0) t1 = std::min(t1, da[i] / (da[i] - db[i]));
    }
    return t0 <= t1;
}

}  // namespace

std::vector<std::vector<glm::vec3>> clip_polylines_to_frustum(const std::vector<std::vector<glm::vec3>>& lines,
                                                             const glm::dmat4& vp, double margin) {
    const double k = 1.0 + margin;
    std::vector<std::vector<glm::vec3>> out;
    for (const auto& line : lines) {
        std::vector<glm::vec3> piece;
        for (std::size_t i = 0; i + 1 < line.size(); ++i) {
            const glm::dvec3 p(line[i]), q(line[i + 1]);
            double t0, t1;
            if (!clip_segment(vp * glm::dvec4(p, 1.0), vp * glm::dvec4(q, 1.0), k, t0, t1)) {
                if (piece.size() >= 2) out.push_back(std::move(piece));
                piece.clear();
                continue;
            }
            const glm::vec3 a(p + (q - p) * t0), b(p + (q - p) * t1);
            if (piece.empty()) piece.push_back(a);
            piece.push_back(b);
            if (t1 < 1.0) {  // leaves the frustum: this piece ends here
                if (piece.size() >= 2) out.push_back(std::move(piece));
                piece.clear();
            }
        }
        if (piece.size() >= 2) out.push_back(std::move(piece));
    }
    return out;
}

}  // namespace penink
