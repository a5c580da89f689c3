// Elevation of a terrain grid under a plan point, found on the grid itself (no mesh of the DEM):
// the flat full-resolution triangles of surface_mesh.hpp (each cell split along its NW-SE
// diagonal, a triangle present when its three nodes hold data), interpolated linearly. The cell
// under (x, y) is found by walking from the cell the grid's corner nodes predict (exact in one
// step on an affine grid; a few steps on the curvilinear grid of a projected geographic DEM),
// at most cols + rows steps. Frames: the Terrain's local metres (x east, y north), z as stored
// in Terrain::pos (exaggerated). The cell is found as grid_cell.hpp finds it.
#pragma once
#include "input/grid_nodes.hpp"
#include "input/terrain.hpp"

namespace penink {

// False when (x, y) lies outside the grid or in a triangle without data.
bool grid_ground_height(const Terrain& terrain, double x, double y, double& z);
// The same on nodes wherever they are stored (z as GridNodes::at draws it).
bool grid_ground_height(const GridNodes& nodes, double x, double y, double& z);

}  // namespace penink
