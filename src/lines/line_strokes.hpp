// Object-space sketching of scored polylines (Potter et al., "NPR-Style 3D Line Textures", 4.3;
// Mower, "Concurrent Drainage Network Rendering": creases and ridges stay object-space lines):
// the visible runs of a scored vertex set (scored_polylines.hpp) as image strokes (pixels, eye
// distance in metres); with sketchiness each run is perturbed within the surface's tangent planes
// at its vertices (finish_drawing.hpp's sketch_object_copies, amount in pixels at the run's mean
// depth) and repeated before it is projected.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/drawing.hpp"
#include "core/vertex_run.hpp"

namespace penink {

// The style's object-space sketch of a layer (export/style.hpp's sketch and repeat).
struct ObjectSketch {
    float sketch_px = 0.0f;  // end points moved up to this far, pixels
    int repeat = 1;          // copies of each stroke
    std::uint64_t seed = 0;
};

// Visible, scored runs of `set` (scores: one per vertex, as scored_runs_to_strokes reads them)
// as image strokes of kind `kind`; with no sketch and one copy, scored_runs_to_strokes itself.
// `weight`: one per vertex of `set` (each stroke's Stroke::weight from its vertices'), or empty.
std::vector<Stroke> line_strokes(const VertexLines& set, const std::vector<float>& scores, const Camera& camera,
                                 const std::string& kind, const ObjectSketch& sketch,
                                 const std::vector<float>& weight = {});

}  // namespace penink
