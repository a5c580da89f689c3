// Crease and ridge scores rs of eq. 6 (Mower, "Concurrent Drainage Network Rendering", eq. 1-6;
// conventions.md, core/crease_params.hpp) from the terms the DM pass writes per vertex (sc, ic,
// fc in [0, 1], eye distance d in metres, render/dm.hpp), under the three normalisations:
//   thirds: rs = (sw sc + iw ic + fw fc) / 3              - rs_min(d)
//   paper:  rs = (sw sc + iw ic + fw fc) / (sw + iw + fw) - rs_min(d)
//   rank:   rs = (sw P(sc) + iw P(ic) + fw P(fc)) / (sw + iw + fw) - rs_min(d)
// with rs_min(d) = min_score + distance_attenuation d / D and a divisor of 1 when every weight is 0
// (the score is then -rs_min). P(x) = (number of visible values below x + half the number equal
// to x) / visible count, in (0, 1); ties share one percentile (a term equal everywhere scores 1/2
// everywhere). Flow normalised per basin is concentrated near 0 (on volcano half the visible
// drainage vertices have fc < .004) while the others spread over [0, 1]; ranking gives every term
// the same uniform spread, so a threshold means a share of the drawn network
// (docs/reproduction.md). Output: one rs per vertex, dm_hidden where the vertex is not visible.
#pragma once
#include <span>
#include <vector>

#include "core/crease_params.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

// rs of every vertex under p; D = max_distance (metres, the frame's farthest visible surface).
// "thirds" and "paper" are computed in float in the order written above; a term whose weight is 0
// is not ranked.
std::vector<float> crease_scores(std::span<const CreaseTerms> terms, const CreaseParams& p, float max_distance);
inline std::vector<float> crease_scores(const std::vector<CreaseTerms>& terms, const CreaseParams& p, float max_distance) {
    return crease_scores(std::span<const CreaseTerms>(terms), p, max_distance);
}

// D: the largest finite eye distance of the frame's toward-facing surface, metres (0 when none).
float max_visible_distance(const DepthImage& toward);

// Percentile P of each visible value among the visible values (hidden: `hidden`, left as is).
std::vector<float> visible_percentiles(const std::vector<float>& values, float hidden);

}  // namespace penink
