#include "core/georeference.hpp"

#include <cmath>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace penink {

bool is_plan_view(const Camera& cam) { return is_orthographic(cam) && std::abs(cam.altitude + 90.0) < 1e-6; }

std::optional<Georeference> plan_view_georeference(const Camera& cam, glm::dvec2 origin, const std::string& crs_wkt) {
    if (!is_plan_view(cam) || cam.width <= 0 || cam.height <= 0) return std::nullopt;
    // Image right and up in the world are the inverse view matrix's first two columns; the
    // image centre (W/2, H/2) is the eye's plan position.
    const glm::dmat4 inv = glm::inverse(view_matrix(cam));
    const glm::dvec3 right(inv[0]), up(inv[1]);
    const double s = cam.view_width / double(cam.width);  // metres a pixel
    const double w2 = 0.5 * cam.width, h2 = 0.5 * cam.height;
    Georeference g;
    g.crs_wkt = crs_wkt;
    g.geotransform = {origin.x + cam.eye.x - right.x * s * w2 + up.x * s * h2, right.x * s, -up.x * s,
                      origin.y + cam.eye.y - right.y * s * w2 + up.y * s * h2, right.y * s, -up.y * s};
    return g;
}

glm::dvec2 map_point(const Georeference& g, double col, double row) {
    const auto& t = g.geotransform;
    return {t[0] + col * t[1] + row * t[2], t[3] + col * t[4] + row * t[5]};
}

}  // namespace penink
