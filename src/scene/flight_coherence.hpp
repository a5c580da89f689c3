// Frame-to-frame coherence along a flight (`penink bench --flight`): for each pair of consecutive
// frames (scene/flight_frames.hpp), the share of frame i's drawn length, per layer, that persists
// in frame i + 1: each stroke point is carried to the world by its eye distance (Stroke::depth,
// the ray through its pixel), projected into frame i + 1's camera, and the carried strokes are
// scored against frame i + 1's strokes of the same layer rasterised at 1 px
// (lines/line_accuracy.hpp: recall at `tolerance_px`). Points with unknown depth (0) or behind
// the next camera split their stroke. Layers: silhouettes and creases.
#pragma once
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/drawing.hpp"
#include "core/log.hpp"
#include "render/gl_context.hpp"
#include "scene/scene.hpp"

namespace penink {

struct CoherenceRow {
    int frame = 0;  // 1-based index of the first frame of the pair
    double silhouettes = 0, creases = 0;  // persisting share of the drawn length, 0..1
    double silhouette_px = 0, crease_px = 0;  // frame's drawn length, pixels
};

// Strokes of one frame carried into another camera's image (pixels).
std::vector<std::vector<glm::vec2>> carry_strokes(const std::vector<Stroke>& strokes, const Camera& from,
                                                  const Camera& to);

std::vector<CoherenceRow> flight_coherence(const Scene& scene, const std::string& flight_csv, GlContext& context,
                                           double tolerance_px, const Log& log);

// CSV: frame,silhouettes,creases,silhouette_px,crease_px (3 decimals), then a "mean" row weighted
// by drawn length.
std::string coherence_csv(const std::vector<CoherenceRow>& rows);

}  // namespace penink
