#include "lines/line_strokes.hpp"

#include <algorithm>

#include "lines/finish_drawing.hpp"
#include "lines/scored_polylines.hpp"

namespace penink {

std::vector<Stroke> line_strokes(const VertexLines& set, const std::vector<float>& scores, const Camera& camera,
                                 const std::string& kind, const ObjectSketch& sketch, const std::vector<float>& weight) {
    const float sketch_px = sketch.sketch_px;
    const int repeat = sketch.repeat;
    if (sketch_px <= 0.0f && repeat <= 1)
        return scored_runs_to_strokes(set.positions, scores, set.runs, camera, kind, weight);
    std::vector<Stroke> out;
    for (const DrawnRun& run : drawn_runs(set.positions, scores, set.runs, camera)) {
        ObjectLine line;
        line.points = drawn_points(run, set.positions);
        const std::uint32_t first = run.run.first, last = run.run.first + run.run.count - 1;
        if (run.has_head) line.normals.push_back(set.normals[first]);
        for (std::uint32_t i = first; i <= last; ++i) line.normals.push_back(set.normals[i]);
        if (run.has_tail) line.normals.push_back(set.normals[last]);
        for (const glm::vec3& p : line.points) line.depth.push_back(float(eye_depth(camera, glm::dvec3(p))));
        const float strength = mean_score(scores, run.run);
        for (const ObjectLine& copy : sketch_object_copies(line, sketch_px, std::max(repeat, 1), camera, sketch.seed))
            out.push_back(project_stroke(copy.points, camera, strength, kind, drawn_values(run, weight)));
    }
    return out;
}


}  // namespace penink
