#include "scene/drainage_lines.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "core/parallel_chunks.hpp"
#include "drainage/stems.hpp"
#include "lines/finish_drawing.hpp"
#include "lines/polyline_smoothing.hpp"
#include "lines/spacing_thinning.hpp"
#include "surface/terrain_locator.hpp"

namespace penink {

namespace {

// Drapes a smoothed vertex back on the PN surface and gives it the surface normal. Vertices off
// the rendered surface are outside the view: a zero normal keeps them hidden in the DM pass.
void drape_vertex(const TerrainLocator& locator, float flow, glm::vec3& p, DmVertex& out) {
    SurfaceHit hit;
    out.flow = flow;
    out.normal = glm::vec3(0.0f);
    if (locator.locate(p.x, p.y, hit)) {
        glm::vec3 on_surface;
        locator.pn_position_normal_at(hit, on_surface, out.normal);
        p.z = on_surface.z;
    }
    out.position = p;
}

// Lays the polylines (vertex index lists) out contiguously, smooths them (line ends that meet
// another line's interior follow it) and drapes them on the PN surface, ready for a DM pass.
ScoredLineSet make_line_set(const DvVertices& vertices,
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
    const std::vector<glm::vec3> before = set.positions;
    smooth_runs_xy(set.positions, set.runs, smoothing);
    rejoin_line_ends(before, set.runs, set.positions);
    std::vector<DmVertex> dm(set.positions.size());
    parallel_chunks(dm.size(), 10000, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) drape_vertex(locator, flow[i], set.positions[i], dm[i]);
    });
    set.normals.resize(dm.size());
    for (std::size_t i = 0; i < dm.size(); ++i) set.normals[i] = dm[i].normal;
    set.upload = std::move(dm);
    return set;
}

// Visible, scored runs of a line set as image strokes; with sketchiness, each run is perturbed
// within the surface's tangent planes (and repeated) before it is projected.
std::vector<Stroke> line_strokes(const ScoredLineSet& set, const std::vector<float>& scores,
                                 const Camera& camera, const std::string& kind, float sketch_px,
                                 int repeat, std::uint64_t seed) {
    if (sketch_px <= 0.0f && repeat <= 1) return scored_runs_to_strokes(set.positions, scores, set.runs, camera, kind);
    std::vector<Stroke> out;
    for (const VertexRun& run : drawn_runs(set.positions, scores, set.runs, camera)) {
        ObjectLine line;
        for (std::uint32_t i = run.first; i < run.first + run.count; ++i) {
            line.points.push_back(set.positions[i]);
            line.normals.push_back(set.normals[i]);
            line.depth.push_back(float(glm::length(glm::dvec3(set.positions[i]) - camera.eye)));
        }
        const float strength = mean_score(scores, run);
        for (const ObjectLine& copy : sketch_object_copies(line, sketch_px, std::max(repeat, 1), float(camera.fov),
                                                           camera.width, seed))
            out.push_back(project_stroke(copy.points, camera, strength, kind));
    }
    return out;
}

}  // namespace

float max_visible_distance(const DepthImage& toward) {
    float d = 0.0f;
    for (float t : toward.depth)
        if (std::isfinite(t)) d = std::max(d, t);
    return d;
}

DrainageLineData prepare_drainage_lines(const DrainageDb& db, const SurfaceMesh& mesh) {
    const TerrainLocator locator(mesh);
    glm::vec2 lo(1e30f), hi(-1e30f);  // plan extent of the rendered surface
    for (const glm::uvec3& t : mesh.tri)
        for (int k = 0; k < 3; ++k) lo = glm::min(lo, glm::vec2(mesh.pos[t[k]])), hi = glm::max(hi, glm::vec2(mesh.pos[t[k]]));
    DrainageLineData data;
    data.creases = make_line_set(db.vertices, lines_in_box(drainage_stems(db), db.vertices, lo, hi), locator, 3);
    data.ridges = make_line_set(db.divide_vertices, lines_in_box(divide_polylines(db), db.divide_vertices, lo, hi),
                                locator, 3);
    return data;
}

DrainageLines::DrainageLines(const GlApi& gl, DrainageLineData data)
    : creases_(std::move(data.creases)), ridges_(std::move(data.ridges)) {
    for (ScoredLineSet* set : {&creases_, &ridges_}) {
        set->pass = std::make_unique<DmPass>(gl, set->upload);
        set->upload = {};
    }
}

DrainageLines::DrainageLines(const GlApi& gl, const DrainageDb& db, const SurfaceMesh& mesh)
    : DrainageLines(gl, prepare_drainage_lines(db, mesh)) {}

void DrainageLines::draw(const Camera& camera, const Scene& scene, GLuint toward_texture,
                         float max_distance, Drawing& drawing, PassTimings& times) {
    DmFrame frame;
    frame.camera = &camera;
    frame.light = glm::vec3(light_vector(Light{scene.light.azimuth, scene.light.altitude}));
    frame.max_distance = max_distance;
    frame.toward_texture = toward_texture;
    std::vector<float> scores;
    if (scene.creases.enabled) {
        times.dm = creases_.pass->run(frame, scene.creases, scores);
        drawing.layer(LayerKind::creases).strokes = thin_by_spacing(
            line_strokes(creases_, scores, camera, "crease", scene.crease_sketch_px, scene.crease_repeat, scene.seed),
            float(scene.creases.spacing_px));
    }
    if (scene.ridges.enabled) {
        times.ridges = ridges_.pass->run(frame, scene.ridges, scores);
        drawing.layer(LayerKind::ridges).strokes = thin_by_spacing(
            line_strokes(ridges_, scores, camera, "ridge", scene.ridge_sketch_px, scene.ridge_repeat, scene.seed),
            float(scene.ridges.spacing_px));
    }
}

}  // namespace penink
