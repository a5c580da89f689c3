#include "lines/raycast_silhouettes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "core/parallel_chunks.hpp"

namespace penink {

namespace {

constexpr float none = std::numeric_limits<float>::infinity();

struct Hits {
    int w = 0, h = 0;
    std::vector<float> dist;           // eye distance of the nearest hit, `none` where no hit
    std::vector<std::uint32_t> tri;    // tessellated triangle hit
};

}  // namespace

std::vector<std::vector<glm::vec2>> raycast_silhouettes(const std::vector<glm::vec3>& pos,
                                                        const std::vector<glm::uvec3>& tris,
                                                        const std::vector<std::uint8_t>& cut, const Camera& camera,
                                                        const RaycastOptions& options) {
    const int s = std::max(1, options.supersample);
    Hits hits;
    hits.w = camera.width * s, hits.h = camera.height * s;
    const glm::dmat4 vp = view_projection(camera);
    hits.dist.assign(std::size_t(hits.w) * hits.h, none);
    hits.tri.assign(hits.dist.size(), 0);

    // Ray through sample (i, j): direction = far-plane point - eye, affine in (i, j).
    const glm::dmat4 inv = glm::inverse(vp);
    const glm::dvec3 eye = camera.eye;
    const auto ray = [&](double sx, double sy) {
        const glm::dvec4 q = inv * glm::dvec4(2.0 * sx / hits.w - 1.0, 1.0 - 2.0 * sy / hits.h, 1.0, 1.0);
        return glm::normalize(glm::dvec3(q) / q.w - eye);
    };
    // Screen boxes (sample units) of the triangles in front of the eye.
    struct Box {
        float x0, y0, x1, y1;
    };
    std::vector<Box> box(tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t) {
        Box b{1e30f, 1e30f, -1e30f, -1e30f};
        bool behind = false;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec4 c = vp * glm::dvec4(glm::dvec3(pos[tris[t][k]]), 1.0);
            if (c.w <= 1e-9) behind = true;
            const double x = (c.x / c.w * 0.5 + 0.5) * hits.w, y = (0.5 - c.y / c.w * 0.5) * hits.h;
            b = {std::min(b.x0, float(x)), std::min(b.y0, float(y)), std::max(b.x1, float(x)), std::max(b.y1, float(y))};
        }
        box[t] = behind ? Box{0.0f, 0.0f, float(hits.w), float(hits.h)} : b;
    }
    parallel_chunks(std::size_t(hits.h), 16, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t t = 0; t < tris.size(); ++t) {
            const Box& b = box[t];
            const int j0 = std::max<int>(int(r0), int(std::ceil(b.y0 - 0.5f)));
            const int j1 = std::min<int>(int(r1) - 1, int(std::floor(b.y1 - 0.5f)));
            const int i0 = std::max(0, int(std::ceil(b.x0 - 0.5f))), i1 = std::min(hits.w - 1, int(std::floor(b.x1 - 0.5f)));
            if (j0 > j1 || i0 > i1) continue;
            const glm::dvec3 p0(pos[tris[t][0]]), e1 = glm::dvec3(pos[tris[t][1]]) - p0,
                e2 = glm::dvec3(pos[tris[t][2]]) - p0, o = eye - p0;
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) {
                    const glm::dvec3 d = ray(i + 0.5, j + 0.5);
                    const glm::dvec3 pv = glm::cross(d, e2);
                    const double det = glm::dot(e1, pv);
                    if (std::abs(det) < 1e-18) continue;
                    const double u = glm::dot(o, pv) / det;
                    if (u < 0.0 || u > 1.0) continue;
                    const glm::dvec3 qv = glm::cross(o, e1);
                    const double v = glm::dot(d, qv) / det;
                    if (v < 0.0 || u + v > 1.0) continue;
                    const double dist = glm::dot(e2, qv) / det;
                    const std::size_t k = std::size_t(j) * hits.w + i;
                    if (dist > 0.0 && dist < hits.dist[k]) hits.dist[k] = float(dist), hits.tri[k] = std::uint32_t(t);
                }
        }
    });

    // Splits between neighbouring samples.
    const double dalpha = 2.0 * std::tan(camera.fov * 0.5 * 3.14159265358979323846 / 180.0) / hits.w;
    const double max_tan = std::tan(89.0 * 3.14159265358979323846 / 180.0);
    const auto split = [&](std::size_t a, std::size_t b) {
        if (hits.dist[a] > hits.dist[b]) std::swap(a, b);
        const float da = hits.dist[a], db = hits.dist[b];
        if (da == none || (!cut.empty() && cut[hits.tri[a]])) return false;
        if (db == none) return true;
        const glm::uvec3 t = tris[hits.tri[b]];
        const glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(pos[t[1]] - pos[t[0]]),
                                                       glm::dvec3(pos[t[2]] - pos[t[0]])));
        const double c = std::abs(glm::dot(n, ray((b % hits.w) + 0.5, (b / hits.w) + 0.5)));
        const double tan_psi = std::min(max_tan, std::sqrt(std::max(0.0, 1.0 - c * c)) / std::max(c, 1e-12));
        return db - da > std::max(4.0 * db * dalpha * tan_psi, options.min_gap * db);
    };
    // Marching squares over 2 x 2 sample cells; a split's point is midway between its samples.
    const float inv_s = 1.0f / float(s);
    return parallel_collect<std::vector<glm::vec2>>(std::size_t(std::max(0, hits.h - 1)), 16,
        [&](std::size_t r0, std::size_t r1, std::vector<std::vector<glm::vec2>>& out) {
            for (std::size_t j = r0; j < r1; ++j)
                for (int i = 0; i + 1 < hits.w; ++i) {
                    const std::size_t k00 = j * hits.w + i, k10 = k00 + 1, k01 = k00 + hits.w, k11 = k01 + 1;
                    glm::vec2 p[4];
                    int n = 0;
                    const float x = float(i) + 1.0f, y = float(j) + 1.0f;  // cell centre in sample units
                    if (split(k00, k10)) p[n++] = {x, y - 0.5f};  // top
                    if (split(k10, k11)) p[n++] = {x + 0.5f, y};  // right
                    if (split(k01, k11)) p[n++] = {x, y + 0.5f};  // bottom
                    if (split(k00, k01)) p[n++] = {x - 0.5f, y};  // left
                    if (n < 2) continue;
                    for (int a = 0; a + 1 < n; a += 2) out.push_back({p[a] * inv_s, p[a + 1] * inv_s});
                    if (n == 3) out.push_back({p[1] * inv_s, p[2] * inv_s});
                }
        });
}

}  // namespace penink
