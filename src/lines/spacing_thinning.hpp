// Even line density in the image (after Jobard & Lefer 1997, "Creating evenly-spaced
// streamlines"): strokes are taken strongest first; a point closer than `spacing` pixels to a
// point of an already accepted stroke is dropped, splitting the stroke there, so hachure-like
// creases never merge into grey blots. Image pixels in and out; deterministic (ties by index).
#pragma once
#include <vector>

#include "core/drawing.hpp"

namespace penink {

// Pieces shorter than `min_length` pixels after splitting are dropped (default: 3 spacings, so no
// specks remain). spacing <= 0 returns the input.
std::vector<Stroke> thin_by_spacing(const std::vector<Stroke>& strokes, float spacing, float min_length = -1.0f);

}  // namespace penink
