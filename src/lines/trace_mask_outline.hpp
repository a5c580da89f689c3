// Surface outline: binary coverage mask (image frame, origin top-left, y down) -> closed rings
// along pixel edges (marching squares on pixel corners, points at integer corner coordinates),
// then simplified (collinear removal + Douglas-Peucker). Rings are oriented: outer boundaries
// have positive shoelace area in the y-down image frame (clockwise on screen), holes negative;
// the set is even-odd compatible. Diagonal-only contacts keep pixels apart (4-connected cover).
#pragma once
#include <string>
#include <vector>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

// Rings of the mask, in scan order of their top-left corner; no point is repeated at the end
// (penink::Ring is implicitly closed). tolerance <= 0: exact pixel-edge rings (corners only).
// Throws penink::Error on a malformed mask.
std::vector<Ring> trace_mask_outline(const PixelMask& mask, float tolerance = 0.7f);

// Signed shoelace area (pixels^2) of a ring: > 0 for outer boundaries, < 0 for holes.
double signed_area(const Ring& ring);

// Rings as closed strokes (first point repeated), kind `kind`, strength 1, depth per point
// from sample_depth_at_point (0 where unknown or the depth image is empty). Only outer rings
// unless include_holes.
std::vector<Stroke> outline_strokes(const std::vector<Ring>& rings, const DepthImage& depth,
                                    bool include_holes = false, const std::string& kind = "outline");

}  // namespace penink
