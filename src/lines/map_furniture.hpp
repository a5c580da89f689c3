// Map furniture of a plan view (conventions.md, "Maps and georeferencing") as strokes, paper-
// coloured panels (fill rings) and labels in the five furniture layers of a Drawing, in image
// pixels (origin top-left, y down):
// - neatline: the map's frame, the image's border moved in by half its pen;
// - scale bar: a nice round length (1, 2 or 5 x 10^n metres or kilometres; feet or miles when
//   imperial) no longer than 40 mm on the page, in divisions with labelled ticks, and the ratio
//   "1:N" under it when the page has a map scale;
// - north arrow: true north at the map's centre, i.e. grid north (the map CRS's +Y through the
//   plan view's geotransform) turned by the CRS's meridian convergence there (GeographicLib's
//   gamma: grid north's bearing clockwise from true north, so true north lies gamma
//   anticlockwise of grid north);
// - grid: ticks on the neatline, pointing in, with labels, at multiples of a nice interval of the
//   map CRS's coordinates (eastings on the top and bottom sides, northings on the left and
//   right), or of longitude and latitude (a graticule, from lon/lat sampled along the sides);
// - title: the scene's title in the top-left corner.
// Sizes are millimetres on the page (mm_per_px: export/page.hpp's scale), times a factor that
// shrinks them on maps smaller than 150 mm a side, so the furniture prints alike at any dpi.
// Text is Helvetica (core/helvetica_metrics.hpp measures it to size the panels).
#pragma once
#include <array>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/drawing.hpp"

namespace penink {

enum class MapGrid { none, map, graticule };

// The scene's [map] furniture keys (scene/map_furniture.hpp reads them).
struct MapFurnitureOptions {
    bool neatline = true, scale_bar = true, north_arrow = true;
    MapGrid grid = MapGrid::none;
    std::string title;      // "" = none
    bool imperial = false;  // the scale bar in feet and miles
};

// Where the map lies and how big things are on its page.
struct FurnitureFrame {
    int width = 0, height = 0;                         // image pixels
    std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};  // pixel corner -> map CRS (core/georeference.hpp)
    double map_unit_m = 1.0;                           // metres per map CRS unit
    double mm_per_px = 25.4 / 96.0;                    // on the page
    double convergence_deg = 0.0;                      // at the map's centre (GeographicLib's gamma)
    double map_scale = 0.0;                            // N of the page's 1:N, 0: none
    double neatline_inset_px = 0.0;                    // half the neatline's pen
    // Label sizes (the em) in pixels at full size; 0: that layer draws no text.
    double grid_text_px = 0.0, scale_text_px = 0.0, arrow_text_px = 0.0, title_text_px = 0.0;
    // For a graticule: (longitude, latitude) in degrees at evenly spaced points (at least 2, the
    // ends included) along each side of the image, clockwise: top (0,0)->(W,0), right
    // (W,0)->(W,H), bottom (W,H)->(0,H), left (0,H)->(0,0). Empty: no graticule can be drawn.
    std::array<std::vector<glm::dvec2>, 4> edge_lon_lat;
};

// The largest 1, 2 or 5 x 10^n not over `at_most` (> 0).
double nice_length(double at_most);

struct ScaleBarLength {
    double length = 0.0;    // in `unit`
    std::string unit = "m"; // "m", "km", "ft" or "mi"
    double unit_m = 1.0;    // metres per unit
    int divisions = 1;      // 5 for a length of 1 or 5 x 10^n, 4 for 2 x 10^n
    double length_px = 0.0; // the length on the image
};

// The longest nice length (in metres, or kilometres from 1 km; feet, or miles from 1 mile, when
// imperial) at most max_px long at metres_per_px.
ScaleBarLength scale_bar_length(double metres_per_px, double max_px, bool imperial);

// Ground metres per image pixel along the image's rows (the geotransform's column step).
double ground_metres_per_px(const FurnitureFrame& frame);

// The image direction (unit vector, y down) of true north: grid north (map +Y) turned
// anticlockwise by convergence_deg, through the inverse of the geotransform's linear part.
glm::dvec2 true_north_direction(const std::array<double, 6>& geotransform, double convergence_deg);

// Where, along the segment from -> to (image pixels), component `axis` of values sampled at
// evenly spaced points of it (linear between samples) crosses a multiple of `interval`.
struct EdgeTick {
    glm::dvec2 at;
    double value = 0.0;
};
std::vector<EdgeTick> edge_ticks(glm::dvec2 from, glm::dvec2 to, const std::vector<glm::dvec2>& samples, int axis,
                                 double interval);

// A graticule interval, degrees: the largest of 1', 2', 5', 10', 15', 30', 1, 2, 5, 10, 15, 30,
// 45 degrees not over `at_most` (the smallest when all are).
double graticule_interval_deg(double at_most);

// "36°35'N", "84°10'W", "36°35'30\"N": degrees, minutes, and seconds when not whole (UTF-8).
std::string lon_lat_label(double degrees, bool longitude);

// Fills the drawing's furniture layers (and sets drawing.furniture): what `options` asks for, on
// the map `frame` describes.
void add_map_furniture(Drawing& drawing, const FurnitureFrame& frame, const MapFurnitureOptions& options);

}  // namespace penink
