#include "cli/drainage_lines.hpp"

#include <bit>
#include <algorithm>
#include <cmath>
#include <thread>

#include <glm/common.hpp>
#include <cstdint>
#include <unordered_map>

#include "drainage/stems.hpp"
#include "lines/finish_drawing.hpp"
#include "lines/polyline_smoothing.hpp"
#include "lines/spacing_thinning.hpp"
#include "surface/terrain_locator.hpp"

namespace penink {

namespace {

std::uint64_t xy_key(const glm::vec3& p) {
    return (std::uint64_t(std::bit_cast<std::uint32_t>(p.x)) << 32) | std::bit_cast<std::uint32_t>(p.y);
}

// A line ending where another passes through (a tributary at its junction with the main stem)
// keeps its end point fixed while smoothing moves the other line's junction vertex: the end
// follows that vertex so the two stay joined. `before` holds the positions before smoothing.
void rejoin_line_ends(const std::vector<glm::vec3>& before, const std::vector<VertexRun>& runs,
                      std::vector<glm::vec3>& positions) {
    std::unordered_map<std::uint64_t, std::uint32_t> interior;
    for (const VertexRun& r : runs)
        for (std::uint32_t k = 1; k + 1 < r.count; ++k) interior.emplace(xy_key(before[r.first + k]), r.first + k);
    for (const VertexRun& r : runs) {
        if (r.count < 2) continue;
        for (const std::uint32_t end : {r.first, r.first + r.count - 1}) {
            const auto it = interior.find(xy_key(before[end]));
            if (it == interior.end()) continue;
            positions[end].x = positions[it->second].x;
            positions[end].y = positions[it->second].y;
        }
    }
}

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

// Runs f(begin, end) over [0, n) split across the hardware threads (independent items, so the
// result does not depend on the split).
template <typename F>
void parallel_ranges(std::size_t n, F&& f) {
    const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 8);
    if (n < 20000 || threads == 1) return f(0, n);
    std::vector<std::thread> pool;
    const std::size_t chunk = (n + threads - 1) / threads;
    for (std::size_t t = 1; t < threads; ++t)
        pool.emplace_back([&, t] { f(std::min(n, t * chunk), std::min(n, (t + 1) * chunk)); });
    f(0, std::min(n, chunk));
    for (std::thread& th : pool) th.join();
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
    parallel_ranges(dm.size(), [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) drape_vertex(locator, flow[i], set.positions[i], dm[i]);
    });
    set.normals.resize(dm.size());
    for (std::size_t i = 0; i < dm.size(); ++i) set.normals[i] = dm[i].normal;
    set.upload = std::move(dm);
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

// The pieces of each line inside the plan box [lo, hi] (one vertex beyond it at each cut, so
// lines run to the edge): a view cropped to part of a large DEM scores only what it models.
std::vector<std::vector<std::uint32_t>> lines_in_box(const std::vector<std::vector<std::uint32_t>>& lines,
                                                     const DvVertices& v, glm::vec2 lo, glm::vec2 hi) {
    std::vector<std::vector<std::uint32_t>> out;
    const auto inside = [&](std::uint32_t i) {
        return v[i].x >= lo.x && v[i].x <= hi.x && v[i].y >= lo.y && v[i].y <= hi.y;
    };
    for (const auto& line : lines) {
        std::size_t k = 0;
        while (k < line.size()) {
            while (k < line.size() && !inside(line[k])) ++k;
            if (k == line.size()) break;
            std::size_t end = k;
            while (end < line.size() && inside(line[end])) ++end;
            const std::size_t a = k > 0 ? k - 1 : k, b = std::min(end + 1, line.size());
            out.emplace_back(line.begin() + std::ptrdiff_t(a), line.begin() + std::ptrdiff_t(b));
            k = end;
        }
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

DrainageLineData prepare_drainage_lines(const DrainageDb& db, const SurfaceMesh& mesh) {
    const TerrainLocator locator(mesh);
    glm::vec2 lo(1e30f), hi(-1e30f);  // plan extent of the rendered surface
    for (const glm::uvec3& t : mesh.tri)
        for (int k = 0; k < 3; ++k) lo = glm::min(lo, glm::vec2(mesh.pos[t[k]])), hi = glm::max(hi, glm::vec2(mesh.pos[t[k]]));
    DrainageLineData data;
    data.creases = make_line_set(db.vertices, lines_in_box(drainage_stems(db), db.vertices, lo, hi), locator, 3);
    data.ridges = make_line_set(db.divide_vertices, lines_in_box(polyline_indices(db.divides), db.divide_vertices, lo, hi),
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
        times.dm = creases_.pass->run(frame, crease_score(scene.creases), scores);
        drawing.layer(LayerKind::creases).strokes = thin_by_spacing(
            line_strokes(creases_, scores, camera, "crease", scene.crease_sketch_px, scene.crease_repeat, scene.seed),
            float(scene.creases.spacing_px));
    }
    if (scene.ridges.enabled) {
        times.ridges = ridges_.pass->run(frame, crease_score(scene.ridges), scores);
        drawing.layer(LayerKind::ridges).strokes = thin_by_spacing(
            line_strokes(ridges_, scores, camera, "ridge", scene.ridge_sketch_px, scene.ridge_repeat, scene.seed),
            float(scene.ridges.spacing_px));
    }
}

}  // namespace penink
