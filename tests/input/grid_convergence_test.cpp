// Meridian convergence through OSR (input/crs_util.hpp: grid_convergence_deg) against
// GeographicLib's transverse Mercator gamma: UTM zones either side of their central meridian,
// both hemispheres, and New Zealand's NZTM2000 (a transverse Mercator on GRS80, k0 0.9996,
// central meridian 173 E). Tolerance 1e-3 degrees: the numerical step of 1e-4 degrees of latitude
// bends with the meridian by about 1e-6 degrees; the map furniture needs 0.1.
#include <gtest/gtest.h>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/TransverseMercator.hpp>
#include <ogr_spatialref.h>

#include "input/crs_util.hpp"
#include "input/utm_projection.hpp"

using namespace penink;

namespace {

double utm_gamma(double lon, double lat, int zone) {
    double x = 0, y = 0, gamma = 0, k = 0;
    GeographicLib::TransverseMercator::UTM().Forward(6.0 * zone - 183.0, lat, lon, x, y, gamma, k);
    return gamma;
}

}  // namespace

TEST(GridConvergence, UtmAgreesWithGeographicLib) {
    const struct { double lon, lat; int zone; bool north; } places[] = {
        {-84.15, 36.60, 16, true},   // Jacksboro: 2.85 degrees east of zone 16's meridian
        {-88.90, 36.60, 16, true},   // west of it
        {174.76, -36.88, 60, false}, // Auckland in 60S
        {-87.0, 10.0, 16, true},     // on the meridian: 0
    };
    for (const auto& p : places) {
        const glm::dvec2 xy = project_to_utm({p.lon, p.lat}, p.zone, p.north);
        const auto gamma = grid_convergence_deg(utm_wkt(p.zone, p.north), xy);
        ASSERT_TRUE(gamma.has_value());
        EXPECT_NEAR(*gamma, utm_gamma(p.lon, p.lat, p.zone), 1e-3) << p.lon << ", " << p.lat;
    }
    // the sign: east of the meridian in the north, grid north is east of true north
    EXPECT_GT(*grid_convergence_deg(utm_wkt(16, true), project_to_utm({-84.15, 36.6}, 16, true)), 1.6);
}

TEST(GridConvergence, OtherTransverseMercatorsToo) {
    OGRSpatialReference nztm;
    ASSERT_EQ(nztm.importFromEPSG(2193), OGRERR_NONE);
    const std::string wkt = srs_wkt(nztm);
    const GeographicLib::TransverseMercator tm(GeographicLib::Constants::WGS84_a(), 1 / 298.257222101, 0.9996);
    double x = 0, y = 0, gamma = 0, k = 0;
    tm.Forward(173.0, -36.8763, 174.7648, x, y, gamma, k);  // Maunga Whau
    const auto g = grid_convergence_deg(wkt, {x + 1600000.0, y + 10000000.0});
    ASSERT_TRUE(g.has_value());
    EXPECT_NEAR(*g, gamma, 1e-3);
    EXPECT_FALSE(grid_convergence_deg("", {0.0, 0.0}).has_value());
}

TEST(GridConvergence, MapPointsToLonLat) {
    const glm::dvec2 xy = project_to_utm({-84.15, 36.6}, 16, true);
    const auto ll = map_to_lon_lat(utm_wkt(16, true), {xy});
    ASSERT_EQ(ll.size(), 1u);
    EXPECT_NEAR(ll[0].x, -84.15, 1e-9);
    EXPECT_NEAR(ll[0].y, 36.6, 1e-9);
    EXPECT_TRUE(map_to_lon_lat("nonsense", {xy}).empty());
}
