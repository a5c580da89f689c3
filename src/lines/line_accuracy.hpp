// Accuracy of drawn lines against reference lines, both in image pixels (origin top-left, y
// down; pixel (x, y) covers [x, x+1] x [y, y+1], its centre (x + 0.5, y + 0.5)). Drawn lines are
// a PixelMask (or strokes rasterised at 1 px); references are polylines. For each tolerance tau:
// precision = share of drawn pixels whose centre lies within tau of a reference polyline;
// recall = share of the reference length lying within tau of a drawn pixel centre (sampled every
// <= 0.1 px, length-weighted). Mean distances: drawn pixel centre -> nearest reference segment
// (exact), reference point -> nearest drawn pixel centre (length-weighted). Conventions for empty
// inputs: no drawn pixels -> precision 1; no reference -> recall 1; a mean over nothing is 0 and
// a distance to nothing is +inf.
#pragma once
#include <vector>

#include <glm/vec2.hpp>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"

namespace penink {

using ImagePolyline = std::vector<glm::vec2>;

struct ToleranceScore {
    double tolerance = 0, precision = 0, recall = 0;
};

struct LineAccuracy {
    std::vector<ToleranceScore> scores;  // one per requested tolerance, same order
    double mean_drawn_to_reference = 0;  // pixels
    double mean_reference_to_drawn = 0;  // pixels
    std::size_t drawn_pixels = 0;
    double reference_length = 0;         // pixels
    // Score at a requested tolerance; throws penink::Error("lines") when it was not requested.
    const ToleranceScore& at(double tolerance) const;
};

LineAccuracy line_accuracy(const PixelMask& drawn, const std::vector<ImagePolyline>& reference,
                           const std::vector<double>& tolerances = {1.0, 2.0});

// Marks every pixel a polyline passes through (sampled every 0.1 px): a 1-px-wide raster.
PixelMask rasterize_polylines(const std::vector<ImagePolyline>& lines, int width, int height);
PixelMask rasterize_strokes(const std::vector<Stroke>& strokes, int width, int height);

}  // namespace penink
