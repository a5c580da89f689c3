// Sub-pixel placement of traced silhouette points on the depth edge they mark (image pixels,
// origin top-left, y down). A Toward/Away silhouette pixel (Mower, "Fast Image-Space Silhouette
// Extraction", sec. 3.2) is an occluder pixel: its centre ray meets the near surface, and an
// 8-neighbour's centre ray passes it and meets surface farther than the nearest away-facing
// fragment a behind the pixel (or none). The silhouette crosses between those centres, on average
// on the pixel's border, while a line traced through pixel centres lies half a pixel (a diagonal
// step: 0.71 px) inside the occluder. Each point moves, from its pixel's centre offset, to that
// border: by d * 0.5 / max(|d_x|, |d_y|), d the sum of the offsets of the far neighbours (toward
// distance > a): 0.5 px across a row or column, 0.71 px diagonally. Points
// whose pixel has no far neighbour (or no toward or away fragment) stay.
#pragma once
#include <vector>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

// toward, away: the TFT/AFT eye distances (+inf where none), same size.
void place_on_depth_edges(std::vector<Stroke>& strokes, const DepthImage& toward, const DepthImage& away);

}  // namespace penink
