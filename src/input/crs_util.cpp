#include "input/crs_util.hpp"

#include <cpl_conv.h>

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

}  // namespace penink
