#include "scene/map_scale.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"

namespace penink {

void apply_map_scale(Scene& scene, const PageOptions& page) {
    if (!(scene.view.map_scale > 0.0)) return;
    const std::string& file = scene.source.file.empty() ? scene.source.dem : scene.source.file;
    SceneCamera& cam = scene.view.camera;
    if (!page.page.empty()) {
        double w_mm = 0.0, h_mm = 0.0;
        try {
            page_size_mm(page.page, w_mm, h_mm);
        } catch (const std::invalid_argument& e) {
            throw Error("export", file, e.what());
        }
        // page_layout's orientation: a named page turns landscape for a wide image, "WxHmm" is as given
        const bool custom = page.page.find_first_of("xX") != std::string::npos;
        if (!custom && (cam.width > cam.height) != (w_mm > h_mm)) std::swap(w_mm, h_mm);
        const double pw = w_mm - 2.0 * page.margin_mm, ph = h_mm - 2.0 * page.margin_mm;
        if (!(pw > 0.0 && ph > 0.0)) throw Error("export", file, "margin leaves no room on the page");
        const double w = std::round(pw / 25.4 * page.dpi), h = std::round(ph / 25.4 * page.dpi);
        if (w < 1.0 || h < 1.0 || w > max_image_side || h > max_image_side)
            throw Error("scene", file, "the map's page at " + format_number(page.dpi, 1) + " dpi is " + format_number(w, 0) + "x" +
                                           format_number(h, 0) + " pixels (1 to " + std::to_string(max_image_side) +
                                           " a side): lower --dpi");
        cam.width = int(w), cam.height = int(h);
    }
    const PageLayout layout = page_layout(cam.width, cam.height, page, file);
    cam.view_width = double(cam.width) * layout.scale_mm / 1000.0 * scene.view.map_scale;
    // A map wider than the Earth has no place in any CRS (GDAL's "point outside of projection
    // domain"): refused here with the scale that fits.
    constexpr double earth_circumference_m = 40075017.0;
    const double across = std::max(cam.view_width, cam.view_width * cam.height / std::max(cam.width, 1));
    if (!(across <= earth_circumference_m))
        throw Error("scene", file, "--scale 1:" + map_scale_text(scene.view.map_scale) + " makes the map " +
                                       format_number(across / 1000.0, 0) + " km across, more than the Earth's " +
                                       "circumference (at most 1:" +
                                       map_scale_text(std::floor(scene.view.map_scale * earth_circumference_m / across)) + " here)");
}

double parse_map_scale(const std::string& text) {
    const std::size_t from = text.size() > 2 && text.compare(0, 2, "1:") == 0 ? 2 : 0;
    const char* b = text.data() + from;
    const char* e = text.data() + text.size();
    double v = 0.0;
    const auto [p, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || p != e || !std::isfinite(v) || v < 1.0 || v > 1e9)
        throw std::invalid_argument("not a map scale");
    return v;
}

std::string map_scale_text(double scale) {
    return format_number(scale, 3);
}

}  // namespace penink
