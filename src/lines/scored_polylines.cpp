#include "lines/scored_polylines.hpp"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

namespace penink {

void whole_or_nothing_by_distance(std::vector<float>& scores, const std::vector<glm::vec3>& positions,
                                  const std::vector<VertexRun>& runs, const Camera& camera,
                                  double attenuation_per_metre) {
    if (!(attenuation_per_metre > 0.0)) return;
    const auto hidden = [&](std::uint32_t i) { return scores[i] < -1e29f; };
    const auto without = [&](std::uint32_t i) {  // the score with the attenuation added back
        return double(scores[i]) + attenuation_per_metre * eye_depth(camera, glm::dvec3(positions[i]));
    };
    for (const VertexRun& run : runs) {
        const std::uint32_t end = run.first + run.count;
        bool cut = false;
        for (std::uint32_t i = run.first; i < end && !cut; ++i) cut = !hidden(i) && scores[i] < 0.0f && without(i) >= 0.0;
        if (!cut) continue;
        double with_len = 0.0, without_len = 0.0;
        for (std::uint32_t i = run.first + 1; i < end; ++i) {
            if (hidden(i) || hidden(i - 1)) continue;
            const double len = glm::length(glm::dvec3(positions[i]) - glm::dvec3(positions[i - 1]));
            if (without(i) >= 0.0 && without(i - 1) >= 0.0) without_len += len;
            if (scores[i] >= 0.0f && scores[i - 1] >= 0.0f) with_len += len;
        }
        const bool whole = with_len >= 0.5 * without_len;
        for (std::uint32_t i = run.first; i < end; ++i) {
            if (hidden(i) || without(i) < 0.0) continue;
            if (whole && scores[i] < 0.0f) scores[i] = 0.0f;
            if (!whole) scores[i] = -1.0f;
        }
    }
}

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
