#include "lines/object_silhouettes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

namespace penink {

namespace {

constexpr int tile_px = 8;

// Triangles binned by the image tiles their projected bounding boxes touch; triangles with a
// vertex behind the eye go to every query.
class TriangleTiles {
public:
    TriangleTiles(const std::vector<glm::vec3>& pos, const std::vector<glm::uvec3>& tri, const Camera& cam)
        : nx_((cam.width + tile_px - 1) / tile_px), ny_((cam.height + tile_px - 1) / tile_px),
          tiles_(std::size_t(nx_) * ny_) {
        const glm::dmat4 view = view_matrix(cam), proj = projection_matrix(cam);
        std::vector<glm::dvec2> px(pos.size());
        std::vector<std::uint8_t> behind(pos.size());
        for (std::size_t i = 0; i < pos.size(); ++i) {
            const glm::dvec4 e = view * glm::dvec4(glm::dvec3(pos[i]), 1.0);
            behind[i] = e.z >= -1e-9;
            const glm::dvec4 c = proj * e;
            if (!behind[i]) px[i] = {(c.x / c.w * 0.5 + 0.5) * cam.width, (0.5 - c.y / c.w * 0.5) * cam.height};
        }
        for (std::uint32_t t = 0; t < tri.size(); ++t) {
            const glm::uvec3 v = tri[t];
            if (behind[v.x] || behind[v.y] || behind[v.z]) { everywhere_.push_back(t); continue; }
            const glm::dvec2 lo = glm::min(px[v.x], glm::min(px[v.y], px[v.z]));
            const glm::dvec2 hi = glm::max(px[v.x], glm::max(px[v.y], px[v.z]));
            if (hi.x < 0 || hi.y < 0 || lo.x > cam.width || lo.y > cam.height) continue;
            const int x0 = std::clamp(int(std::floor(lo.x)) / tile_px, 0, nx_ - 1);
            const int x1 = std::clamp(int(std::floor(hi.x)) / tile_px, 0, nx_ - 1);
            const int y0 = std::clamp(int(std::floor(lo.y)) / tile_px, 0, ny_ - 1);
            const int y1 = std::clamp(int(std::floor(hi.y)) / tile_px, 0, ny_ - 1);
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) tiles_[std::size_t(y) * nx_ + x].push_back(t);
        }
    }
    template <typename F>
    void for_each(glm::dvec2 q, F&& f) const {
        const int x = std::clamp(int(std::floor(q.x)) / tile_px, 0, nx_ - 1);
        const int y = std::clamp(int(std::floor(q.y)) / tile_px, 0, ny_ - 1);
        for (std::uint32_t t : tiles_[std::size_t(y) * nx_ + x]) f(t);
        for (std::uint32_t t : everywhere_) f(t);
    }

private:
    int nx_, ny_;
    std::vector<std::vector<std::uint32_t>> tiles_;
    std::vector<std::uint32_t> everywhere_;
};

// Moller-Trumbore: ray parameter t of o + t d hitting the triangle, or -1.
double ray_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a,
                    const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-300) return -1.0;
    const double inv = 1.0 / det;
    const glm::dvec3 s = o - a;
    const double u = glm::dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) return -1.0;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) return -1.0;
    return glm::dot(e2, q) * inv;
}

struct EdgeFaces {
    std::uint32_t f0 = ~0u, f1 = ~0u;
    int count = 0;
};

std::unordered_map<std::uint64_t, EdgeFaces> edge_faces(const std::vector<glm::uvec3>& tri) {
    std::unordered_map<std::uint64_t, EdgeFaces> edges;
    edges.reserve(tri.size() * 2);
    for (std::uint32_t t = 0; t < tri.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = tri[t][k], b = tri[t][(k + 1) % 3];
            EdgeFaces& e = edges[std::uint64_t(std::min(a, b)) << 32 | std::max(a, b)];
            (e.count++ == 0 ? e.f0 : e.f1) = t;
        }
    return edges;
}

struct Sample {
    glm::dvec2 px;
    float depth;
    bool visible, behind;
};

}  // namespace

ObjectSilhouettes object_space_silhouettes(const std::vector<glm::vec3>& pos,
                                           const std::vector<glm::uvec3>& tri, const Camera& cam,
                                           const ObjectSilhouetteOptions& options) {
    ObjectSilhouettes out;
    const glm::dvec3 eye = cam.eye;
    std::vector<std::uint8_t> toward(tri.size());
    for (std::size_t t = 0; t < tri.size(); ++t) {
        const glm::dvec3 a(pos[tri[t].x]), b(pos[tri[t].y]), c(pos[tri[t].z]);
        toward[t] = glm::dot(glm::cross(b - a, c - a), toward_viewer(cam, a)) > 0.0;
    }
    const TriangleTiles tiles(pos, tri, cam);
    const auto classify = [&](const glm::dvec3& p, const EdgeFaces& ef, Sample& s) {
        double depth = 0;
        s.visible = s.behind = false;
        if (!project_to_pixel(cam, p, s.px, depth) || s.px.x < 0 || s.px.y < 0 || s.px.x > cam.width ||
            s.px.y > cam.height) return;
        s.depth = float(depth);
        s.visible = true;
        // The ray from the viewer to p (orthographic: from the eye plane along the view direction).
        const glm::dvec3 d = is_orthographic(cam) ? direction_from_angles(cam.azimuth, cam.altitude) * depth : p - eye;
        const glm::dvec3 o = p - d;
        tiles.for_each(s.px, [&](std::uint32_t t) {
            if (t == ef.f0 || t == ef.f1 || !s.visible) return;
            const double h = ray_triangle(o, d, glm::dvec3(pos[tri[t].x]), glm::dvec3(pos[tri[t].y]), glm::dvec3(pos[tri[t].z]));
            if (h > 1e-9 && h < 1.0 - 1e-7) s.visible = false;
            else if (h > 1.0 + 1e-7) s.behind = true;
        });
    };
    for (const auto& [key, ef] : edge_faces(tri)) {
        if (ef.count != 2 || toward[ef.f0] == toward[ef.f1]) continue;
        ++out.silhouette_edges;
        const glm::dvec3 a(pos[key >> 32]), b(pos[key & 0xffffffffu]);
        glm::dvec2 pa, pb;
        double da, db;
        if (!project_to_pixel(cam, a, pa, da) || !project_to_pixel(cam, b, pb, db)) continue;
        const int n = std::max(1, int(std::ceil(glm::length(pb - pa) / options.step_px)));
        SilhouetteRun run;
        for (int k = 0; k <= n + 1; ++k) {
            Sample s{};
            if (k <= n) classify(a + (b - a) * ((k + 0.5) / (n + 1)), ef, s);
            const bool extend = s.visible && (run.points.empty() || s.behind == run.surface_behind);
            if (extend) {
                if (run.points.empty()) run.surface_behind = s.behind;
                run.points.push_back(glm::vec2(s.px)), run.depth.push_back(s.depth);
                continue;
            }
            if (!run.points.empty()) out.runs.push_back(std::move(run));
            run = SilhouetteRun{};
            if (s.visible) run.surface_behind = s.behind, run.points = {glm::vec2(s.px)}, run.depth = {s.depth};
        }
    }
    // Deterministic order (the edge map's iteration order is not).
    std::sort(out.runs.begin(), out.runs.end(), [](const SilhouetteRun& x, const SilhouetteRun& y) {
        const glm::vec2 a = x.points.front(), b = y.points.front();
        return a.y != b.y ? a.y < b.y : a.x != b.x ? a.x < b.x : x.points.size() < y.points.size();
    });
    return out;
}

std::vector<ImagePolyline> silhouette_polylines(const ObjectSilhouettes& s, bool only_surface_behind) {
    std::vector<ImagePolyline> out;
    for (const SilhouetteRun& r : s.runs)
        if (!only_surface_behind || r.surface_behind) out.push_back(r.points);
    return out;
}

}  // namespace penink
