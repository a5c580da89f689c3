// A map scale on the physical page: `[map] scale` N (1:N) and the page set by --page, --dpi and
// --margin (export/page.hpp) fix the image size and the ground the image spans. With a named
// page the image fills the printable area (the page less its margins; landscape when the scene's
// image is wider than tall) at the page's dpi; without one the scene's image size is kept and a
// pixel is 25.4 / dpi mm. Either way the orthographic view then spans
//     view_width = width_px * (mm per image pixel, page_layout) / 1000 * N   metres,
// so one millimetre on paper is N millimetres on the ground (in the DEM's projected CRS, whose
// scale distortion is not corrected).
#pragma once
#include <string>

#include "export/page.hpp"
#include "scene/scene.hpp"

namespace penink {

// Sets the scene's image size (with a named page) and camera.view_width from its map scale;
// nothing when the scene has no map scale. Throws penink::Error("scene") when the scale and page
// ask for an image over max_image_side pixels a side, and export's page errors.
void apply_map_scale(Scene& scene, const PageOptions& page);

// A map scale "1:N" (or "N"), 1 <= N <= 1e9: the N; throws std::invalid_argument otherwise.
double parse_map_scale(const std::string& text);

// "25000", "12500.5": N of a 1:N scale as the metadata writes it.
std::string map_scale_text(double scale);

}  // namespace penink
