// Meshes for tests and benchmarks: the unit cube, and spheres centred on the origin, in the mesh's own units (the
// radius), z-up with counter-clockwise (outward-facing) triangles and every triangle of
// material 0 "default":
// - uv_sphere: longitude u = 2 pi j / n (from +x towards +y, j = 0..n) and colatitude
//   v = pi i / (n / 2) (from the +z pole, i = 0..n/2); vertex (i, j) at
//   rho(u, v) (sin v cos u, sin v sin u, cos v) with rho = radius + bump(u, v) (no bump: radius),
//   all in double and rounded to float at the end. Two layouts of the same lattice: `grid` keeps
//   the seam column j = n and one vertex per pole-row node ((n/2 + 1) (n + 1) vertices, row-major
//   by i then j; 2 triangles per cell, those touching a pole degenerate: n/2 * n * 2 triangles);
//   `closed` shares the seam and has one vertex per pole (exactly (0, 0, +-radius), no bump; a closed
//   2-manifold: north pole, rings i = 1..n/2-1 of n vertices, south pole; per column j the north
//   fan triangle, the south fan triangle, then 2 triangles per band).
// - icosphere: the icosahedron (12 vertices at (+-1, +-t, 0) and cyclic permutations, t the golden
//   ratio) subdivided `level` times by edge midpoints (new vertices appended in order of first
//   use, each triangle split into its 3 corners then the middle one), every vertex then pushed to
//   the sphere of radius r: 20 * 4^level triangles.
// - unit_cube: [0,1]^3, vertex i at (i & 1, (i >> 1) & 1, (i >> 2) & 1), faces in order -z, +z, -y,
//   +y, -x, +x, each two outward counter-clockwise triangles (2f, 2f + 1) split along a diagonal.
#pragma once
#include <cstdint>
#include <functional>

#include "core/triangle_mesh.hpp"

namespace penink::test {

TriangleMesh unit_cube();

enum class UvLayout { grid, closed };

// Radial offset added to the radius at longitude u, colatitude v (radians).
using RadialBump = std::function<double(double u, double v)>;

// n segments around (n even), n / 2 rings.
TriangleMesh uv_sphere(int n, double radius = 1.0, UvLayout layout = UvLayout::grid, const RadialBump& bump = {});

TriangleMesh icosphere(int level, float r);

// Unit normals of a mesh centred on the origin pointing away from it (a sphere's exact normals).
std::vector<glm::vec3> radial_normals(const TriangleMesh& m);

// Deterministic normal noise: each normal moved by up to `amp` per coordinate (splitmix64 of
// `seed`), renormalised.
std::vector<glm::vec3> noisy_normals(std::vector<glm::vec3> n, float amp, std::uint64_t seed);

}  // namespace penink::test
