// Loop subdivision (Loop 1987) of a triangle mesh through CGAL's Subdivision_method_3: each
// iteration splits every triangle in four and smooths the positions, so coarse models get the
// smooth surface and curvature that photic extremum lines need (Xie et al. 2007 used dense
// scans). Positions in the mesh's units; the mesh must be an oriented 2-manifold (with boundary).
#pragma once
#include "input/mesh_reader.hpp"

namespace penink {

// Throws penink::Error("input", mesh.source, ...) when the mesh is not manifold ("cannot subdivide:
// the mesh is not an oriented manifold") or holds several materials ("cannot subdivide a mesh with
// several materials"). iterations <= 0 leaves the mesh as it is.
void loop_subdivide(TriangleMesh& mesh, int iterations);

}  // namespace penink
