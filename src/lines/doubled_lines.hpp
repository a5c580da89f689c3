// Doubled lines merged, image pixels: two strokes drawn along one feature (a contour traced twice,
// a thin sliver's upper edge over the nearer contour, a crease along a silhouette) become one. The
// strokes are taken strongest first (then longest, then in order); a stretch of a later stroke
// that runs within `width` px of an earlier one for at least `min_run` px is cut out of it (gaps
// shorter than 2 widths between such stretches count as within: a line zigzagging about another),
// so the stronger line stays whole and the weaker one stops where they part. Crossings and
// junctions, which come that close over a pixel or two, are left alone. Strokes are sampled every
// 0.25 px, as line_metrics measures them. Deterministic.
#pragma once
#include <vector>

#include "core/drawing.hpp"

namespace penink {

// `above`: strokes taken before all of `strokes` and never cut (another layer's, e.g. the
// silhouettes a crease yields to). Returns the strokes in their order, each replaced by the pieces
// left of it (none when all of it ran beside others).
std::vector<Stroke> merge_doubled(std::vector<Stroke> strokes, float width, float min_run,
                                  const std::vector<Stroke>& above = {});

}  // namespace penink
