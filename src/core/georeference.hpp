// Where a drawing lies on the map: the affine transform from drawing pixels to the projected
// coordinates of the DEM's world CRS (metres; the CRS of Terrain::crs_wkt, UTM for a geographic
// DEM), for an orthographic view looking straight down (a plan view, any azimuth). Pixel
// coordinates as in drawing.hpp: origin at the image's top-left corner, y down; (col, row) are
// corner coordinates, so pixel (0, 0) covers [0, 1] x [0, 1]. The transform is in GDAL's
// geotransform order: X = gt[0] + col*gt[1] + row*gt[2], Y = gt[3] + col*gt[4] + row*gt[5].
// Oblique and perspective views have no such transform: they are not georeferenced.
#pragma once
#include <array>
#include <optional>
#include <string>

#include <glm/vec2.hpp>

#include "core/camera.hpp"

namespace penink {

struct Georeference {
    std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
    std::string crs_wkt;  // may be empty: a DEM without a CRS (local metres)
};

// True for an orthographic camera looking straight down (altitude -90 within 1e-6 degrees).
bool is_plan_view(const Camera& cam);

// The plan view's pixel -> map transform; nullopt for any other view. origin: projected
// coordinates of the world frame's (0, 0) (Terrain::origin).
std::optional<Georeference> plan_view_georeference(const Camera& cam, glm::dvec2 origin, const std::string& crs_wkt);

// Map point (X, Y) of drawing pixel corner coordinates (col, row).
glm::dvec2 map_point(const Georeference& g, double col, double row);

}  // namespace penink
