// Object-space polylines clipped by score and visibility (Mower, "Concurrent Drainage Network Rendering": creases and ridges stay exact
// object-space lines, not traced pixels): each polyline is a run of vertices (world positions,
// local metres) with one score each; maximal runs of >= 2 consecutive vertices with score >= 0
// become image-space strokes (pixels, eye distance in metres; strength = mean score of the run).
#pragma once
#include <span>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/drawing.hpp"
#include "core/vertex_run.hpp"

namespace penink {

// A drawn piece of a line: its vertices and, where the line leaves the view next to them, the
// point where the segment to the next vertex outside crosses the view frustum's side (the image
// border, or the near or far plane), so a line drawn to the edge of the frame reaches it.
struct DrawnRun {
    VertexRun run;
    bool has_head = false, has_tail = false;
    glm::vec3 head{0.0f}, tail{0.0f};  // before the first vertex, after the last (world, local metres)
};

// The maximal sub-runs of >= 2 vertices with score >= 0 that lie in front of the camera; a run
// whose neighbouring vertex in its line is hidden (score below -1e29, the DM pass's dm_hidden) and
// lies outside the frustum gets the frustum crossing of the segment to it as head or tail.
std::vector<DrawnRun> drawn_runs(const std::vector<glm::vec3>& positions, const std::vector<float>& scores,
                                 std::span<const VertexRun> runs, const Camera& camera);

// The run's points, head and tail included.
std::vector<glm::vec3> drawn_points(const DrawnRun& run, const std::vector<glm::vec3>& positions);
// Per-vertex values (one per position, e.g. weights) of the run's points: head and tail take
// their neighbour's; empty when `values` is.
std::vector<float> drawn_values(const DrawnRun& run, const std::vector<float>& values);

// The point where segment inside -> outside leaves the view frustum of `view_projection` (clip
// coordinates: |x|, |y|, |z| <= w); `inside` itself when it is not inside, `outside` when it is.
glm::vec3 frustum_exit(const glm::vec3& inside, const glm::vec3& outside, const glm::dmat4& view_projection);

// Far creases drawn whole or not at all: the distance attenuation (scores fall by
// `attenuation_per_metre` times the depth, eye_depth) breaks a far stem into dashes where its score
// hovers about the threshold. Per run, of the length that would be drawn without the attenuation
// (segments whose two vertices score >= 0 with it added back), when at least half is drawn with
// it the run is drawn as without it (the vertices it alone dropped get score 0), else none of it
// is (those vertices get -1). Hidden vertices (score below -1e29) stay hidden. Runs the
// attenuation does not cut are left as they are.
void whole_or_nothing_by_distance(std::vector<float>& scores, const std::vector<glm::vec3>& positions,
                                  const std::vector<VertexRun>& runs, const Camera& camera,
                                  double attenuation_per_metre);

// Mean score of a run's vertices.
float mean_score(const std::vector<float>& scores, VertexRun run);

// World points -> image stroke (pixels, eye distances); points behind the eye are skipped.
// `weight`: one per point (Stroke::weight), or empty.
Stroke project_stroke(const std::vector<glm::vec3>& points, const Camera& camera, float strength,
                      const std::string& kind, const std::vector<float>& weight = {});

// `weight`: one per position (each stroke's Stroke::weight from its vertices'), or empty.
std::vector<Stroke> scored_runs_to_strokes(const std::vector<glm::vec3>& positions,
                                           const std::vector<float>& scores,
                                           const std::vector<VertexRun>& runs, const Camera& camera,
                                           const std::string& kind, const std::vector<float>& weight = {});

}  // namespace penink
