#include "surface/mesh_normals.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace penink {
namespace {

glm::vec3 safe_normalize(const glm::vec3& v) {
    float len = glm::length(v);
    return len > 0.0f ? v / len : glm::vec3(0, 0, 1);
}

float corner_angle(const glm::vec3& at, const glm::vec3& a, const glm::vec3& b) {
    glm::vec3 u = a - at, v = b - at;
    float lu = glm::length(u), lv = glm::length(v);
    if (lu <= 0.0f || lv <= 0.0f) return 0.0f;
    return std::acos(std::clamp(glm::dot(u, v) / (lu * lv), -1.0f, 1.0f));
}

// The edge neighbours of each vertex, sorted, without repeats.
std::vector<std::vector<unsigned>> vertex_neighbours(const TriangleMesh& mesh) {
    std::vector<std::vector<unsigned>> nb(mesh.positions.size());
    for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            nb[t[k]].push_back(t[(k + 1) % 3]);
            nb[t[k]].push_back(t[(k + 2) % 3]);
        }
    for (auto& list : nb) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    return nb;
}

}  // namespace

std::vector<glm::vec3> mesh_face_normals(const TriangleMesh& mesh) {
    std::vector<glm::vec3> out(mesh.triangles.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        const glm::vec3 &a = mesh.positions[t.x], &b = mesh.positions[t.y], &c = mesh.positions[t.z];
        out[f] = safe_normalize(glm::cross(b - a, c - a));
    }
    return out;
}

std::vector<glm::vec3> mesh_vertex_normals(const TriangleMesh& mesh, NormalWeighting weighting) {
    std::vector<glm::vec3> acc(mesh.positions.size(), glm::vec3(0.0f));
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
        glm::vec3 cr = glm::cross(p[1] - p[0], p[2] - p[0]);  // length = 2 * area
        if (weighting == NormalWeighting::area) {
            for (int k = 0; k < 3; ++k) acc[t[k]] += cr;
            continue;
        }
        glm::vec3 n = safe_normalize(cr);
        for (int k = 0; k < 3; ++k) acc[t[k]] += n * corner_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
    }
    for (auto& n : acc) n = safe_normalize(n);
    return acc;
}

std::vector<glm::vec3> smooth_vertex_normals(const TriangleMesh& mesh, std::vector<glm::vec3> normals,
                                             int iterations, float lambda) {
    if (iterations <= 0) return normals;
    const std::vector<std::vector<unsigned>> nb = vertex_neighbours(mesh);
    std::vector<glm::vec3> next(normals.size());
    for (int it = 0; it < iterations; ++it) {
        for (std::size_t i = 0; i < normals.size(); ++i) {
            if (nb[i].empty()) { next[i] = normals[i]; continue; }
            glm::vec3 mean(0.0f);
            for (unsigned j : nb[i]) mean += normals[j];
            mean /= float(nb[i].size());
            next[i] = safe_normalize((1.0f - lambda) * normals[i] + lambda * mean);
        }
        normals.swap(next);
    }
    return normals;
}

float mean_edge_length(const TriangleMesh& mesh) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            sum += glm::length(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]);
            ++n;
        }
    return n ? float(sum / double(n)) : 0.0f;
}

std::vector<glm::vec3> gaussian_filter_normals(const TriangleMesh& mesh, const std::vector<glm::vec3>& normals,
                                               float sigma) {
    if (!(sigma > 0.0f)) return normals;
    const std::vector<std::vector<unsigned>> nb = vertex_neighbours(mesh);
    std::vector<float> area(mesh.positions.size(), 0.0f);  // a third of each incident triangle
    for (const glm::uvec3& t : mesh.triangles) {
        const float a = glm::length(glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                               mesh.positions[t.z] - mesh.positions[t.x])) / 6.0f;
        for (int k = 0; k < 3; ++k) area[t[k]] += a;
    }
    const double reach2 = 4.0 * sigma * sigma, inv = 1.0 / (2.0 * double(sigma) * sigma);
    std::vector<glm::vec3> out(normals.size());
    std::vector<unsigned> seen(normals.size(), ~0u), stack, patch;
    for (unsigned i = 0; i < normals.size(); ++i) {
        // The patch: vertices within 2 sigma of p_i reached through edges that stay within 2 sigma.
        const glm::dvec3 pi(mesh.positions[i]), ni(normals[i]);
        patch.clear();
        stack.assign(1, i);
        seen[i] = i;
        while (!stack.empty()) {
            const unsigned j = stack.back();
            stack.pop_back();
            patch.push_back(j);
            for (unsigned k : nb[j]) {
                if (seen[k] == i) continue;
                const glm::dvec3 e = glm::dvec3(mesh.positions[k]) - pi;
                if (glm::dot(e, e) > reach2) continue;
                seen[k] = i;
                stack.push_back(k);
            }
        }
        // Tangent offsets in a basis (u, v) of the plane normal to n_i (Duff et al. 2017 basis).
        const double sign = ni.z >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sign + ni.z), b = ni.x * ni.y * a;
        const glm::dvec3 u(1.0 + sign * ni.x * ni.x * a, sign * b, -sign * ni.x), v(b, sign + ni.y * ni.y * a, -ni.y);
        double m[2] = {0, 0}, M[3] = {0, 0, 0};  // first moment; second moment (xx, xy, yy)
        for (unsigned j : patch) {
            const glm::dvec3 d = glm::dvec3(mesh.positions[j]) - pi;
            const double g = std::max(double(area[j]), 1e-30) * std::exp(-glm::dot(d, d) * inv);
            const double x = glm::dot(d, u), y = glm::dot(d, v);
            m[0] += g * x, m[1] += g * y, M[0] += g * x * x, M[1] += g * x * y, M[2] += g * y * y;
        }
        // Weights g_j (1 - c . t_j) with c = M^-1 m have no first moment: on a sphere (normals =
        // positions / r) the mean is then exactly radial, so the filter leaves a clean smooth
        // surface's normals alone instead of tilting them towards the patch's centroid.
        const double det = M[0] * M[2] - M[1] * M[1];
        double c[2] = {0, 0};
        if (det > 1e-12 * (M[0] + M[2]) * (M[0] + M[2]))
            c[0] = (M[2] * m[0] - M[1] * m[1]) / det, c[1] = (M[0] * m[1] - M[1] * m[0]) / det;
        glm::dvec3 sum(0.0);
        for (unsigned j : patch) {
            const glm::dvec3 d = glm::dvec3(mesh.positions[j]) - pi;
            const double g = std::max(double(area[j]), 1e-30) * std::exp(-glm::dot(d, d) * inv);
            sum += g * (1.0 - c[0] * glm::dot(d, u) - c[1] * glm::dot(d, v)) * glm::dvec3(normals[j]);
        }
        out[i] = glm::length(sum) > 0.0 ? glm::vec3(glm::normalize(sum)) : normals[i];
    }
    return out;
}

SurfaceMesh surface_mesh_from(const TriangleMesh& mesh, const std::vector<glm::vec3>& normals) {
    SurfaceMesh s;
    s.pos = mesh.positions;
    s.tri = mesh.triangles;
    s.normal = normals;
    s.face_normal = mesh_face_normals(mesh);
    return s;
}

}  // namespace penink
