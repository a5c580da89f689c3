#include "input/geographic_nodes.hpp"

#include <vector>

#include "core/parallel_chunks.hpp"

namespace penink {

glm::dvec2 geographic_node_lonlat(const GeographicNodes& g, int c, int r) {
    const glm::dvec2 p = affine_node_world(g.gt, g.unit, c, r);
    return {p.x + g.meridian, p.y};
}

UtmRowProjector geographic_projector(const GeographicNodes& g) {
    return UtmRowProjector(g.cols, g.rows, [g](int c, int r) { return geographic_node_lonlat(g, c, r); }, g.zone, g.north);
}

bool terrain_geographic(const Terrain& t, GeographicNodes& out) {
    if (!t.source_geographic || t.utm_zone <= 0 || t.source_col0 != 0 || t.source_row0 != 0) return false;
    out = {t.geotransform, t.angular_unit, t.prime_meridian, t.cols, t.rows, t.utm_zone, t.north};
    return true;
}

void GeographicNodeXY::span(int r, int c0, int c1, int every, glm::vec2* out) const {
    if (c0 >= c1) return;
    thread_local std::vector<glm::dvec2> world;
    world.resize(std::size_t((c1 - c0 + every - 1) / every));
    rows_.row_span(r, c0, c1, every, world.data());
    for (std::size_t j = 0; j < world.size(); ++j) out[j] = local_xy(world[j], origin_);
}

NodeXYRows::NodeXYRows(std::shared_ptr<const GeographicNodeXY> xy, int rows)
    : xy_(std::move(xy)), rows_(&xy_->projector()), origin_(xy_->origin()), n_(rows_->sample_count()) {
    samples_.resize(n_ * std::size_t(std::max(rows, 0)));
    parallel_chunks(std::size_t(std::max(rows, 0)), 64, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t r = r0; r < r1; ++r) xy_->projector().row_samples(int(r), samples_.data() + r * n_);
    });
}


}  // namespace penink
