#include "lines/scored_polylines.hpp"

#include <glm/vec4.hpp>

namespace penink {

std::vector<VertexRun> drawn_runs(const std::vector<glm::vec3>& positions, const std::vector<float>& scores,
                                  const std::vector<VertexRun>& runs, const Camera& camera) {
    const glm::dmat4 view = view_matrix(camera);
    std::vector<VertexRun> out;
    for (const VertexRun& run : runs) {
        VertexRun cur{run.first, 0};
        for (std::uint32_t i = run.first; i < run.first + run.count; ++i) {
            const bool in_front = (view * glm::dvec4(glm::dvec3(positions[i]), 1.0)).z < 0.0;
            if (scores[i] >= 0.0f && in_front) {
                if (cur.count == 0) cur.first = i;
                ++cur.count;
                continue;
            }
            if (cur.count >= 2) out.push_back(cur);
            cur.count = 0;
        }
        if (cur.count >= 2) out.push_back(cur);
    }
    return out;
}

float mean_score(const std::vector<float>& scores, VertexRun run) {
    double sum = 0.0;
    for (std::uint32_t i = run.first; i < run.first + run.count; ++i) sum += scores[i];
    return run.count ? float(sum / double(run.count)) : 0.0f;
}

Stroke project_stroke(const std::vector<glm::vec3>& points, const Camera& camera, float strength,
                      const std::string& kind) {
    Stroke s;
    s.kind = kind, s.strength = strength;
    for (const glm::vec3& p : points) {
        glm::dvec2 px;
        double depth = 0.0;
        if (!project_to_pixel(camera, glm::dvec3(p), px, depth)) continue;
        s.points.emplace_back(float(px.x), float(px.y));
        s.depth.push_back(float(depth));
    }
    return s;
}

std::vector<Stroke> scored_runs_to_strokes(const std::vector<glm::vec3>& positions,
                                           const std::vector<float>& scores,
                                           const std::vector<VertexRun>& runs, const Camera& camera,
                                           const std::string& kind) {
    std::vector<Stroke> out;
    for (const VertexRun& run : drawn_runs(positions, scores, runs, camera)) {
        const std::vector<glm::vec3> points(positions.begin() + run.first, positions.begin() + run.first + run.count);
        out.push_back(project_stroke(points, camera, mean_score(scores, run), kind));
    }
    return out;
}

}  // namespace penink
