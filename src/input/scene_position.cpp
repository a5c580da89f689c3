#include "input/scene_position.hpp"

#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <regex>

#include <GeographicLib/Constants.hpp>
#include <cpl_error.h>
#include <ogr_spatialref.h>

#include "core/error.hpp"
#include "core/printable_text.hpp"
#include "input/crs_util.hpp"
#include "input/utm_projection.hpp"

namespace penink {

namespace {

// A position as written in a scene, before any transformation.
struct ParsedPosition {
    enum class Kind { utm, lonlat, native } kind = Kind::native;
    double a = 0.0, b = 0.0;  // easting/northing, lon/lat or x/y
    int zone = 0;
    bool north = true;
};

const std::string number = R"(([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))";

std::optional<ParsedPosition> parse_text(const std::string& text) {
    static const std::regex utm(R"(^\s*)" + number + R"(\s+)" + number + R"(\s+(\d{1,2})\s*([NnSs])\s*$)");
    static const std::regex lonlat(R"(^\s*)" + number + R"(\s*,\s*)" + number + R"(\s*$)");
    static const std::regex native(R"(^\s*)" + number + R"(\s+)" + number + R"(\s*$)");
    std::smatch m;
    ParsedPosition p;
    if (std::regex_match(text, m, utm)) {
        p.kind = ParsedPosition::Kind::utm;
        p.zone = std::stoi(m[3].str());
        p.north = m[4].str() == "N" || m[4].str() == "n";
        if (p.zone < 1 || p.zone > 60) return std::nullopt;
    } else if (std::regex_match(text, m, lonlat)) {
        p.kind = ParsedPosition::Kind::lonlat;
    } else if (std::regex_match(text, m, native)) {
        p.kind = ParsedPosition::Kind::native;
    } else {
        return std::nullopt;
    }
    p.a = std::strtod(m[1].str().c_str(), nullptr), p.b = std::strtod(m[2].str().c_str(), nullptr);
    if (!std::isfinite(p.a) || !std::isfinite(p.b)) return std::nullopt;
    return p;
}

// OGR transformation of one point between two CRSs (traditional GIS axis order on both).
std::optional<glm::dvec2> ogr_transform(const OGRSpatialReference& from, const std::string& to_wkt,
                                        glm::dvec2 p) {
    const auto to = srs_from_wkt(to_wkt);
    if (!to) return std::nullopt;
    OGRSpatialReference src(from);
    src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&src, to.get()));
    const bool ok = ct && ct->Transform(1, &p.x, &p.y) && std::isfinite(p.x) && std::isfinite(p.y);
    CPLErrorReset();
    CPLPopErrorHandler();
    if (!ok) return std::nullopt;
    return p * linear_unit_of(to_wkt);
}

// UTM/UPS easting/northing of lon/lat in the terrain's zone and hemisphere (GeographicLib).
std::optional<glm::dvec2> lonlat_to_terrain_utm(double lon, double lat, const Terrain& t) {
    try {
        return project_to_utm({lon, lat}, t.utm_zone, t.north);
    } catch (const GeographicLib::GeographicErr&) {
        return std::nullopt;
    }
}

// Projected world coordinates (metres) of a parsed position; nullopt when it cannot be placed.
std::optional<glm::dvec2> to_world(const ParsedPosition& p, const Terrain& t) {
    if (p.kind == ParsedPosition::Kind::native) return glm::dvec2(p.a, p.b) * linear_unit_of(t.crs_wkt);
    if (t.crs_wkt.empty()) return std::nullopt;
    if (p.kind == ParsedPosition::Kind::utm) {
        if (t.utm_zone == p.zone && t.north == p.north) return glm::dvec2(p.a, p.b);
        const auto from = srs_from_wkt(utm_wkt(p.zone, p.north));
        return from ? ogr_transform(*from, t.crs_wkt, {p.a, p.b}) : std::nullopt;
    }
    if (std::abs(p.b) > 90.0) return std::nullopt;
    if (t.utm_zone > 0) return lonlat_to_terrain_utm(p.a, p.b, t);
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    return ogr_transform(wgs84, t.crs_wkt, {p.a, p.b});
}

}  // namespace

glm::dvec2 parse_scene_position(const std::string& text, const Terrain& terrain,
                                const std::string& scene_file) {
    const std::optional<ParsedPosition> p = parse_text(text);
    if (!p)
        throw Error("scene", scene_file,
                    "cannot parse position \"" + printable_text(text) +
                        "\" (expected \"EASTING NORTHING ZONE[N|S]\", \"LON,LAT\" or \"X Y\")");
    const std::optional<glm::dvec2> world = to_world(*p, terrain);
    if (!world)
        throw Error("scene", scene_file,
                    "cannot transform position \"" + printable_text(text) + "\" into the DEM's coordinate system");
    return *world - terrain.origin;
}

}  // namespace penink
