// Star-like clusters of short strokes thinned (image pixels): where the spacing thinning
// (spacing_thinning.hpp) leaves several short crease pieces whose ends meet near one point (the
// first-order stems radiating from a summit or a saddle, the stubs of twigs cut where they near
// their trunk), an illustrator draws one of them, not a star. Strokes are taken strongest first
// (then longest, then in order); a short stroke (under `short_px` of length) is dropped when an
// end of it lies within `radius` px of an end of a short stroke already kept that has, within
// `radius` of that end, the ends of at least two short strokes (itself among them): in each
// cluster of three or more the strongest stays. Longer strokes are neither dropped nor counted.
// Deterministic; O(strokes) with a hash grid of the short strokes' ends.
#pragma once
#include <cstddef>
#include <vector>

#include "core/drawing.hpp"

namespace penink {

// Ends of short strokes (under short_px) meeting in clusters of three or more within radius px of
// one end: the number of such clusters (each counted once, at its strongest stroke's end).
std::size_t count_star_clusters(const std::vector<Stroke>& strokes, float short_px, float radius);

// The strokes without the clustered short strokes but the strongest of each cluster (see above).
std::vector<Stroke> thin_star_clusters(std::vector<Stroke> strokes, float short_px, float radius);

}  // namespace penink
