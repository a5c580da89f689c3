// Visible part of a Terrain for a camera: the smallest node window [c0,c1) x [r0,r1) holding
// every valid node inside the view frustum of a world->clip matrix (OpenGL clip space, local
// terrain metres), plus every cell that may cross the view, grown by a margin in nodes.
// "Model no more than a scene needs": the renderer crops the terrain to it (crop_terrain).
#pragma once
#include <glm/mat4x4.hpp>

#include "input/terrain.hpp"

namespace penink {

// Empty window (cols() == 0) when nothing is visible. A cell (2x2 nodes, drawn as triangles of
// valid nodes) is kept unless all its valid corners lie outside the same frustum plane; a cell
// only partly inside also keeps the ring of cells around it. margin_nodes >= 0 widens the result.
GridWindow visible_window(const Terrain& terrain, const glm::dmat4& view_projection, int margin_nodes);

}  // namespace penink
