// Pen-plotter ordering of strokes (image pixels): greedy nearest-end tour starting at a home
// position; a stroke is reversed when its far end is nearer. Candidate ends come from a uniform
// spatial grid searched ring by ring, so the cost is about O(n log n) for spread-out strokes.
#pragma once
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "core/drawing.hpp"

namespace penink {

struct PlotterStats {
    std::size_t count = 0;       // strokes
    double length = 0.0;         // total pen-down length, px
    double travel_before = 0.0;  // pen-up travel of the input order, px
    double travel_after = 0.0;   // pen-up travel of the new order, px
};

// Pen-up travel: from home to the first stroke's start, then from each stroke's end to the
// next one's start (no return home).
double pen_up_travel(const std::vector<Stroke>& strokes, glm::vec2 home = {0.0f, 0.0f});
double pen_down_length(const std::vector<Stroke>& strokes);

// Reorders (and reverses, depth included) strokes in place. Ties: the lower input index, then
// the start end. Closed strokes are entered at their start. Empty strokes are moved to the end.
PlotterStats order_for_plotter(std::vector<Stroke>& strokes, glm::vec2 home = {0.0f, 0.0f});

}  // namespace penink
