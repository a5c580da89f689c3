// Parses a camera position of a scene into the Terrain's local frame (metres):
// UTM "588497 4589846 18N" (easting northing zone+hemisphere), "lon,lat" in WGS84 degrees,
// or "x y" in the Terrain's own projected CRS. Transforms between CRSs with GDAL/OGR
// (GeographicLib for lon/lat <-> UTM).
#pragma once
#include <string>

#include <glm/vec2.hpp>

#include "input/terrain.hpp"

namespace penink {

// Throws penink::Error(stage "scene", file = scene_file) on text it cannot parse.
glm::dvec2 parse_scene_position(const std::string& text, const Terrain& terrain,
                                const std::string& scene_file);

}  // namespace penink
