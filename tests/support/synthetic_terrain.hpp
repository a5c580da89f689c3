// Test terrains: the analytic shapes of input/analytic_terrain.hpp (closed-form heights and
// silhouettes) plus a rough DEM-like surface and nodata holes (local metres, row 0 north).
#pragma once
#include "input/analytic_terrain.hpp"

namespace penink {

// height * exp(-(x^2 + y^2) / (2 sigma^2))
HeightFunction gaussian_hill(double height, double sigma);

// A sum of Gaussian hills (120-420 m, sigma 90-700 m, centred within 1.3 km of the origin) with
// fractal roughness: 9 octaves of ripples, wavelength 1024 m down to 4 m, amplitude 1.5 % of the
// wavelength (15 m to 6 cm), in turning directions: like a real DEM, detail at every scale.
double rough_hills(double x, double y);

// Marks the nodes within `radius` of (cx, cy) as nodata.
void cut_hole(Terrain& terrain, double cx, double cy, double radius);

// A 90 x 70 DEM of 10 m cells of rough_hills (4 times as dense, a fifth as high) with two nodata
// holes, one inside and one on the north-west edge: the drainage lines' tests' DEM with nodata.
Terrain holed_hills();

// `t` georeferenced as a projected DEM of UTM zone 16 whose grid starts at (512000, 4013000) with
// cells of `cell` metres, every node's x, y affine_node_xy of that geotransform (as the DEM reader
// computes a projected DEM's, origin at (512345, 4012345)): a terrain cache then derives them, and
// keeps the node lattice, the coarse nodes and the edge columns.
Terrain on_affine_grid(Terrain t, double cell = 5.0);

}  // namespace penink
