// The coastline of a DEM with water (GridNodes::sea_level): the contour of the DEM's nodes at the
// sea level, by marching triangles on the full-resolution mesh's triangles (each cell split
// NW-SE, a triangle where its three nodes hold data: conventions.md), so no cell is ambiguous
// (marching squares' saddles) and the line follows the mesh the water is drawn on. A node is
// land when its stored height is above the sea level, water at or below it; on each triangle edge
// from a water node a to a land node b the shore crosses at t = (s - z_a) / (z_b - z_a) in [0, 1),
// linear along the edge as the mesh is. Crossings are chained through the triangles into
// polylines (closed ones repeat their first point at the end; an island is a closed loop).
//
// Frames and units: the nodes' local metres (x east, y north), drawn heights: every point at
// z = the water surface (GridNodes::sea_z, sea_level times the exaggeration); `ground` holds the
// drawn mesh's height at the same plan point (the linear interpolation of the drawn, clamped
// node heights along the edge: sea_z at the water node, the land node's height at the other),
// which is where the rendered surface lies above the shore point (for depth tests).
// Work follows the window's cells; output in the order of the cells (row-major), deterministic.
#pragma once
#include <vector>

#include <glm/vec3.hpp>

#include "input/grid_nodes.hpp"
#include "input/terrain.hpp"

namespace penink {

struct ShoreLine {
    std::vector<glm::vec3> points;  // plan position, z = the water surface (drawn metres)
    std::vector<float> ground;      // drawn height of the mesh at each point (>= points[i].z)
};

// The coastline of the nodes inside `window` (clamped to the grid). Empty when the nodes have no
// sea level or no triangle crosses it.
std::vector<ShoreLine> sea_level_contour(const GridNodes& nodes, GridWindow window);

}  // namespace penink
