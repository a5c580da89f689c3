#include "cli/drainage_lines.hpp"

#include <cmath>

#include "drainage/stems.hpp"
#include "lines/polyline_smoothing.hpp"
#include "lines/spacing_thinning.hpp"
#include "surface/terrain_locator.hpp"

namespace penink {

namespace {

// Lays the polylines (vertex index lists) out contiguously, smooths them, drapes them on the PN
// surface and uploads them to a DM pass.
ScoredLineSet make_line_set(const GlApi& gl, const std::vector<DvVertex>& vertices,
                            const std::vector<std::vector<std::uint32_t>>& lines,
                            const TerrainLocator& locator, int smoothing) {
    ScoredLineSet set;
    std::vector<float> flow;
    for (const auto& line : lines) {
        set.runs.push_back({std::uint32_t(set.positions.size()), std::uint32_t(line.size())});
        for (std::uint32_t i : line) {
            set.positions.push_back({vertices[i].x, vertices[i].y, vertices[i].z});
            flow.push_back(vertices[i].flow);
        }
    }
    smooth_runs_xy(set.positions, set.runs, smoothing);
    std::vector<DmVertex> dm(set.positions.size());
    for (std::size_t i = 0; i < dm.size(); ++i) {
        glm::vec3& p = set.positions[i];
        dm[i].flow = flow[i];
        SurfaceHit hit;
        // Vertices off the rendered surface are outside the view: a zero normal keeps them hidden.
        if (locator.locate(p.x, p.y, hit)) {
            p.z = locator.pn_position_at(hit).z;  // drape the smoothed line back on the surface
            dm[i].normal = locator.pn_normal_at(hit);
        } else {
            dm[i].normal = glm::vec3(0.0f);
        }
        dm[i].position = p;
    }
    set.pass = std::make_unique<DmPass>(gl, dm);
    return set;
}

std::vector<std::vector<std::uint32_t>> polyline_indices(const std::vector<DvPolyline>& lines) {
    std::vector<std::vector<std::uint32_t>> out;
    for (const DvPolyline& l : lines) {
        out.emplace_back(l.count);
        for (std::uint32_t k = 0; k < l.count; ++k) out.back()[k] = l.first + k;
    }
    return out;
}

}  // namespace

CreaseScore crease_score(const CreaseParams& p) {
    return {float(p.slope_weight), float(p.illumination_weight), float(p.flow_weight),
            float(p.min_score), float(p.distance_attenuation)};
}

float max_visible_distance(const DepthImage& toward) {
    float d = 0.0f;
    for (float t : toward.depth)
        if (std::isfinite(t)) d = std::max(d, t);
    return d;
}

DrainageLines::DrainageLines(const GlApi& gl, const DrainageDb& db, const SurfaceMesh& mesh) {
    const TerrainLocator locator(mesh);
    creases_ = make_line_set(gl, db.vertices, drainage_stems(db), locator, 3);
    ridges_ = make_line_set(gl, db.divide_vertices, polyline_indices(db.divides), locator, 3);
}

void DrainageLines::draw(const Camera& camera, const Scene& scene, GLuint toward_texture,
                         float max_distance, Drawing& drawing, PassTimings& times) {
    DmFrame frame;
    frame.camera = &camera;
    frame.light = glm::vec3(light_vector(Light{scene.light.azimuth, scene.light.altitude}));
    frame.max_distance = max_distance;
    frame.toward_texture = toward_texture;
    std::vector<float> scores;
    if (scene.creases.enabled) {
        times.dm = creases_.pass->run(frame, crease_score(scene.creases), scores);
        drawing.layer(LayerKind::creases).strokes = thin_by_spacing(
            scored_runs_to_strokes(creases_.positions, scores, creases_.runs, camera, "crease"),
            float(scene.creases.spacing_px));
    }
    if (scene.ridges.enabled) {
        times.ridges = ridges_.pass->run(frame, crease_score(scene.ridges), scores);
        drawing.layer(LayerKind::ridges).strokes = thin_by_spacing(
            scored_runs_to_strokes(ridges_.positions, scores, ridges_.runs, camera, "ridge"),
            float(scene.ridges.spacing_px));
    }
}

}  // namespace penink
