// Where a drawing lies on the map: the affine transform from drawing pixels to the projected
// coordinates of the DEM's world CRS (metres; the CRS of Terrain::crs_wkt, UTM for a geographic
// DEM), for an orthographic view looking straight down (a plan view, any azimuth). Pixel
// coordinates as in drawing.hpp: origin at the image's top-left corner, y down; (col, row) are
// corner coordinates, so pixel (0, 0) covers [0, 1] x [0, 1]. The transform is in GDAL's
// geotransform order: X = gt[0] + col*gt[1] + row*gt[2], Y = gt[3] + col*gt[4] + row*gt[5].
// Oblique and perspective views have no such transform: they are not georeferenced.
// The export writers carry it (conventions.md, "Maps and georeferencing"); the geographic corners
// a PDF's geospatial measure needs are added by the input stage (input/crs_util.hpp), which has
// GDAL, as export has not.
#pragma once
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/camera.hpp"

namespace penink {

struct Georeference {
    std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
    std::string crs_wkt;  // may be empty: a DEM without a CRS (local metres)
    // What the CRS is, for writers without GDAL (input/crs_util.hpp: add_geographic_corners).
    int epsg = 0;             // EPSG code of the CRS, 0 when it has none
    bool geographic = false;  // the CRS is geographic (degrees), not projected
    // (latitude, longitude) in degrees, in the CRS's own geographic CRS (its datum), of the
    // drawing's corners (0, 0), (0, H), (W, H), (W, 0) (top-left, bottom-left, bottom-right,
    // top-right) for a drawing of W x H pixels; empty when unknown (no CRS).
    std::vector<glm::dvec2> corner_lat_lon;
};

// True for an orthographic camera looking straight down (altitude -90 within 1e-6 degrees).
bool is_plan_view(const Camera& cam);

// The plan view's pixel -> map transform; nullopt for any other view. origin: projected
// coordinates of the world frame's (0, 0) (Terrain::origin).
std::optional<Georeference> plan_view_georeference(const Camera& cam, glm::dvec2 origin, const std::string& crs_wkt);

// Map point (X, Y) of drawing pixel corner coordinates (col, row).
glm::dvec2 map_point(const Georeference& g, double col, double row);

// The shortest fixed-point decimal (no exponent) that reads back as exactly `value`, via
// std::to_chars (locale-independent): map coordinates in world files, PDF and metadata.
std::string exact_decimal(double value);

// `gt` with the scale/rotation terms (1, 2, 4, 5) that are below 1e-12 of the largest of them set
// to exactly 0: the rounding left by a north-up view's rotation, which written out would read as
// a rotation of 1e-17.
std::array<double, 6> tidy_geotransform(std::array<double, 6> gt);

// The (tidy) geotransform as six exact_decimal numbers separated by spaces, GDAL order.
std::string geotransform_text(const Georeference& g);

// The drawing metadata entries that say whether and how the view is georeferenced:
// "georeferenced" ("yes (plan view)", "yes (plan view, local coordinates without a CRS)",
// "no (oblique view)", "no (perspective view)"), and for a georeferenced view "geotransform"
// (geotransform_text), "geotransform_order" (how the six numbers apply) and "crs" (the WKT,
// when there is one).
std::map<std::string, std::string> georeference_metadata(const Camera& cam, const std::optional<Georeference>& g);

}  // namespace penink
