#include "surface/pn_triangle.hpp"

#include <cmath>
#include <type_traits>

#include <glm/geometric.hpp>

namespace penink {

namespace {

// Edge control point near pi on edge pi->pj: (2 pi + pj - ((pj - pi) . ni) ni) / 3, whole
// (T = vec3) or one coordinate (T = float; d = (pj - pi) . ni either way).
template <class T, class D> [[gnu::always_inline]] inline T edge_point(const T& pi, const T& pj, D d, const T& ni) {
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
template <class T, class W> T cubic(const T* b, W w, W u, W v) {
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

namespace {

// pn_height_normal's arithmetic on lanes F: float, or 4 floats (GCC's vector extension) evaluated
// side by side, each lane the same IEEE operations in the same order as the float path (glm's
// dot: (x + y) + z; length: sqrt(dot); normalize: v * (1 / sqrt(dot)); both sides of a choice
// made, the chosen one kept), so every lane's floats are the float path's.
using F4 = float __attribute__((vector_size(16)));

template <class F> struct V3 {
    F x, y, z;
};
template <class F> V3<F> operator+(const V3<F>& a, const V3<F>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class F> V3<F> operator-(const V3<F>& a, const V3<F>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class F> V3<F> operator*(const V3<F>& a, F s) { return {a.x * s, a.y * s, a.z * s}; }
template <class F> V3<F> operator*(F s, const V3<F>& a) { return {s * a.x, s * a.y, s * a.z}; }
template <class F> V3<F> operator/(const V3<F>& a, F s) { return {a.x / s, a.y / s, a.z / s}; }
template <class F> F dot(const V3<F>& a, const V3<F>& b) {
    const V3<F> t{a.x * b.x, a.y * b.y, a.z * b.z};
    return t.x + t.y + t.z;
}
inline float lane_sqrt(float x) { return std::sqrt(x); }
inline F4 lane_sqrt(F4 x) { return __builtin_ia32_sqrtps(x); }
inline float choose(bool c, float a, float b) { return c ? a : b; }
template <class M> F4 choose(M c, F4 a, F4 b) { return c ? a : b; }
template <class F, class M> V3<F> choose(M c, const V3<F>& a, const V3<F>& b) {
    return {choose(c, a.x, b.x), choose(c, a.y, b.y), choose(c, a.z, b.z)};
}
template <class F> V3<F> normalized(const V3<F>& v) { return v * (1.0f / lane_sqrt(dot(v, v))); }
template <class F> F splat(float x) {
    if constexpr (std::is_same_v<F, float>) return x;
    else return F{x, x, x, x};
}

template <class F> [[gnu::always_inline]] inline V3<F> lane_edge_normal(const V3<F>& pi, const V3<F>& pj, const V3<F>& ni, const V3<F>& nj) {
    const V3<F> e = pj - pi;
    const F ee = dot(e, e), zero = splat<F>(0.0f);
    const F v = choose(ee > zero, 2.0f * dot(e, ni + nj) / ee, zero);
    const V3<F> n = ni + nj - v * e;
    const F len = lane_sqrt(dot(n, n));
    return choose(len > zero, n / len, normalized(ni + nj));
}

template <class F>
F lane_height_normal(const V3<F> p[3], const V3<F> n[3], F w, F u, F v, V3<F>& normal) {
    F b[10];
    b[0] = p[0].z, b[1] = p[1].z, b[2] = p[2].z;
    b[3] = edge_point(p[0].z, p[1].z, dot(p[1] - p[0], n[0]), n[0].z);
    b[4] = edge_point(p[1].z, p[0].z, dot(p[0] - p[1], n[1]), n[1].z);
    b[5] = edge_point(p[1].z, p[2].z, dot(p[2] - p[1], n[1]), n[1].z);
    b[6] = edge_point(p[2].z, p[1].z, dot(p[1] - p[2], n[2]), n[2].z);
    b[7] = edge_point(p[2].z, p[0].z, dot(p[0] - p[2], n[2]), n[2].z);
    b[8] = edge_point(p[0].z, p[2].z, dot(p[2] - p[0], n[0]), n[0].z);
    b[9] = centre_point(b, p[0].z, p[1].z, p[2].z);
    const V3<F> m[6] = {n[0], n[1], n[2], lane_edge_normal(p[0], p[1], n[0], n[1]),
                        lane_edge_normal(p[1], p[2], n[1], n[2]), lane_edge_normal(p[2], p[0], n[2], n[0])};
    // quadratic_normal
    normal = normalized(m[0] * (w * w) + m[1] * (u * u) + m[2] * (v * v) + m[3] * (w * u) + m[4] * (u * v) +
                        m[5] * (w * v));
    return cubic(b, w, u, v);
}

V3<float> lanes(const glm::vec3& a) { return {a.x, a.y, a.z}; }

}  // namespace

float pn_height_normal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& n0,
                       const glm::vec3& n1, const glm::vec3& n2, const glm::vec3& t, glm::vec3& normal) {
    const V3<float> p[3] = {lanes(p0), lanes(p1), lanes(p2)}, n[3] = {lanes(n0), lanes(n1), lanes(n2)};
    V3<float> m;
    const float z = lane_height_normal(p, n, t.x, t.y, t.z, m);
    normal = glm::vec3(m.x, m.y, m.z);
    return z;
}

void pn_height_normal4(const glm::vec3 p[4][3], const glm::vec3 n[4][3], const glm::vec3 t[4], float z[4],
                       glm::vec3 normal[4]) {
    V3<F4> pl[3], nl[3];
    for (int k = 0; k < 3; ++k) {
        pl[k] = {F4{p[0][k].x, p[1][k].x, p[2][k].x, p[3][k].x}, F4{p[0][k].y, p[1][k].y, p[2][k].y, p[3][k].y},
                 F4{p[0][k].z, p[1][k].z, p[2][k].z, p[3][k].z}};
        nl[k] = {F4{n[0][k].x, n[1][k].x, n[2][k].x, n[3][k].x}, F4{n[0][k].y, n[1][k].y, n[2][k].y, n[3][k].y},
                 F4{n[0][k].z, n[1][k].z, n[2][k].z, n[3][k].z}};
    }
    const F4 w{t[0].x, t[1].x, t[2].x, t[3].x}, u{t[0].y, t[1].y, t[2].y, t[3].y}, v{t[0].z, t[1].z, t[2].z, t[3].z};
    V3<F4> m;
    const F4 h = lane_height_normal(pl, nl, w, u, v, m);
    for (int i = 0; i < 4; ++i) z[i] = h[i], normal[i] = glm::vec3(m.x[i], m.y[i], m.z[i]);
}

}  // namespace penink
