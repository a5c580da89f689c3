// Parses a camera position of a scene into the Terrain's local frame (metres):
// UTM "588497 4589846 18N" (easting northing zone+hemisphere), "lon,lat" in WGS84 degrees,
// or "x y" in the Terrain's own projected CRS. Transforms between CRSs with GDAL/OGR
// (GeographicLib for lon/lat <-> UTM).
#pragma once
#include <string>

#include <glm/vec2.hpp>

#include "input/terrain.hpp"

namespace penink {

// "x y" is in the CRS's units (scaled to metres like the Terrain); UTM in the Terrain's own zone
// and hemisphere is used as is (any datum); lon/lat goes through GeographicLib when the Terrain is
// UTM, else OGR. Throws penink::Error(stage "scene", file = scene_file): "cannot parse position
// \"TEXT\" (expected \"EASTING NORTHING ZONE[N|S]\", \"LON,LAT\" or \"X Y\")", or "cannot transform
// position \"TEXT\" into the DEM's coordinate system" (Terrain without CRS, |lat| > 90, OGR fails).
glm::dvec2 parse_scene_position(const std::string& text, const Terrain& terrain,
                                const std::string& scene_file);

}  // namespace penink
