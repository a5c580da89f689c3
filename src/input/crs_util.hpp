// Small OGR helpers shared by the DEM reader and scene positions: WKT of a WGS84 UTM/UPS zone,
// WKT of a spatial reference, and a spatial reference (x = easting/lon, y = northing/lat, i.e.
// OAMS_TRADITIONAL_GIS_ORDER) parsed back from a Terrain's crs_wkt.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include <ogr_spatialref.h>

#include "core/georeference.hpp"

namespace penink {

// WKT of WGS 84 / UTM zone `zone` (1..60) in hemisphere `north`; zone 0 = UPS (EPSG 32661/32761).
std::string utm_wkt(int zone, bool north);

// WKT1 of `srs` (WKT2_2019 when the CRS cannot be written as WKT1); empty on failure.
std::string srs_wkt(const OGRSpatialReference& srs);

// Spatial reference from WKT with traditional GIS axis order; null when empty or unparsable.
std::unique_ptr<OGRSpatialReference> srs_from_wkt(const std::string& wkt);

// Metres per horizontal unit of the CRS in `wkt` (1 when empty, not projected or unparsable).
double linear_unit_of(const std::string& wkt);

// Completes a plan view's Georeference for writers without GDAL: the CRS's EPSG code (when its
// WKT names one or OSR identifies it), whether it is geographic, and the (lat, lon) of the
// corners of a width x height drawing in the CRS's own geographic CRS (OGRCoordinateTransformation
// from the map CRS to its CloneGeogCS, as the PDF geospatial measure asks:
// Adobe, "Supplement to ISO 32000", ExtensionLevel 3, sec. 8.8.1, GPTS).
// Leaves g as it is when it has no CRS or the CRS cannot be parsed or transformed.
void add_geographic_corners(Georeference& g, int width, int height);

// Longitude and latitude (degrees, in the CRS's own geographic CRS) of the point (x, y) in the CRS
// of `wkt` (its units); none when the CRS cannot be parsed or the point transformed.
std::optional<glm::dvec2> lon_lat_of(const std::string& wkt, glm::dvec2 xy);

}  // namespace penink
