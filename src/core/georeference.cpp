#include "core/georeference.hpp"

#include <algorithm>
#include <charconv>
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

std::string exact_decimal(double value) {
    if (!std::isfinite(value)) return "0";
    if (value == 0.0) return "0";  // also -0
    char buf[400];  // a double in fixed notation has at most ~330 characters
    const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed);
    return std::string(buf, r.ptr);
}

std::array<double, 6> tidy_geotransform(std::array<double, 6> gt) {
    const double s = std::max({std::abs(gt[1]), std::abs(gt[2]), std::abs(gt[4]), std::abs(gt[5])});
    for (int i : {1, 2, 4, 5})
        if (std::abs(gt[i]) < 1e-12 * s) gt[i] = 0.0;
    return gt;
}

std::string geotransform_text(const Georeference& g) {
    const std::array<double, 6> gt = tidy_geotransform(g.geotransform);
    std::string s;
    for (size_t i = 0; i < gt.size(); ++i) {
        if (i) s += ' ';
        s += exact_decimal(gt[i]);
    }
    return s;
}

std::map<std::string, std::string> georeference_metadata(const Camera& cam, const std::optional<Georeference>& g) {
    if (!g) return {{"georeferenced", is_orthographic(cam) ? "no (oblique view)" : "no (perspective view)"}};
    std::map<std::string, std::string> m = {
        {"georeferenced", g->crs_wkt.empty() ? "yes (plan view, local coordinates without a CRS)" : "yes (plan view)"},
        {"geotransform", geotransform_text(*g)},
        {"geotransform_order",
         "GDAL: X = g0 + col*g1 + row*g2, Y = g3 + col*g4 + row*g5; (col, row) drawing pixel corner "
         "coordinates from the image's top-left corner, y down; X, Y in the CRS's units"}};
    if (!g->crs_wkt.empty()) m["crs"] = g->crs_wkt;
    return m;
}

}  // namespace penink
