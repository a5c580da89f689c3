// The map furniture of a terrain's plan view (lines/map_furniture.hpp): the scene's [map]
// furniture keys read and checked, and the furniture added to a finished drawing, sized for the
// page it is written on (export/page.hpp), with the style's pens and label sizes, the map CRS's
// meridian convergence at the map's centre (input/crs_util.hpp) and, for a graticule, the
// longitude and latitude along the neatline.
#pragma once
#include <string>
#include <vector>

#include "core/drawing.hpp"
#include "export/page.hpp"
#include "export/style.hpp"
#include "lines/map_furniture.hpp"

namespace penink {

// The furniture keys of [map] (besides scale): furniture (false turns every piece off),
// neatline, scale_bar, north_arrow (true or false), grid ("none", "map", "graticule"), title (a
// string), units ("metric", "imperial"); read by the scene file's reader (scene_file.cpp).
std::vector<std::string> map_furniture_keys();

// "none", "map", "graticule"; throws std::invalid_argument otherwise.
MapGrid map_grid_named(const std::string& name);

// Adds the furniture to a plan view's drawing (it has a georeference), laid out on the page the
// drawing is written on (`page`, for the image size of the drawing; `path` names it in page
// errors), and marks the drawing as a map (its furniture layers written). `map_scale` is the
// scene's 1:N (0: none). Other views are left as they are.
void add_scene_furniture(Drawing& drawing, const MapFurnitureOptions& options, double map_scale, const Style& style,
                         const PageOptions& page, const std::string& path);

}  // namespace penink
