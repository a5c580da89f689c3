#include "surface/terrain_locator.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "surface/pn_triangle.hpp"

namespace penink {

namespace {

struct Box { glm::dvec2 lo, hi; };

Box triangle_box(const SurfaceMesh& m, std::size_t t) {
    const glm::uvec3 v = m.tri[t];
    Box b{glm::dvec2(m.pos[v.x]), glm::dvec2(m.pos[v.x])};
    for (int k = 1; k < 3; ++k) {
        b.lo = glm::min(b.lo, glm::dvec2(m.pos[v[k]]));
        b.hi = glm::max(b.hi, glm::dvec2(m.pos[v[k]]));
    }
    return b;
}

}  // namespace

TerrainLocator::TerrainLocator(const SurfaceMesh& mesh) : mesh_(&mesh) {
    if (mesh.tri.empty()) return;
    Box all = triangle_box(mesh, 0);
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.tri.size(); ++t) {
        const Box b = triangle_box(mesh, t);
        all.lo = glm::min(all.lo, b.lo), all.hi = glm::max(all.hi, b.hi);
        area += (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y);
    }
    lo_ = all.lo;
    bin_ = std::max(std::sqrt(area / double(mesh.tri.size())) * 2.0, 1e-6);  // ~2 triangles a bin
    nx_ = std::max(1, int((all.hi.x - all.lo.x) / bin_) + 1);
    ny_ = std::max(1, int((all.hi.y - all.lo.y) / bin_) + 1);
    std::vector<std::uint32_t> count(std::size_t(nx_) * ny_ + 1, 0);
    auto for_bins = [&](std::size_t t, auto&& f) {
        const Box b = triangle_box(mesh, t);
        const int x0 = int((b.lo.x - lo_.x) / bin_), x1 = int((b.hi.x - lo_.x) / bin_);
        const int y0 = int((b.lo.y - lo_.y) / bin_), y1 = int((b.hi.y - lo_.y) / bin_);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) f(std::size_t(y) * nx_ + x);
    };
    for (std::size_t t = 0; t < mesh.tri.size(); ++t) for_bins(t, [&](std::size_t b) { ++count[b + 1]; });
    for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    start_ = count;
    items_.resize(count.back());
    for (std::size_t t = 0; t < mesh.tri.size(); ++t)
        for_bins(t, [&](std::size_t b) { items_[count[b]++] = std::uint32_t(t); });
}

bool TerrainLocator::locate(double x, double y, SurfaceHit& hit) const {
    if (items_.empty()) return false;
    const int bx = int(std::floor((x - lo_.x) / bin_)), by = int(std::floor((y - lo_.y) / bin_));
    if (bx < 0 || by < 0 || bx >= nx_ || by >= ny_) return false;
    const std::size_t b = std::size_t(by) * nx_ + bx;
    for (std::uint32_t i = start_[b]; i < start_[b + 1]; ++i) {
        const glm::uvec3 v = mesh_->tri[items_[i]];
        const glm::dvec2 p0(mesh_->pos[v.x]), p1(mesh_->pos[v.y]), p2(mesh_->pos[v.z]);
        const double det = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
        if (std::abs(det) < 1e-12) continue;
        const double u = ((x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (y - p0.y)) / det;
        const double w = ((p1.x - p0.x) * (y - p0.y) - (x - p0.x) * (p1.y - p0.y)) / det;
        constexpr double eps = 1e-7;
        if (u < -eps || w < -eps || u + w > 1.0 + eps) continue;
        hit.triangle = items_[i];
        hit.bary = glm::vec3(float(1.0 - u - w), float(u), float(w));
        return true;
    }
    return false;
}

glm::vec3 TerrainLocator::pn_position_at(const SurfaceHit& hit) const {
    const glm::uvec3 v = mesh_->tri[hit.triangle];
    const PnPatch p = pn_patch(mesh_->pos[v.x], mesh_->pos[v.y], mesh_->pos[v.z], mesh_->normal[v.x],
                               mesh_->normal[v.y], mesh_->normal[v.z]);
    return pn_position(p, hit.bary);
}

glm::vec3 TerrainLocator::pn_normal_at(const SurfaceHit& hit) const {
    const glm::uvec3 v = mesh_->tri[hit.triangle];
    const PnPatch p = pn_patch(mesh_->pos[v.x], mesh_->pos[v.y], mesh_->pos[v.z], mesh_->normal[v.x],
                               mesh_->normal[v.y], mesh_->normal[v.z]);
    return pn_normal(p, hit.bary);
}

void TerrainLocator::pn_position_normal_at(const SurfaceHit& hit, glm::vec3& position, glm::vec3& normal) const {
    const glm::uvec3 v = mesh_->tri[hit.triangle];
    const PnPatch p = pn_patch(mesh_->pos[v.x], mesh_->pos[v.y], mesh_->pos[v.z], mesh_->normal[v.x],
                               mesh_->normal[v.y], mesh_->normal[v.z]);
    position = pn_position(p, hit.bary);
    normal = pn_normal(p, hit.bary);
}

}  // namespace penink
