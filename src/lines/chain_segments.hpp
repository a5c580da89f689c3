// Chaining of line pieces in image pixels (origin top-left, y down; depth = eye distance):
// object-space segments projected to the image, or already-polyline strokes, are joined end to
// end into the longest polylines. End points within `tolerance` px are merged into one node
// (greedy leader clustering on a spatial hash grid, O(n)); a node shared by >= 3 pieces (or
// by 1) ends chains there; chains are extended through every node shared by exactly 2 pieces.
#pragma once
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/drawing.hpp"

namespace penink {

struct ImageSegment {
    glm::vec2 a{0.0f}, b{0.0f};  // image pixels
    float depth_a = 0.0f, depth_b = 0.0f;
    float strength = 1.0f;
};

// Strength of a chain from its members: plain mean of the members' strengths, or their max.
enum class StrengthRule { mean, max };

struct ChainParams {
    float tolerance = 0.5f;       // px; end points closer than this are joined
    float max_turn_deg = 180.0f;  // chains also end at a node turning more than this
    StrengthRule strength = StrengthRule::mean;
    std::string kind = "feature-edge";  // Stroke::kind of chain_segments' output
    // Occlusion-aware joins, for contours whose depth is the occluding surface's (silhouettes):
    // at a node of three or more ends, the two ends whose strokes are nearest there (the median
    // depth of their first five points, within 10 % of each other; the straighter pair among
    // equally near ones) continue through it and the others end there, as an illustrator draws a
    // T-junction: the occluding contour goes on, the occluded one stops on it. A node of two ends
    // that lies on a third stroke (within `tolerance`) is such a T too and is not joined through,
    // so a sliver of far terrain between two junctions stays an open upper edge, never a loop.
    bool occlusion = false;
};

// Polylines from segments. Joint points are the mean of the merged end points (position and
// depth). Segments whose ends merge into one node are dropped, and so are repeats of a segment
// joining the same two nodes (the first one is kept). Output order: chains from end/junction
// nodes in order of first appearance of the node, each incident piece in input order, then
// closed chains (first point repeated) in input order of their first segment.
std::vector<Stroke> chain_segments(const std::vector<ImageSegment>& segments, const ChainParams& params = {});

// Joins strokes whose ends lie within `tolerance` px, keeping junctions; only strokes of the
// same kind join (groups in order of first appearance). Closed strokes pass through unchanged.
std::vector<Stroke> join_strokes(std::vector<Stroke> strokes, float tolerance);
std::vector<Stroke> join_strokes(std::vector<Stroke> strokes, const ChainParams& params);

}  // namespace penink
