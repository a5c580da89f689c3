// Point location on a terrain's triangle surface: for a world point (x, y) (local metres) the
// triangle of the SurfaceMesh whose xy projection holds it, with barycentric coordinates, through
// a uniform bin grid over triangle bounding boxes (O(1) expected per query). Used to evaluate the
// PN surface (height, normal: Vlachos 2001) under drainage vertices and the camera.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "surface/surface_mesh.hpp"

namespace penink {

struct SurfaceHit {
    std::uint32_t triangle = 0;
    glm::vec3 bary{0.0f};  // weights of the triangle's vertices 0, 1, 2
};

class TerrainLocator {
public:
    explicit TerrainLocator(const SurfaceMesh& mesh);
    // False when (x, y) lies on no triangle.
    bool locate(double x, double y, SurfaceHit& hit) const;
    // PN-surface position and unit normal at a hit.
    glm::vec3 pn_position_at(const SurfaceHit& hit) const;
    glm::vec3 pn_normal_at(const SurfaceHit& hit) const;
    // Both at once (one patch set-up).
    void pn_position_normal_at(const SurfaceHit& hit, glm::vec3& position, glm::vec3& normal) const;

private:
    const SurfaceMesh* mesh_;
    glm::dvec2 lo_{0.0};
    double bin_ = 1.0;
    int nx_ = 0, ny_ = 0;
    std::vector<std::uint32_t> start_, items_;  // CSR: bin -> triangles
};

}  // namespace penink
