#include "surface/pn_triangle.hpp"

#include <glm/geometric.hpp>

namespace penink {

namespace {

// Edge control point near pi on edge pi->pj: (2 pi + pj - ((pj - pi) . ni) ni) / 3.
glm::vec3 edge_point(const glm::vec3& pi, const glm::vec3& pj, const glm::vec3& ni) {
    return (2.0f * pi + pj - glm::dot(pj - pi, ni) * ni) / 3.0f;
}

// Mid-edge normal: reflection of ni + nj across the plane perpendicular to the edge.
glm::vec3 edge_normal(const glm::vec3& pi, const glm::vec3& pj, const glm::vec3& ni,
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
    const glm::vec3 e = (q.b[3] + q.b[4] + q.b[5] + q.b[6] + q.b[7] + q.b[8]) / 6.0f;
    const glm::vec3 v = (p0 + p1 + p2) / 3.0f;
    q.b[9] = e + (e - v) * 0.5f;  // b111
    q.n[0] = n0, q.n[1] = n1, q.n[2] = n2;
    q.n[3] = edge_normal(p0, p1, n0, n1);  // n110
    q.n[4] = edge_normal(p1, p2, n1, n2);  // n011
    q.n[5] = edge_normal(p2, p0, n2, n0);  // n101
    return q;
}

glm::vec3 pn_position(const PnPatch& q, const glm::vec3& t) {
    const float w = t.x, u = t.y, v = t.z;  // weights of p0, p1, p2
    return q.b[0] * (w * w * w) + q.b[1] * (u * u * u) + q.b[2] * (v * v * v) +
           q.b[3] * (3.0f * w * w * u) + q.b[4] * (3.0f * w * u * u) +
           q.b[5] * (3.0f * u * u * v) + q.b[6] * (3.0f * u * v * v) +
           q.b[7] * (3.0f * w * v * v) + q.b[8] * (3.0f * w * w * v) +
           q.b[9] * (6.0f * w * u * v);
}

glm::vec3 pn_normal(const PnPatch& q, const glm::vec3& t) {
    const float w = t.x, u = t.y, v = t.z;
    const glm::vec3 n = q.n[0] * (w * w) + q.n[1] * (u * u) + q.n[2] * (v * v) +
                        q.n[3] * (w * u) + q.n[4] * (u * v) + q.n[5] * (w * v);
    return glm::normalize(n);
}

}  // namespace penink
