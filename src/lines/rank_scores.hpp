// Crease and ridge scores under the rank normalisation of eq. 6 (Mower, "Concurrent Drainage
// Network Rendering", eq. 1-6; `[creases] normalisation = "rank"`, core/crease_params.hpp): each
// term (sc, ic, fc, each in [0, 1] as the DM pass computes them) is replaced by its percentile
// among the frame's visible vertices, and
//   rs = (sw P(sc) + iw P(ic) + fw P(fc)) / (sw + iw + fw) - rs_min(d).
// P(x) = (number of visible values below x + half the number equal to x) / visible count, in
// (0, 1); ties share one percentile (a term that is equal everywhere scores 1/2 everywhere).
// Flow normalised per basin is concentrated near 0 (on volcano half the visible drainage vertices
// have fc < .004) while the others spread over [0, 1]; ranking gives every term the same uniform
// spread, so a threshold means a share of the drawn network (docs/reproduction.md).
// Input: per vertex, the three terms and -rs_min(d), with dm_hidden (render/dm.hpp) for vertices
// not visible (the same in every array); output: per vertex rs, dm_hidden where not visible.
#pragma once
#include <array>
#include <vector>

namespace penink {

// Percentile of each visible value among the visible values (hidden: `hidden`, left as is).
std::vector<float> visible_percentiles(const std::vector<float>& values, float hidden);

// rs under the rank normalisation; weights {slope, illumination, flow}; a term whose weight is 0
// is not read (it may be empty); all weights 0 gives -rs_min (the weighted mean is then 0).
std::vector<float> rank_scores(const std::array<std::vector<float>, 3>& terms, const std::vector<float>& minus_rs_min,
                               const std::array<double, 3>& weights, float hidden);

}  // namespace penink
