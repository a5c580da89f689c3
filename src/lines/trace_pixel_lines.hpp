// Silhouette/line tracing: a mask of 1-2 px wide line pixels (image frame, origin top-left,
// y down) -> polylines through pixel centres (x+0.5, y+0.5) with per-point eye depth sampled
// from a DepthImage. Thinning per thin_mask.hpp (Zhang-Suen + connectivity check), then chains
// split at junctions, then closed loops; junction clusters end their chains at the cluster centre.
#pragma once
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

struct TraceParams {
    int min_pixels = 3;          // chains covering fewer skeleton pixels are dropped
    int max_spur = 0;            // prune end-point-to-junction branches of <= this many pixels
    bool thin = true;            // false: the mask already is a one-pixel 8-connected skeleton
    std::string kind = "silhouette";  // Stroke::kind of the result
    float strength = 1.0f;       // Stroke::strength of the result
    // > 0: a point's depth is the nearest valid depth within this many pixels (the occluding
    // surface's, for contours: the skeleton may run on either side of a depth step); 0: its own
    // pixel's (sample_depth).
    int depth_radius = 0;
};

// One traced chain before depth sampling: points in image pixels; pixel[i] is the skeleton
// pixel (x, y) whose depth belongs to points[i]; closed chains repeat their first point.
struct PixelChain {
    std::vector<glm::vec2> points;
    std::vector<glm::ivec2> pixel;
    int pixel_count = 0;  // skeleton pixels covered (junction pixels included)
    bool closed = false;
};

// Chains of a one-pixel skeleton: walks start at end points (1 neighbour) and junction pixels
// (>= 3 neighbours) in scan order, run pixel to pixel and stop at the next end point or
// junction (where the junction cluster's centre is appended); then the remaining closed loops,
// each started at its first pixel in scan order. Every non-junction pixel is used once.
std::vector<PixelChain> chain_skeleton(const PixelMask& skeleton, int min_pixels);

// Full pipeline: thin (unless params.thin is false), prune spurs, chain, sample depth.
// Depth: sample_depth at each point's pixel (or the nearest within params.depth_radius); points with no valid depth within 3x3 take the
// depth of the nearest point along the chain that has one; chains with none at all (or an
// empty DepthImage) get depth 0 ("unknown"). Throws penink::Error when the depth image is
// non-empty and its size differs from the mask's.
std::vector<Stroke> trace_pixel_lines(const PixelMask& mask, const DepthImage& depth,
                                      const TraceParams& params = {});

}  // namespace penink
