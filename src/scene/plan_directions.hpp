// The direction measures of a plan view's creases and ridges (lines/stroke_directions.hpp), what
// `penink render --verbose` prints for a map: the strokes taken from image pixels to the Terrain's
// local metres through the drawing's georeference (map_point, less the Terrain's origin) and
// measured against the fall line of the DEM read again, unexaggerated.
#pragma once
#include <string>
#include <vector>

#include "core/drawing.hpp"
#include "lines/stroke_directions.hpp"

namespace penink {

struct LayerDirections {
    LayerKind kind = LayerKind::creases;
    StrokeDirections directions;
};

// Nothing when the drawing has no georeference (not a plan view) or no crease or ridge strokes.
std::vector<LayerDirections> plan_view_directions(const Drawing& drawing, const std::string& dem_path);

}  // namespace penink
