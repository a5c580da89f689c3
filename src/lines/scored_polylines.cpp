#include "lines/scored_polylines.hpp"

#include <algorithm>
#include <span>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "core/parallel_chunks.hpp"

namespace penink {

namespace {

// Runs handed to a core at a time (a whole view of a large DEM scores some 80 000).
constexpr std::size_t runs_per_chunk = 2048;

}  // namespace

void whole_or_nothing_by_distance(std::vector<float>& scores, const std::vector<glm::vec3>& positions,
                                  const std::vector<VertexRun>& runs, const Camera& camera,
                                  double attenuation_per_metre) {
    if (!(attenuation_per_metre > 0.0)) return;
    const auto hidden = [&](std::uint32_t i) { return scores[i] < -1e29f; };
    const auto without = [&](std::uint32_t i) {  // the score with the attenuation added back
        return double(scores[i]) + attenuation_per_metre * eye_depth(camera, glm::dvec3(positions[i]));
    };
    // the runs on all cores (each writes its own vertices' scores)
    parallel_chunks(runs.size(), runs_per_chunk, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t r = r0; r < r1; ++r) {
            const VertexRun& run = runs[r];
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
    });
}

namespace {

// The six frustum planes' signed functions at clip point c (>= 0 inside).
void plane_values(const glm::dvec4& c, double f[6]) {
    f[0] = c.w + c.x, f[1] = c.w - c.x, f[2] = c.w + c.y, f[3] = c.w - c.y, f[4] = c.w + c.z, f[5] = c.w - c.z;
}

bool in_frustum(const glm::dvec4& c) {
    double f[6];
    plane_values(c, f);
    for (double v : f)
        if (v < 0.0) return false;
    return true;
}

}  // namespace

glm::vec3 frustum_exit(const glm::vec3& inside, const glm::vec3& outside, const glm::dmat4& vp) {
    const glm::dvec4 a = vp * glm::dvec4(glm::dvec3(inside), 1.0), b = vp * glm::dvec4(glm::dvec3(outside), 1.0);
    double fa[6], fb[6];
    plane_values(a, fa);
    plane_values(b, fb);
    double t = 1.0;
    for (int k = 0; k < 6; ++k) {
        if (fa[k] < 0.0) return inside;
        if (fb[k] < 0.0) t = std::min(t, fa[k] / (fa[k] - fb[k]));
    }
    return glm::vec3(glm::dvec3(inside) + t * (glm::dvec3(outside) - glm::dvec3(inside)));
}

std::vector<glm::vec3> drawn_points(const DrawnRun& r, const std::vector<glm::vec3>& positions) {
    std::vector<glm::vec3> points;
    points.reserve(r.run.count + 2);
    if (r.has_head) points.push_back(r.head);
    points.insert(points.end(), positions.begin() + r.run.first, positions.begin() + r.run.first + r.run.count);
    if (r.has_tail) points.push_back(r.tail);
    return points;
}

std::vector<DrawnRun> drawn_runs(const std::vector<glm::vec3>& positions, const std::vector<float>& scores,
                                 std::span<const VertexRun> runs, const Camera& camera) {
    const glm::dmat4 view = view_matrix(camera), vp = view_projection(camera);
    const auto outside_view = [&](std::uint32_t i) {
        return scores[i] < -1e29f && !in_frustum(vp * glm::dvec4(glm::dvec3(positions[i]), 1.0));
    };
    std::vector<DrawnRun> out;
    for (const VertexRun& run : runs) {
        const std::uint32_t end = run.first + run.count;
        const auto close = [&](VertexRun cur) {
            if (cur.count < 2) return;
            DrawnRun d;
            d.run = cur;
            const std::uint32_t last = cur.first + cur.count - 1;
            if (cur.first > run.first && outside_view(cur.first - 1))
                d.has_head = true, d.head = frustum_exit(positions[cur.first], positions[cur.first - 1], vp);
            if (last + 1 < end && outside_view(last + 1))
                d.has_tail = true, d.tail = frustum_exit(positions[last], positions[last + 1], vp);
            out.push_back(d);
        };
        VertexRun cur{run.first, 0};
        for (std::uint32_t i = run.first; i < end; ++i) {
            const bool in_front = (view * glm::dvec4(glm::dvec3(positions[i]), 1.0)).z < 0.0;
            if (scores[i] >= 0.0f && in_front) {
                if (cur.count == 0) cur.first = i;
                ++cur.count;
                continue;
            }
            close(cur);
            cur.count = 0;
        }
        close(cur);
    }
    return out;
}

float mean_score(const std::vector<float>& scores, VertexRun run) {
    double sum = 0.0;
    for (std::uint32_t i = run.first; i < run.first + run.count; ++i) sum += scores[i];
    return run.count ? float(sum / double(run.count)) : 0.0f;
}

Stroke project_stroke(const std::vector<glm::vec3>& points, const Camera& camera, float strength,
                      const std::string& kind, const std::vector<float>& weight) {
    Stroke s;
    s.kind = kind, s.strength = strength;
    const bool weighted = weight.size() == points.size() && !points.empty();
    const PixelProjector project(camera);
    for (std::size_t i = 0; i < points.size(); ++i) {
        glm::dvec2 px;
        double depth = 0.0;
        if (!project(glm::dvec3(points[i]), px, depth)) continue;
        s.points.emplace_back(float(px.x), float(px.y));
        s.depth.push_back(float(depth));
        if (weighted) s.weight.push_back(weight[i]);
    }
    return s;
}

std::vector<float> drawn_values(const DrawnRun& r, const std::vector<float>& values) {
    std::vector<float> out;
    if (values.empty() || r.run.count == 0) return out;
    out.reserve(r.run.count + 2);
    if (r.has_head) out.push_back(values[r.run.first]);
    out.insert(out.end(), values.begin() + r.run.first, values.begin() + r.run.first + r.run.count);
    if (r.has_tail) out.push_back(values[r.run.first + r.run.count - 1]);
    return out;
}

std::vector<Stroke> scored_runs_to_strokes(const std::vector<glm::vec3>& positions,
                                           const std::vector<float>& scores,
                                           const std::vector<VertexRun>& runs, const Camera& camera,
                                           const std::string& kind, const std::vector<float>& weight) {
    // the runs on all cores, their strokes joined in run order
    return parallel_collect<Stroke>(runs.size(), runs_per_chunk, [&](std::size_t r0, std::size_t r1, std::vector<Stroke>& out) {
        for (const DrawnRun& run : drawn_runs(positions, scores, {runs.data() + r0, r1 - r0}, camera))
            out.push_back(project_stroke(drawn_points(run, positions), camera, mean_score(scores, run.run), kind,
                                         drawn_values(run, weight)));
    });
}

}  // namespace penink
