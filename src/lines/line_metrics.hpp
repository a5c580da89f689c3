// Measures of a finished layer, image pixels: its paths, its closed loops smaller than a size
// (slivers of far terrain traced as outlines, specks), and the share of its pen-down length that
// runs within a distance of another of its paths (doubled lines). What --verbose prints per layer
// and what the drawing-finish tests and docs/timings.md measure.
#pragma once
#include <cstddef>
#include <vector>

#include "core/drawing.hpp"

namespace penink {

// Pen-down length of a stroke, pixels.
double stroke_length(const Stroke& s);

// Largest side of a stroke's bounding box, pixels.
float stroke_extent(const Stroke& s);

struct LineMetrics {
    std::size_t paths = 0;
    std::size_t small_loops = 0;  // closed strokes less than loop_px across (stroke_extent)
    double length = 0.0;          // pen-down length, px
    double doubled_length = 0.0;  // of which doubled (runs within near_px of another stroke), px
    double doubled_share() const { return length > 0.0 ? doubled_length / length : 0.0; }
};

// Each stroke sampled every quarter pixel along its length; a sample is near when a sample of
// another stroke lies within near_px, and doubled when it is part of a run of near samples at
// least min_run_px long (shorter runs are crossings and junctions). O(samples) with a grid of
// near_px cells.
LineMetrics line_metrics(const std::vector<Stroke>& strokes, float loop_px = 25.0f, float near_px = 1.5f,
                         float min_run_px = 4.0f);

}  // namespace penink
