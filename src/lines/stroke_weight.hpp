// Stroke weights: a per-point weight in [0, 1] (core/drawing.hpp Stroke::weight) that places a
// line in its layer's hierarchy of weight, which the style turns into width (styles/README.md).
//  - Creases by flow: trunk streams heavier than twigs. The drainage vertices carry normalised
//    flow f (accumulation / basin total, in [0, 1]); the measure is log10 f.
//  - Ridges by height (basin divides carry no flow): the measure is the vertex's height z on the
//    surface (exaggerated or not, the order is the same), so the main crests are heavier than
//    the low spurs, and a ridge thins as it falls from a summit.
//  - Silhouettes by the depth gap behind them (Lobeck's profile lines; Winkenbach & Salesin,
//    "Computer-generated pen-and-ink illustration": outline accents): at each point, within
//    `radius` px of it in the toward (TFT) eye-distance image, the nearest surface's distance n and
//    the farthest f (+inf where a pixel has no surface: sky); gap g = (f - n) / n, relative to the
//    edge's own distance; weight = g / (g + gap_half), 1 against the sky. A ridge against the sky
//    or a far valley is heavy; a fold against the slope just behind it is light. The weights are
//    then smoothed along the stroke (a running mean over `smooth_px` of arc length each side).
// The raw measures (log flow, height, gap weight) are then spread over the whole range by their
// rank among the layer's drawn strokes (equalise_weights): a point's weight is the share of the
// layer's drawn length whose raw measure is at most its own (the length-weighted cumulative
// distribution, histogram equalisation). The order is the measure's, so the hierarchy stays real
// (a trunk stays heavier than its twigs, a skyline heavier than a fold), but a frame whose
// creases are all twigs, whose ridges all stand at mid height or whose silhouettes all stand
// before far ridges uses the layer's full range of widths instead of a compressed corner of it.
// Ties take the top of their step: every point against the sky weighs 1.
#pragma once
#include <vector>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"
#include "core/vertex_run.hpp"

namespace penink {

// The raw measure of flow that equalise_weights ranks: log10 f (f <= 1e-12 as 1e-12).
float log_flow(float flow);
// The raw measure of height that equalise_weights ranks for ridges: one per vertex of `lines`,
// its z; a vertex off the surface (zero normal) takes the lowest z of those on it, so it ranks
// with the lowest ridge vertex (all 0 when none is on the surface).
std::vector<float> ridge_heights(const VertexLines& lines);
// Weight of a relative depth gap g >= 0 (+inf: 1).
float gap_weight(float gap, float gap_half = 0.1f);

struct DepthGapParams {
    int radius = 2;          // px: window half-size searched for the near and far surfaces
    float gap_half = 0.1f;   // relative gap that weighs 0.5
    float smooth_px = 3.0f;  // running-mean half-length along the stroke, px
};

// The relative depth gap at image point p (pixels, origin top-left, y down); +inf when some pixel
// of the window has no surface; 0 when none has one.
float depth_gap_at(const DepthImage& toward, glm::vec2 p, int radius);

// Sets every stroke's weight from the depth gap behind it (see above).
void weigh_by_depth_gap(std::vector<Stroke>& strokes, const DepthImage& toward, const DepthGapParams& params = {});

// Replaces every point's weight by its rank among all the strokes' points: the share of their
// length (each point standing for half of each segment it ends) whose weight is at most its own
// (see above). Strokes without weights are left alone; nothing changes when no point has length.
void equalise_weights(std::vector<Stroke>& strokes);

// Running mean of per-point values over `half_px` of arc length each side (in place).
void smooth_along(const std::vector<glm::vec2>& points, std::vector<float>& values, float half_px);

}  // namespace penink
