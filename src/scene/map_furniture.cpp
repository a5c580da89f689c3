#include "scene/map_furniture.hpp"

#include <stdexcept>

#include "core/error.hpp"
#include "input/crs_util.hpp"

namespace penink {

namespace {

constexpr int graticule_samples = 65;  // per side: lon/lat between them is linear within metres

}  // namespace

std::vector<std::string> map_furniture_keys() {
    return {"furniture", "neatline", "scale_bar", "north_arrow", "grid", "title", "units"};
}

MapGrid map_grid_named(const std::string& name) {
    if (name == "none") return MapGrid::none;
    if (name == "map") return MapGrid::map;
    if (name == "graticule") return MapGrid::graticule;
    throw std::invalid_argument("grid must be \"none\", \"map\" or \"graticule\" (got \"" + name + "\")");
}

void add_scene_furniture(Drawing& drawing, const MapFurnitureOptions& options, double map_scale, const Style& style,
                         const PageOptions& page, const std::string& path) {
    if (!drawing.georeference || drawing.width <= 0 || drawing.height <= 0) return;
    const Georeference& g = *drawing.georeference;
    const PageLayout layout = page_layout(drawing.width, drawing.height, page, path);
    FurnitureFrame f;
    f.width = drawing.width, f.height = drawing.height;
    f.geotransform = g.geotransform;
    f.map_unit_m = linear_unit_of(g.crs_wkt);
    f.mm_per_px = layout.scale_mm;
    f.map_scale = map_scale;
    const glm::dvec2 centre = map_point(g, 0.5 * f.width, 0.5 * f.height);
    f.convergence_deg = grid_convergence_deg(g.crs_wkt, centre).value_or(0.0);  // no CRS: grid north
    const double px_per_pen = style.widths_mm ? 1.0 / layout.scale_mm : 1.0;    // the pens' unit in pixels
    const LayerStyle& neat = style.layer(LayerKind::neatline);
    f.neatline_inset_px = neat.visible ? 0.5 * neat.width * px_per_pen : 0.0;
    const auto text_px = [&](LayerKind k) {  // points on the page -> image pixels
        const LayerStyle& l = style.layer(k);
        return l.visible ? l.font_size * (mm_per_inch / 72.0) / layout.scale_mm : 0.0;
    };
    f.grid_text_px = text_px(LayerKind::grid), f.scale_text_px = text_px(LayerKind::scale_bar);
    f.arrow_text_px = text_px(LayerKind::north_arrow), f.title_text_px = text_px(LayerKind::title);
    if (options.grid == MapGrid::graticule) {
        const double W = f.width, H = f.height;
        const glm::dvec2 corners[4] = {{0, 0}, {W, 0}, {W, H}, {0, H}};
        for (int e = 0; e < 4; ++e) {
            std::vector<glm::dvec2> points;
            for (int i = 0; i < graticule_samples; ++i) {
                const glm::dvec2 p = corners[e] + (corners[(e + 1) % 4] - corners[e]) * (double(i) / (graticule_samples - 1));
                points.push_back(map_point(g, p.x, p.y));
            }
            f.edge_lon_lat[e] = map_to_lon_lat(g.crs_wkt, points);  // empty without a CRS: no graticule
        }
    }
    add_map_furniture(drawing, f, options);
}

}  // namespace penink
