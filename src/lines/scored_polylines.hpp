// Object-space polylines clipped by score and visibility (Mower, "Concurrent Drainage Network Rendering": creases and ridges stay exact
// object-space lines, not traced pixels): each polyline is a run of vertices (world positions,
// local metres) with one score each; maximal runs of >= 2 consecutive vertices with score >= 0
// become image-space strokes (pixels, eye distance in metres; strength = mean score of the run).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/drawing.hpp"
#include "core/vertex_run.hpp"

namespace penink {

// The maximal sub-runs of >= 2 vertices with score >= 0 that lie in front of the camera.
std::vector<VertexRun> drawn_runs(const std::vector<glm::vec3>& positions, const std::vector<float>& scores,
                                  const std::vector<VertexRun>& runs, const Camera& camera);

// Mean score of a run's vertices.
float mean_score(const std::vector<float>& scores, VertexRun run);

// World points -> image stroke (pixels, eye distances); points behind the eye are skipped.
Stroke project_stroke(const std::vector<glm::vec3>& points, const Camera& camera, float strength,
                      const std::string& kind);

std::vector<Stroke> scored_runs_to_strokes(const std::vector<glm::vec3>& positions,
                                           const std::vector<float>& scores,
                                           const std::vector<VertexRun>& runs, const Camera& camera,
                                           const std::string& kind);

}  // namespace penink
