// Triangle meshes read from OBJ, PLY or OFF files (OBJ and PLY through CGAL's polygon-soup
// readers, the PLY header checked first; ASCII OFF read here; polygons are triangulated as fans
// from their first vertex) in the file's own units and frame, plus the
// per-face material of OBJ `usemtl` groups (scanned here, CGAL drops them).
// Faces of files without materials all get material 0 named "default".
#pragma once
#include <string>
#include <vector>

#include "core/triangle_mesh.hpp"

namespace penink {

// Largest magnitude of a mesh coordinate (the file's units): beyond it, squared distances and
// the camera's fit overflow floats.
constexpr double max_mesh_coordinate = 1e9;

// Reads path (.obj, .ply, .off; extension case-insensitive). Throws penink::Error("input", path,
// ...) with "no such file", "not a mesh (cannot read OBJ/PLY/OFF)", "mesh has no triangles",
// "vertex N has coordinate X, out of range (mesh coordinates must be finite and within +-1e9)" or
// "unsupported mesh format \".xyz\" (use .obj, .ply or .off)".
// weld: merge vertices with bit-identical positions (files that split vertices along seams)
// and drop triangles that become degenerate, so edges are shared between faces.
TriangleMesh read_mesh(const std::string& path, bool weld = true);

// Merges vertices with identical positions, drops triangles with a repeated vertex.
void weld_mesh(TriangleMesh& mesh);

// Per-face material names of an OBJ text, one per polygon face (`f` line) in file order;
// faces before any `usemtl` are "default". Exposed for tests.
std::vector<std::string> scan_obj_face_materials(const std::string& obj_text);

}  // namespace penink
