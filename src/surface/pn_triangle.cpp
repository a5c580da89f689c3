#include "surface/pn_triangle.hpp"

#include <glm/geometric.hpp>

namespace penink {

namespace {

// Edge control point near pi on edge pi->pj: (2 pi + pj - ((pj - pi) . ni) ni) / 3, whole
// (T = vec3) or one coordinate (T = float; d = (pj - pi) . ni either way).
template <class T> [[gnu::always_inline]] inline T edge_point(const T& pi, const T& pj, float d, const T& ni) {
    return (2.0f * pi + pj - d * ni) / 3.0f;
}
[[gnu::always_inline]] inline glm::vec3 edge_point(const glm::vec3& pi, const glm::vec3& pj, const glm::vec3& ni) {
    return edge_point(pi, pj, glm::dot(pj - pi, ni), ni);
}

// The centre control point b111 from the six edge points b[3..8] and the corners (T as above).
template <class T> T centre_point(const T* b, const T& p0, const T& p1, const T& p2) {
    const T e = (b[3] + b[4] + b[5] + b[6] + b[7] + b[8]) / 6.0f;
    const T v = (p0 + p1 + p2) / 3.0f;
    return e + (e - v) * 0.5f;
}

// The cubic Bezier patch of control points b[0..9] at weights (w, u, v) (T as above).
template <class T> T cubic(const T* b, float w, float u, float v) {
    return b[0] * (w * w * w) + b[1] * (u * u * u) + b[2] * (v * v * v) + b[3] * (3.0f * w * w * u) +
           b[4] * (3.0f * w * u * u) + b[5] * (3.0f * u * u * v) + b[6] * (3.0f * u * v * v) +
           b[7] * (3.0f * w * v * v) + b[8] * (3.0f * w * w * v) + b[9] * (6.0f * w * u * v);
}

// Mid-edge normal: reflection of ni + nj across the plane perpendicular to the edge.
// Inlined with edge_point into their callers (pn_height_normal, pn_patch): the same floats, without
// the calls.
[[gnu::always_inline]] inline glm::vec3 edge_normal(const glm::vec3& pi, const glm::vec3& pj, const glm::vec3& ni,
                                                    const glm::vec3& nj) {
    const glm::vec3 e = pj - pi;
    const float ee = glm::dot(e, e);
    const float v = ee > 0.0f ? 2.0f * glm::dot(e, ni + nj) / ee : 0.0f;
    const glm::vec3 n = ni + nj - v * e;
    const float len = glm::length(n);
    return len > 0.0f ? n / len : glm::normalize(ni + nj);
}

}  // namespace

PnPatch pn_patch(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                 const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& n2) {
    PnPatch q;
    q.b[0] = p0, q.b[1] = p1, q.b[2] = p2;
    q.b[3] = edge_point(p0, p1, n0);  // b210
    q.b[4] = edge_point(p1, p0, n1);  // b120
    q.b[5] = edge_point(p1, p2, n1);  // b021
    q.b[6] = edge_point(p2, p1, n2);  // b012
    q.b[7] = edge_point(p2, p0, n2);  // b102
    q.b[8] = edge_point(p0, p2, n0);  // b201
    q.b[9] = centre_point(q.b.data(), p0, p1, p2);  // b111
    q.n[0] = n0, q.n[1] = n1, q.n[2] = n2;
    q.n[3] = edge_normal(p0, p1, n0, n1);  // n110
    q.n[4] = edge_normal(p1, p2, n1, n2);  // n011
    q.n[5] = edge_normal(p2, p0, n2, n0);  // n101
    return q;
}

glm::vec3 pn_position(const PnPatch& q, const glm::vec3& t) {
    return cubic(q.b.data(), t.x, t.y, t.z);  // weights of p0, p1, p2
}

namespace {

// The quadratic normal patch of n[0..5] at weights (w, u, v), normalised.
glm::vec3 quadratic_normal(const glm::vec3* n, float w, float u, float v) {
    return glm::normalize(n[0] * (w * w) + n[1] * (u * u) + n[2] * (v * v) + n[3] * (w * u) + n[4] * (u * v) +
                          n[5] * (w * v));
}

}  // namespace

glm::vec3 pn_normal(const PnPatch& q, const glm::vec3& t) { return quadratic_normal(q.n.data(), t.x, t.y, t.z); }

float pn_height_normal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& n0,
                       const glm::vec3& n1, const glm::vec3& n2, const glm::vec3& t, glm::vec3& normal) {
    float b[10];
    b[0] = p0.z, b[1] = p1.z, b[2] = p2.z;
    b[3] = edge_point(p0.z, p1.z, glm::dot(p1 - p0, n0), n0.z);
    b[4] = edge_point(p1.z, p0.z, glm::dot(p0 - p1, n1), n1.z);
    b[5] = edge_point(p1.z, p2.z, glm::dot(p2 - p1, n1), n1.z);
    b[6] = edge_point(p2.z, p1.z, glm::dot(p1 - p2, n2), n2.z);
    b[7] = edge_point(p2.z, p0.z, glm::dot(p0 - p2, n2), n2.z);
    b[8] = edge_point(p0.z, p2.z, glm::dot(p2 - p0, n0), n0.z);
    b[9] = centre_point(b, p0.z, p1.z, p2.z);
    const glm::vec3 n[6] = {n0, n1, n2, edge_normal(p0, p1, n0, n1), edge_normal(p1, p2, n1, n2),
                            edge_normal(p2, p0, n2, n0)};
    normal = quadratic_normal(n, t.x, t.y, t.z);
    return cubic(b, t.x, t.y, t.z);
}

}  // namespace penink
