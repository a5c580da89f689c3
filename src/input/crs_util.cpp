#include "input/crs_util.hpp"

#include <cmath>

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdlib>

namespace penink {

std::string utm_wkt(int zone, bool north) {
    OGRSpatialReference srs;
    if (zone == 0) {
        srs.importFromEPSG(north ? 32661 : 32761);
    } else {
        const std::string name = "WGS 84 / UTM zone " + std::to_string(zone) + (north ? "N" : "S");
        srs.SetProjCS(name.c_str());
        srs.SetWellKnownGeogCS("WGS84");
        srs.SetUTM(zone, north ? TRUE : FALSE);
        srs.AutoIdentifyEPSG();
    }
    return srs_wkt(srs);
}

std::string srs_wkt(const OGRSpatialReference& srs) {
    char* text = nullptr;
    if (srs.exportToWkt(&text) != OGRERR_NONE || !text || !*text) {
        CPLFree(text);
        text = nullptr;
        const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
        if (srs.exportToWkt(&text, options) != OGRERR_NONE) text = nullptr;
    }
    std::string out = text ? text : "";
    CPLFree(text);
    return out;
}

std::unique_ptr<OGRSpatialReference> srs_from_wkt(const std::string& wkt) {
    if (wkt.empty()) return nullptr;
    auto srs = std::make_unique<OGRSpatialReference>();
    if (srs->importFromWkt(wkt.c_str()) != OGRERR_NONE) return nullptr;
    srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

double linear_unit_of(const std::string& wkt) {
    const auto srs = srs_from_wkt(wkt);
    if (!srs || !srs->IsProjected()) return 1.0;
    const double u = srs->GetLinearUnits(nullptr);
    return u > 0.0 ? u : 1.0;
}

namespace {

// The EPSG code the WKT names at its root, else the one OSR identifies; 0 when none.
int epsg_code(const OGRSpatialReference& srs) {
    OGRSpatialReference s(srs);
    if (!s.GetAuthorityCode(nullptr)) s.AutoIdentifyEPSG();
    const char* name = s.GetAuthorityName(nullptr);
    const char* code = s.GetAuthorityCode(nullptr);
    return name && code && EQUAL(name, "EPSG") ? std::atoi(code) : 0;
}

}  // namespace

void add_geographic_corners(Georeference& g, int width, int height) {
    const auto srs = srs_from_wkt(g.crs_wkt);
    if (!srs) return;
    g.geographic = srs->IsGeographic();
    g.epsg = epsg_code(*srs);
    std::unique_ptr<OGRSpatialReference> geog(srs->CloneGeogCS());
    if (!geog) return;
    geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = lon, y = lat
    std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(srs.get(), geog.get()));
    if (!ct) return;
    const double cols[4] = {0.0, 0.0, double(width), double(width)}, rows[4] = {0.0, double(height), double(height), 0.0};
    std::vector<glm::dvec2> corners;
    for (int i = 0; i < 4; ++i) {
        const glm::dvec2 p = map_point(g, cols[i], rows[i]);
        double x = p.x, y = p.y;
        if (!ct->Transform(1, &x, &y)) return;
        corners.push_back({y, x});
    }
    g.corner_lat_lon = std::move(corners);
}

namespace {

// Transforms between the CRS in `wkt` and its own geographic CRS (x = lon, y = lat).
struct GeographicTransforms {
    std::unique_ptr<OGRSpatialReference> srs, geog;
    std::unique_ptr<OGRCoordinateTransformation> to_geog, from_geog;
};

std::optional<GeographicTransforms> geographic_transforms(const std::string& wkt) {
    GeographicTransforms t;
    t.srs = srs_from_wkt(wkt);
    if (!t.srs) return std::nullopt;
    t.geog.reset(t.srs->CloneGeogCS());
    if (!t.geog) return std::nullopt;
    t.geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    t.to_geog.reset(OGRCreateCoordinateTransformation(t.srs.get(), t.geog.get()));
    t.from_geog.reset(OGRCreateCoordinateTransformation(t.geog.get(), t.srs.get()));
    if (!t.to_geog || !t.from_geog) return std::nullopt;
    return t;
}

}  // namespace

std::vector<glm::dvec2> map_to_lon_lat(const std::string& wkt, const std::vector<glm::dvec2>& points) {
    const auto t = geographic_transforms(wkt);
    if (!t) return {};
    std::vector<glm::dvec2> out;
    out.reserve(points.size());
    for (const glm::dvec2& p : points) {
        double x = p.x, y = p.y;
        if (!t->to_geog->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y)) return {};
        out.emplace_back(x, y);
    }
    return out;
}

std::optional<double> grid_convergence_deg(const std::string& wkt, glm::dvec2 p) {
    const auto t = geographic_transforms(wkt);
    if (!t) return std::nullopt;
    if (t->srs->IsGeographic()) return 0.0;
    double lon = p.x, lat = p.y;
    if (!t->to_geog->Transform(1, &lon, &lat)) return std::nullopt;
    const double step = lat + 1e-4 <= 90.0 ? 1e-4 : -1e-4;
    double x = lon, y = lat + step;
    if (!t->from_geog->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y)) return std::nullopt;
    const double dx = (x - p.x) * (step > 0 ? 1.0 : -1.0), dy = (y - p.y) * (step > 0 ? 1.0 : -1.0);
    if (dx == 0.0 && dy == 0.0) return std::nullopt;
    // true north lies at bearing atan2(dx, dy) from grid north; grid north at minus that from it
    return -std::atan2(dx, dy) * 180.0 / 3.14159265358979323846;
}

}  // namespace penink
