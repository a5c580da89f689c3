#include "lines/scored_polylines.hpp"

namespace penink {

namespace {

void flush(Stroke& s, double score_sum, std::vector<Stroke>& out, const std::string& kind) {
    if (s.points.size() >= 2) {
        s.strength = float(score_sum / double(s.points.size()));
        s.kind = kind;
        out.push_back(std::move(s));
    }
    s = Stroke{};
}

}  // namespace

std::vector<Stroke> scored_runs_to_strokes(const std::vector<glm::vec3>& positions,
                                           const std::vector<float>& scores,
                                           const std::vector<VertexRun>& runs, const Camera& camera,
                                           const std::string& kind) {
    std::vector<Stroke> out;
    for (const VertexRun& run : runs) {
        Stroke s;
        double sum = 0.0;
        for (std::uint32_t i = run.first; i < run.first + run.count; ++i) {
            glm::dvec2 px;
            double depth = 0.0;
            if (scores[i] < 0.0f || !project_to_pixel(camera, glm::dvec3(positions[i]), px, depth)) {
                flush(s, sum, out, kind);
                sum = 0.0;
                continue;
            }
            s.points.emplace_back(float(px.x), float(px.y));
            s.depth.push_back(float(depth));
            sum += scores[i];
        }
        flush(s, sum, out, kind);
    }
    return out;
}

}  // namespace penink
