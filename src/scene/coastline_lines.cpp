// The coastline layer (coastline_lines.hpp).
#include "scene/coastline_lines.hpp"

#include "lines/crease_scores.hpp"
#include "lines/scored_polylines.hpp"

namespace penink {

ScoredLineSet coastline_vertices(const std::vector<ShoreLine>& lines, std::vector<glm::vec3>& ground) {
    ScoredLineSet set;
    ground.clear();
    const glm::vec3 up(0.0f, 0.0f, 1.0f);  // the water's normal
    for (const ShoreLine& line : lines) {
        set.runs.push_back({std::uint32_t(set.positions.size()), std::uint32_t(line.points.size())});
        for (std::size_t i = 0; i < line.points.size(); ++i) {
            set.positions.push_back(line.points[i]);
            set.normals.push_back(up);
            ground.emplace_back(line.points[i].x, line.points[i].y, line.ground[i]);
        }
    }
    return set;
}

CoastlineLines::CoastlineLines(const GlApi& gl, const GridNodes& nodes, GridWindow window)
    : set_{coastline_vertices(sea_level_contour(nodes, window), ground_), nullptr} {
    if (ground_.empty()) return;
    set_.pass = std::make_unique<DmPass>(gl, DmInput{ground_, set_.lines.normals, {}});
}

void CoastlineLines::draw(const Camera& camera, GLuint toward_texture, Drawing& drawing) {
    if (!set_.pass) return;
    DmFrame frame;
    frame.camera = &camera;
    frame.toward_texture = toward_texture;
    // Visibility alone: no slope, light or flow term and rs_min = -1, so every visible vertex
    // scores 1 and every hidden one dm_hidden.
    CreaseParams visible;
    visible.slope_weight = visible.illumination_weight = visible.flow_weight = 0.0;
    visible.min_score = -1.0, visible.distance_attenuation = 0.0;
    std::vector<float> scores;
    set_.pass->run(frame, [&](std::span<const CreaseTerms> terms) { scores = crease_scores(terms, visible, 1.0f); });
    drawing.layer(LayerKind::coastline).strokes =
        scored_runs_to_strokes(set_.lines.positions, scores, set_.lines.runs, camera, "coastline");
}

}  // namespace penink
