#include "lines/mesh_visibility.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

namespace penink {
namespace {

struct ProjVertex {
    glm::dvec2 px;   // pixel
    glm::dvec3 eye;  // eye-space position
    double inv_z;    // 1 / view depth (perspective-correct weights); 1 for an orthographic camera
    bool ortho;
    bool ok;
};

ProjVertex project_vertex(const glm::dmat4& view, const glm::dmat4& proj, const Camera& cam,
                          const glm::vec3& p) {
    glm::dvec4 e = view * glm::dvec4(glm::dvec3(p), 1.0);
    const bool ortho = is_orthographic(cam);
    if (-e.z <= cam.near_plane) return {{}, {}, 0.0, ortho, false};
    glm::dvec4 c = proj * e;
    glm::dvec2 px{(c.x / c.w * 0.5 + 0.5) * cam.width, (0.5 - c.y / c.w * 0.5) * cam.height};
    return {px, glm::dvec3(e), ortho ? 1.0 : 1.0 / -e.z, ortho, true};
}

double edge_fn(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

void raster_triangle(const ProjVertex v[3], DepthImage& img) {
    double area = edge_fn(v[0].px, v[1].px, v[2].px);
    if (area == 0.0) return;
    int x0 = std::max(0, int(std::floor(std::min({v[0].px.x, v[1].px.x, v[2].px.x}))));
    int x1 = std::min(img.width - 1, int(std::ceil(std::max({v[0].px.x, v[1].px.x, v[2].px.x}))));
    int y0 = std::max(0, int(std::floor(std::min({v[0].px.y, v[1].px.y, v[2].px.y}))));
    int y1 = std::min(img.height - 1, int(std::ceil(std::max({v[0].px.y, v[1].px.y, v[2].px.y}))));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            glm::dvec2 p(x + 0.5, y + 0.5);
            double b0 = edge_fn(v[1].px, v[2].px, p) / area, b1 = edge_fn(v[2].px, v[0].px, p) / area;
            double b2 = 1.0 - b0 - b1;
            if (b0 < 0.0 || b1 < 0.0 || b2 < 0.0) continue;
            double w0 = b0 * v[0].inv_z, w1 = b1 * v[1].inv_z, w2 = b2 * v[2].inv_z, s = w0 + w1 + w2;
            const glm::dvec3 e = (w0 * v[0].eye + w1 * v[1].eye + w2 * v[2].eye) / s;
            const float d = float(v[0].ortho ? -e.z : glm::length(e));  // eye_depth
            float& cell = img.depth[std::size_t(y) * img.width + x];
            cell = std::min(cell, d);
        }
}

struct Sample {
    glm::vec2 px;
    float depth;
    bool visible;
};

Sample sample_at(const DepthImage& img, const Camera& cam, const glm::vec3& p, const VisibilityOptions& o) {
    glm::dvec2 px;
    double d;
    if (!project_to_pixel(cam, glm::dvec3(p), px, d)) return {{}, 0.0f, false};
    return {glm::vec2(px), float(d), point_visible(img, cam, p, o)};
}

// Appends the visible runs of segment a->b (sample 0 only when first) to out.
void walk_segment(const glm::vec3& a, const glm::vec3& b, bool first, const DepthImage& img,
                  const Camera& cam, const VisibilityOptions& o, Stroke& cur,
                  std::vector<Stroke>& out, const Stroke& proto) {
    Sample sa = sample_at(img, cam, a, o), sb = sample_at(img, cam, b, o);
    float len = glm::length(sb.px - sa.px);
    int n = std::max(1, int(std::ceil(len / o.step_px)));
    Sample prev = sa;
    for (int k = first ? 0 : 1; k <= n; ++k) {
        Sample s = k == 0 ? sa : k == n ? sb : sample_at(img, cam, a + (b - a) * (float(k) / n), o);
        if (s.visible && cur.points.empty()) cur = proto;
        if (s.visible && (cur.points.size() < 1 || k == n || k == 0 || !prev.visible)) {
            cur.points.push_back(s.px);
            cur.depth.push_back(s.depth);
        }
        if (!s.visible && !cur.points.empty()) {
            if (prev.visible && cur.points.back() != prev.px) {
                cur.points.push_back(prev.px);
                cur.depth.push_back(prev.depth);
            }
            if (cur.points.size() >= 2) out.push_back(cur);
            cur.points.clear();
            cur.depth.clear();
        }
        prev = s;
    }
}

}  // namespace

DepthImage rasterize_depth(const TriangleMesh& mesh, const Camera& cam) {
    DepthImage img{cam.width, cam.height,
                   std::vector<float>(std::size_t(cam.width) * cam.height,
                                      std::numeric_limits<float>::infinity())};
    const glm::dmat4 view = view_matrix(cam), proj = projection_matrix(cam);
    std::vector<ProjVertex> pv(mesh.positions.size());
    for (std::size_t i = 0; i < pv.size(); ++i) pv[i] = project_vertex(view, proj, cam, mesh.positions[i]);
    for (const glm::uvec3& t : mesh.triangles) {
        const ProjVertex v[3] = {pv[t.x], pv[t.y], pv[t.z]};
        if (v[0].ok && v[1].ok && v[2].ok) raster_triangle(v, img);
    }
    return img;
}

bool point_visible(const DepthImage& img, const Camera& cam, const glm::vec3& p,
                   const VisibilityOptions& o) {
    return point_visible(img, cam, PixelProjector(cam), p, o);
}

bool point_visible(const DepthImage& img, const Camera& cam, const PixelProjector& project, const glm::vec3& p,
                   const VisibilityOptions& o) {
    glm::dvec2 px;
    double d;
    if (!project(glm::dvec3(p), px, d)) return false;
    return pixel_visible(img, cam, px, d, o);
}

bool pixel_visible(const DepthImage& img, const Camera& cam, glm::dvec2 px, double d, const VisibilityOptions& o) {
    int x = int(std::floor(px.x)), y = int(std::floor(px.y));
    if (x < 0 || y < 0 || x >= cam.width || y >= cam.height) return false;
    if (img.width <= 0 || img.height <= 0) return true;  // no depth image: everything visible
    if (x >= img.width || y >= img.height) return false;
    float far = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int xx = std::clamp(x + dx, 0, img.width - 1), yy = std::clamp(y + dy, 0, img.height - 1);
            far = std::max(far, img.depth[std::size_t(yy) * img.width + xx]);
        }
    return d <= double(far) * (1.0 + o.rel_tolerance) + o.abs_tolerance;
}

std::vector<Stroke> visible_strokes(const std::vector<ObjectPolyline>& lines, const DepthImage& img,
                                    const Camera& cam, const VisibilityOptions& options) {
    std::vector<Stroke> out;
    for (const ObjectPolyline& pl : lines) {
        Stroke proto;
        proto.kind = pl.kind;
        proto.strength = pl.strength;
        Stroke cur;
        for (std::size_t i = 1; i < pl.points.size(); ++i)
            walk_segment(pl.points[i - 1], pl.points[i], i == 1, img, cam, options, cur, out, proto);
        if (cur.points.size() >= 2) out.push_back(cur);
    }
    return out;
}

}  // namespace penink
