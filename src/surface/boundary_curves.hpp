// The boundary of a triangle surface (edges used by one triangle: a DEM's cut edges, nodata
// holes) as chained 3D polylines that follow the PN-triangle edge curves (cubic Bezier of the
// edge's end points and normals, Vlachos 2001), sampled `samples` times per edge, so the drawn
// outline matches the rendered surface. World frame, local metres; loops repeat their first point.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "surface/surface_mesh.hpp"

namespace penink {

std::vector<std::vector<glm::vec3>> boundary_polylines(const SurfaceMesh& mesh, int samples = 4);

}  // namespace penink
