// Surface outline: binary coverage mask (image frame, origin top-left, y down) -> closed rings
// along pixel edges (marching squares on pixel corners, points at integer corner coordinates),
// then simplified (collinear removal + Douglas-Peucker). Rings are oriented: outer boundaries
// have positive shoelace area in the y-down image frame (clockwise on screen), holes negative;
// the set is even-odd compatible. Diagonal-only contacts keep pixels apart (4-connected cover).
#pragma once
#include <vector>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

// Rings of the mask, in scan order of their top-left corner; no point is repeated at the end
// (penink::Ring is implicitly closed). tolerance <= 0: exact pixel-edge rings (corners only).
// Throws penink::Error on a malformed mask.
std::vector<Ring> trace_mask_outline(const PixelMask& mask, float tolerance = 0.7f);

}  // namespace penink
