#include "input/dem_reader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>

#include <GeographicLib/UTMUPS.hpp>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "core/error.hpp"
#include "support/test_grids.hpp"

namespace penink {
namespace {

using test::TempDir;

std::string error_of(const std::string& path, const DemOptions& o = {}) {
    try {
        read_dem(path, o);
    } catch (const Error& e) {
        EXPECT_EQ(e.stage(), "input");
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.code(), ExitCode::bad_input);
        return e.what();
    }
    return "no error";
}

TEST(DemReader, AsciiValuesAndOrientation) {
    TempDir dir;
    const std::string p = test::write_asc(dir.file("g.asc"), 3, {{1, 2, 3}, {4, 5, 6}}, 1000, 2000, 10);
    const Terrain t = read_dem(p);
    ASSERT_EQ(t.cols, 3);
    ASSERT_EQ(t.rows, 2);
    // Node centres x 1005..1025, y 2015 (north row) .. 2005: origin = centre of the grid.
    EXPECT_EQ(t.origin, glm::dvec2(1015, 2010));
    EXPECT_EQ(t.pos[t.index(0, 0)], glm::vec3(-10, 5, 1));
    EXPECT_EQ(t.pos[t.index(2, 0)], glm::vec3(10, 5, 3));
    EXPECT_EQ(t.pos[t.index(0, 1)], glm::vec3(-10, -5, 4));
    EXPECT_EQ(t.pos[t.index(2, 1)], glm::vec3(10, -5, 6));
    EXPECT_TRUE(std::all_of(t.valid.begin(), t.valid.end(), [](auto v) { return v == 1; }));
    EXPECT_TRUE(t.crs_wkt.empty());
    EXPECT_EQ(t.utm_zone, 0);
    EXPECT_EQ(t.source, p);
    EXPECT_EQ(t.elevation_min, 1.0);
    EXPECT_EQ(t.elevation_max, 6.0);
}

TEST(DemReader, NodataNodesAreInvalid) {
    TempDir dir;
    // the last row gives the grid a cell with data at its four corners (read_dem wants one)
    const std::string p = test::write_asc(dir.file("g.asc"), 3, {{-9999, 2, 3}, {4, 5, -9999}, {1, 1, 1}}, 0, 0, 1,
                                          "NODATA_value -9999\n");
    const Terrain t = read_dem(p);
    const std::vector<std::uint8_t> want{0, 1, 1, 1, 1, 0, 1, 1, 1};
    EXPECT_EQ(t.valid, want);
    EXPECT_EQ(t.elevation_min, 1.0);
    EXPECT_EQ(t.elevation_max, 5.0);
    EXPECT_EQ(t.pos[t.index(1, 0)].z, 2.0f);
}

TEST(DemReader, NanAndNodataInGeoTiffAreInvalid) {
    TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const double nodata = -3.4028234663852886e+38;
    // the last column gives the grid a cell with data at its four corners (read_dem wants one)
    const std::string p = test::write_tif(dir.file("g.tif"), 3, 2, {nan, 7, 8, float(nodata), 9, 10},
                                          {0, 1, 0, 2, 0, -1}, 0, &nodata);
    const Terrain t = read_dem(p);
    const std::vector<std::uint8_t> want{0, 1, 1, 0, 1, 1};
    EXPECT_EQ(t.valid, want);
    EXPECT_EQ(t.pos[4].z, 9.0f);
}

TEST(DemReader, SouthUpGridIsFlippedSoRowZeroIsNorth) {
    TempDir dir;
    // File row 0 is the south edge (GT[5] > 0): y of file row r centre = 100 + 10 (r + 0.5).
    const std::string p = test::write_tif(dir.file("s.tif"), 2, 3, {1, 2, 3, 4, 5, 6},
                                          {500, 10, 0, 100, 0, 10});
    const Terrain t = read_dem(p);
    ASSERT_EQ(t.rows, 3);
    EXPECT_EQ(t.origin, glm::dvec2(510, 115));
    EXPECT_EQ(t.pos[t.index(0, 0)], glm::vec3(-5, 10, 5));  // north row = last file row
    EXPECT_EQ(t.pos[t.index(1, 2)], glm::vec3(5, -10, 2));
    const std::array<double, 6> gt{500, 10, 0, 130, 0, -10};
    EXPECT_EQ(t.geotransform, gt);
}

TEST(DemReader, RotatedGeotransformAppliesFullAffine) {
    TempDir dir;
    const double c = std::cos(0.5), s = std::sin(0.5);
    const std::array<double, 6> gt{1000, 10 * c, 10 * s, 5000, 10 * s, -10 * c};
    const std::string p = test::write_tif(dir.file("r.tif"), 3, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9}, gt);
    const Terrain t = read_dem(p);
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) {
            const double x = gt[0] + (col + 0.5) * gt[1] + (r + 0.5) * gt[2];
            const double y = gt[3] + (col + 0.5) * gt[4] + (r + 0.5) * gt[5];
            const glm::vec3 q = t.pos[t.index(col, r)];
            EXPECT_NEAR(q.x + t.origin.x, x, 1e-3);
            EXPECT_NEAR(q.y + t.origin.y, y, 1e-3);
            EXPECT_EQ(q.z, float(r * 3 + col + 1));
        }
    // Centre node (1, 1) sits at the grid centre: origin is it, rounded to metres.
    EXPECT_EQ(t.origin, glm::round(glm::dvec2(gt[0] + 1.5 * (gt[1] + gt[2]), gt[3] + 1.5 * (gt[4] + gt[5]))));
}

TEST(DemReader, ExaggerationScalesZOnly) {
    const std::string p = PENINK_SOURCE_DIR "/examples/volcano.asc";
    const Terrain a = read_dem(p);
    const Terrain b = read_dem(p, {.vertical_exaggeration = 2.5});
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(b.vertical_exaggeration, 2.5);
    EXPECT_EQ(a.origin, b.origin);
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.pos[i].x, b.pos[i].x);
        ASSERT_EQ(a.pos[i].y, b.pos[i].y);
        ASSERT_FLOAT_EQ(a.pos[i].z * 2.5f, b.pos[i].z);
    }
}

TEST(DemReader, ErrorTexts) {
    TempDir dir;
    const std::string missing = dir.file("nothing.tif");
    EXPECT_EQ(error_of(missing), "penink: input: " + missing + ": no such file");
    const std::string text = test::write_text(dir.file("notes.txt"), "this is not a raster\n");
    EXPECT_EQ(error_of(text), "penink: input: " + text + ": not a DEM raster (GDAL cannot read it)");
    const std::string empty = test::write_asc(dir.file("empty.asc"), 2, {{-1, -1}, {-1, -1}}, 0, 0, 1,
                                              "NODATA_value -1\n");
    EXPECT_EQ(error_of(empty), "penink: input: " + empty + ": DEM has no valid elevation (all nodata)");
    const std::string one = test::write_asc(dir.file("one.asc"), 1, {{5}}, 0, 0, 1);
    EXPECT_EQ(error_of(one), "penink: input: " + one + ": DEM is too small (1x1 nodes; at least 2x2 needed)");
    const std::string line = test::write_asc(dir.file("line.asc"), 3, {{5, 6, 7}}, 0, 0, 1);
    EXPECT_EQ(error_of(line), "penink: input: " + line + ": DEM is too small (3x1 nodes; at least 2x2 needed)");
    const std::string ok = PENINK_SOURCE_DIR "/examples/volcano.asc";
    for (double ve : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        EXPECT_EQ(error_of(ok, {.vertical_exaggeration = ve}),
                  "penink: input: " + ok + ": vertical exaggeration must be > 0");
}

TEST(DemReader, GdalStaysSilent) {
    TempDir dir;
    const std::string bad = test::write_text(dir.file("bad.tif"), "II*\0 truncated tiff");
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(error_of(bad), "penink: input: " + bad + ": not a DEM raster (GDAL cannot read it)");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(CPLGetLastErrorType(), CE_None);
}

TEST(DemReader, ForcedZoneErrors) {
    const std::string p = PENINK_SOURCE_DIR "/examples/jacksboro.tif";
    EXPECT_EQ(error_of(p, {.utm_zone = 61}),
              "penink: input: " + p + ": UTM zone must be 1..60 (0 = standard zone), got 61");
    const std::string far = error_of(p, {.utm_zone = 40});
    EXPECT_EQ(far.rfind("penink: input: " + p + ": DEM cannot be projected to UTM zone 40N: ", 0), 0u) << far;
}

TEST(DemReader, VolcanoGridShapeRangeAndSpacing) {
    const Terrain t = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    EXPECT_EQ(t.cols, 61);
    EXPECT_EQ(t.rows, 87);
    float lo = 1e9f, hi = -1e9f;
    for (const glm::vec3& p : t.pos) lo = std::min(lo, p.z), hi = std::max(hi, p.z);
    EXPECT_EQ(lo, 94.0f);
    EXPECT_EQ(hi, 195.0f);
    EXPECT_EQ(t.pos[t.index(1, 0)].x - t.pos[t.index(0, 0)].x, 10.0f);
    EXPECT_EQ(t.pos[t.index(0, 0)].y - t.pos[t.index(0, 1)].y, 10.0f);
    EXPECT_EQ(t.pos[t.index(0, 0)].y - t.pos[t.index(60, 0)].y, 0.0f);
    // NZTM (volcano.prj): projected, not UTM; origin at the grid centre.
    EXPECT_NE(t.crs_wkt.find("New Zealand Transverse Mercator"), std::string::npos);
    EXPECT_EQ(t.utm_zone, 0);
    EXPECT_EQ(t.origin, glm::dvec2(1756970 + 305, 5917000 + 435));
    // The first (north) row of the file ends with 97: the north-east node.
    EXPECT_EQ(t.pos[t.index(60, 0)].z, 97.0f);
}

TEST(DemReader, VolcanoTifMatchesAsc) {
    const Terrain a = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    const Terrain b = read_dem(PENINK_SOURCE_DIR "/tests/data/volcano.tif");
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.origin, b.origin);
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.pos[i], b.pos[i]) << i;
}

TEST(DemReader, ProjectedFeetAreConvertedToMetres) {
    TempDir dir;  // EPSG:2274 NAD83 / Tennessee (ftUS): 100 ft cells
    const std::string p = test::write_tif(dir.file("ft.tif"), 2, 2, {1, 2, 3, 4},
                                          {1800000, 100, 0, 600000, 0, -100}, 2274);
    const Terrain t = read_dem(p);
    EXPECT_NEAR(t.pos[1].x - t.pos[0].x, 100 * 1200.0 / 3937.0, 1e-3);
    EXPECT_NEAR(t.origin.x, std::round(1800100 * 1200.0 / 3937.0), 0.5);
    EXPECT_EQ(t.pos[0].z, 1.0f);  // elevations stay metres
}

TEST(DemReader, ElevationsInFeetAreConvertedInBothReads) {
    TempDir dir;  // band unit "ft"; the heights-only read takes the values as metres first, then redoes them
    const double nodata = -9999;
    const std::string p = test::write_tif(dir.file("zft.tif"), 3, 2, {10, 20, -9999, 40, 50, 60},
                                          {1000, 10, 0, 5000, 0, -10}, 2193, &nodata);
    {
        GDALDatasetUniquePtr ds(GDALDataset::Open(p.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
        ds->GetRasterBand(1)->SetUnitType("ft");
    }
    DemOptions heights, full;
    heights.heights_only = true;
    heights.vertical_exaggeration = full.vertical_exaggeration = 2.0;
    const Terrain f = read_dem(p, full), h = read_dem(p, heights);
    EXPECT_EQ(f.elevation_min, 10 * 0.3048);
    EXPECT_EQ(f.elevation_max, 60 * 0.3048);
    EXPECT_EQ(f.pos[1].z, float(20 * 0.3048 * 2.0));
    EXPECT_EQ(f.pos[2].z, float(10 * 0.3048 * 2.0));  // nodata: the lowest valid elevation
    ASSERT_EQ(h.z.size(), f.pos.size());
    for (std::size_t i = 0; i < h.z.size(); ++i) EXPECT_EQ(h.z[i], f.pos[i].z) << i;
    EXPECT_EQ(h.elevation_min, f.elevation_min);
    EXPECT_EQ(h.elevation_max, f.elevation_max);
}

// Independent UTM coordinates of node (c, r) of a geographic file, from its geotransform.
glm::dvec2 utm_of_node(const std::string& path, int c, int r, int zone, bool& north) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
    double gt[6];
    ds->GetGeoTransform(gt);
    const double lon = gt[0] + (c + 0.5) * gt[1], lat = gt[3] + (r + 0.5) * gt[5];
    int z = 0;
    double x, y;
    GeographicLib::UTMUPS::Forward(lat, lon, z, north, x, y, zone);
    return {x, y};
}

TEST(DemReader, JacksboroIsProjectedToUtm16North) {
    const std::string p = PENINK_SOURCE_DIR "/examples/jacksboro.tif";
    const Terrain t = read_dem(p);
    EXPECT_EQ(t.cols, 403);
    EXPECT_EQ(t.rows, 344);
    EXPECT_EQ(t.utm_zone, 16);
    EXPECT_TRUE(t.north);
    EXPECT_TRUE(t.source_geographic);
    EXPECT_NE(t.crs_wkt.find("UTM zone 16N"), std::string::npos);
    bool north = false;
    const glm::dvec2 nw = utm_of_node(p, 0, 0, GeographicLib::UTMUPS::STANDARD, north);
    EXPECT_TRUE(north);
    EXPECT_NEAR(t.origin.x + t.pos[0].x, nw.x, 1.0);
    EXPECT_NEAR(t.origin.y + t.pos[0].y, nw.y, 1.0);
    EXPECT_NEAR(t.elevation_min, 236.0, 1e-9);
    EXPECT_NEAR(t.elevation_max, 1076.0, 1e-9);
    // ~75 m x 93 m cells: east step positive, south step negative.
    EXPECT_NEAR(t.pos[1].x - t.pos[0].x, 74.5, 1.5);
    EXPECT_NEAR(t.pos[t.index(0, 1)].y - t.pos[0].y, -92.6, 1.0);
}

TEST(DemReader, JacksboroForcedZoneAndAscii) {
    const std::string p = PENINK_SOURCE_DIR "/examples/jacksboro.tif";
    const Terrain t = read_dem(p, {.utm_zone = 17});
    EXPECT_EQ(t.utm_zone, 17);
    bool north = false;
    const glm::dvec2 ne = utm_of_node(p, 402, 0, 17, north);
    EXPECT_NEAR(t.origin.x + t.pos[402].x, ne.x, 1.0);
    EXPECT_NEAR(t.origin.y + t.pos[402].y, ne.y, 1.0);
    const Terrain a = read_dem(PENINK_SOURCE_DIR "/tests/data/jacksboro.asc");
    const Terrain b = read_dem(p);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.origin, b.origin);
    for (std::size_t i = 0; i < a.size(); i += 97) ASSERT_NEAR(glm::distance(a.pos[i], b.pos[i]), 0.0, 0.05) << i;
}

// The origin is the rounded centre of the bounds of ALL projected nodes, although the reader visits
// only the first and last rows and the rows' ends on an axis-aligned grid (every row when the
// geotransform rotates): checked against every node projected on its own, west of the zone's
// central meridian (curved rows), on an axis-aligned and a rotated grid.
TEST(DemReader, GeographicOriginIsTheCentreOfAllNodes) {
    TempDir dir;
    const int w = 90, h = 40;
    const std::vector<float> z(std::size_t(w) * h, 100.0f);
    for (const double rot : {0.0, 0.0021}) {
        const std::array<double, 6> gt{-89.95, 0.011, rot, 37.2, rot * 0.5, -0.009};
        const std::string p = test::write_tif(dir.file(rot ? "rot.tif" : "axis.tif"), w, h, z, gt, 4326);
        const Terrain t = read_dem(p);
        glm::dvec2 lo(1e300), hi(-1e300);
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                int zone = 0;
                bool north = true;
                double x, y;
                const double lon = gt[0] + (c + 0.5) * gt[1] + (r + 0.5) * gt[2];
                const double lat = gt[3] + (c + 0.5) * gt[4] + (r + 0.5) * gt[5];
                GeographicLib::UTMUPS::Forward(lat, lon, zone, north, x, y, t.utm_zone);
                lo = glm::min(lo, glm::dvec2(x, y)), hi = glm::max(hi, glm::dvec2(x, y));
            }
        EXPECT_EQ(t.origin, glm::round(0.5 * (lo + hi))) << "rotation " << rot;
    }
}

// A projected DEM's nodes are an affine grid whose formula gives every stored position exactly
// (the drainage database stores cells instead of x, y on it), also in a cropped window; a
// geographic DEM has none.
TEST(DemReader, ProjectedNodesFollowTheirAffineGridExactly) {
    const Terrain full = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    const Terrain window = crop_terrain(full, {7, 11, 50, 80});
    for (const Terrain* t : {&full, &window}) {
        AffineNodes a;
        ASSERT_TRUE(terrain_affine(*t, a));
        for (int r = 0; r < t->rows; ++r)
            for (int c = 0; c < t->cols; ++c) {
                const glm::vec3& p = t->pos[t->index(c, r)];
                ASSERT_EQ(affine_node_xy(a, t->origin, c, r), glm::vec2(p.x, p.y)) << c << " " << r;
            }
    }
    AffineNodes none;
    EXPECT_FALSE(terrain_affine(read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), none));
}

// The same options with positions read.
DemOptions heights_full(DemOptions o) {
    o.heights_only = false;
    return o;
}

TEST(DemReader, HeightsOnlyReadKeepsTheElevationsAndLeavesPositionsOut) {
    TempDir dir;
    const double c = std::cos(0.3), s = std::sin(0.3), nodata = -9999;
    const std::string rotated = test::write_tif(dir.file("r.tif"), 4, 3, {1, 2, 3, 4, 5, -9999, 7, 8, 9, 10, 11, 12},
                                                {1000, 10 * c, 10 * s, 5000, 10 * s, -10 * c}, 2193, &nodata);
    DemOptions heights;
    heights.heights_only = true;
    heights.vertical_exaggeration = 2.5;
    for (const std::string& p : {std::string(PENINK_SOURCE_DIR "/examples/volcano.asc"), rotated}) {
        DemOptions full_options;
        full_options.vertical_exaggeration = 2.5;
        const Terrain full = read_dem(p, full_options), h = read_dem(p, heights);
        EXPECT_TRUE(h.pos.empty());
        ASSERT_EQ(h.z.size(), full.pos.size());
        for (std::size_t i = 0; i < full.pos.size(); ++i) ASSERT_EQ(h.z[i], full.pos[i].z) << p << " " << i;
        EXPECT_EQ(h.valid, full.valid);
        EXPECT_EQ(h.origin, full.origin);
        EXPECT_EQ(h.xy_unit, full.xy_unit);
        EXPECT_EQ(h.elevation_min, full.elevation_min);
        EXPECT_EQ(h.elevation_max, full.elevation_max);
        EXPECT_EQ(h.crs_wkt, full.crs_wkt);
    }
    EXPECT_TRUE(read_dem(rotated, heights).xy.empty());  // x, y from the affine grid
    // a geographic DEM has no affine grid in metres: its nodes' UTM x, y come apart, in xy
    const Terrain full = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif", heights_full(heights));
    const Terrain geo = read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif", heights);
    EXPECT_TRUE(geo.pos.empty());
    ASSERT_EQ(geo.z.size(), full.pos.size());
    ASSERT_EQ(geo.xy.size(), full.pos.size());
    for (std::size_t i = 0; i < full.pos.size(); ++i) {
        ASSERT_EQ(geo.z[i], full.pos[i].z) << i;
        ASSERT_EQ(geo.xy[i], glm::vec2(full.pos[i])) << i;
    }
    EXPECT_EQ(geo.valid, full.valid);
    EXPECT_EQ(geo.origin, full.origin);
    EXPECT_EQ(geo.crs_wkt, full.crs_wkt);
    EXPECT_EQ(geo.utm_zone, full.utm_zone);
}

TEST(DemReader, SouthernHemisphereGeographic) {
    TempDir dir;  // around Auckland: zone 60 south
    const std::string p = test::write_tif(dir.file("akl.tif"), 3, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9},
                                          {174.70, 0.01, 0, -36.80, 0, -0.01}, 4326);
    const Terrain t = read_dem(p);
    EXPECT_EQ(t.utm_zone, 60);
    EXPECT_FALSE(t.north);
    bool north = true;
    const glm::dvec2 q = utm_of_node(p, 2, 2, 60, north);
    EXPECT_FALSE(north);
    EXPECT_NEAR(t.origin.x + t.pos[8].x, q.x, 1.0);
    EXPECT_NEAR(t.origin.y + t.pos[8].y, q.y, 1.0);
    EXPECT_NE(t.crs_wkt.find("UTM zone 60S"), std::string::npos);
}

}  // namespace
}  // namespace penink

namespace penink {
namespace {

TEST(DemReader, DegreesWithoutACrsAreWarnedAbout) {
    TempDir dir;
    const std::string deg = test::write_asc(dir.file("d.asc"), 3, {{1, 2, 3}, {4, 5, 6}}, -84.41375, 36.44625, 0.000833333);
    EXPECT_EQ(missing_crs_warning(read_dem(deg)),
              "penink: warning: input: " + deg + ": no CRS and a cell size of 0.000833333: if these are "
              "degrees, add the CRS (e.g. a .prj); positions are taken as metres");
    const std::string metres = test::write_asc(dir.file("m.asc"), 3, {{1, 2, 3}, {4, 5, 6}}, 1000, 2000, 10);
    EXPECT_EQ(missing_crs_warning(read_dem(metres)), "");
    // a small cell far outside the longitude/latitude range: metres in a local frame
    const std::string local = test::write_asc(dir.file("l.asc"), 3, {{1, 2, 3}, {4, 5, 6}}, 5000, 7000, 0.001);
    EXPECT_EQ(missing_crs_warning(read_dem(local)), "");
    const std::string tif = test::write_tif(dir.file("g.tif"), 2, 2, {1, 2, 3, 4},
                                            {-84.4, 0.000833, 0, 36.4, 0, -0.000833}, 4326);
    EXPECT_EQ(missing_crs_warning(read_dem(tif)), "");  // geographic CRS known: projected to UTM
}

}  // namespace
}  // namespace penink

namespace penink {
namespace {

TEST(DemReader, TextGridDeclaringMoreValuesThanItsFileHoldsFailsBeforeReading) {
    TempDir dir;
    const std::string huge = test::write_text(dir.file("huge.asc"),
                                              "ncols 50000\nnrows 50000\nxllcorner 0\nyllcorner 0\ncellsize 10\n"
                                              "1 2 3 4 5 6 7 8\n");
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(error_of(huge),
              "penink: input: " + huge + ": ASCII grid declares 50000x50000 values but its 76 bytes hold at most 38");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
    try {
        read_dem_size(huge);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("declares 50000x50000 values"), std::string::npos);
    }
    const DemSize v = read_dem_size(PENINK_SOURCE_DIR "/examples/volcano.asc");
    EXPECT_EQ(v.cols, 61);
    EXPECT_EQ(v.rows, 87);
}

TEST(DemReader, ValuesBeyondAMillionAreErrorsNamingTheirCell) {
    TempDir dir;
    for (const char* v : {"1e30", "-2e6"}) {
        const std::string p = test::write_text(dir.file("g.asc"), std::string("ncols 3\nnrows 2\nxllcorner 0\n"
                                                                              "yllcorner 0\ncellsize 1\n1 2 3\n4 ") + v + " 6\n");
        char value[32];
        std::snprintf(value, sizeof value, "%g", std::strtod(v, nullptr));
        EXPECT_EQ(error_of(p), "penink: input: " + p + ": row 2, column 2 holds " + value +
                                   ": elevations must lie within +-1e6 (mark missing cells with the nodata value)");
    }
    const float inf = std::numeric_limits<float>::infinity();  // (GDAL's ASCII grid reads "inf" as 0 or FLT_MAX)
    const std::string tif = test::write_tif(dir.file("g.tif"), 3, 2, {1, 2, 3, 4, 5, -inf}, {0, 1, 0, 2, 0, -1});
    EXPECT_EQ(error_of(tif), "penink: input: " + tif +
                                 ": row 2, column 3 holds -inf: elevations must lie within +-1e6 (mark missing cells "
                                 "with the nodata value)");
    const std::string ok = test::write_text(dir.file("ok.asc"), "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n"
                                                                "cellsize 1\n1e6 -1e6\n0 0\n");
    EXPECT_EQ(error_of(ok), "no error");
}

TEST(DemReader, NeedsACellWithDataAtItsFourCorners) {
    TempDir dir;
    const std::string one = test::write_asc(dir.file("one.asc"), 3, {{-1, -1, -1}, {-1, 5, -1}, {-1, -1, -1}}, 0, 0, 1,
                                            "NODATA_value -1\n");
    EXPECT_EQ(error_of(one), "penink: input: " + one +
                                 ": DEM has fewer than 2x2 valid nodes (no cell with data at its four corners)");
    const std::string diagonal = test::write_asc(dir.file("diag.asc"), 2, {{1, -1}, {-1, 1}}, 0, 0, 1, "NODATA_value -1\n");
    EXPECT_NE(error_of(diagonal).find("fewer than 2x2 valid nodes"), std::string::npos);
}

TEST(DemReader, CellSizeMustBePositive) {
    TempDir dir;
    for (const char* size : {"0", "-10", "nan"}) {
        const std::string p = test::write_text(dir.file("c.asc"), std::string("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n"
                                                                              "cellsize ") + size + "\n1 2\n3 4\n");
        EXPECT_EQ(error_of(p), "penink: input: " + p + ": cell size must be > 0 (got " + size + ")");
    }
    const std::string dy = test::write_text(dir.file("dy.asc"), "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n"
                                                                "dx 10\ndy -5\n1 2\n3 4\n");
    EXPECT_EQ(error_of(dy), "penink: input: " + dy + ": cell size must be > 0 (got -5)");
}

TEST(DemReader, ReadBeyondTheMemoryBudgetFailsNamingWhatItNeeds) {
    const std::string p = PENINK_SOURCE_DIR "/examples/volcano.asc";  // 61 x 87 nodes, 21 B each
    EXPECT_EQ(error_of(p, {.max_memory = 100000}),
              "penink: input: " + p + ": reading the DEM's 61x87 nodes would need about 109 KiB of memory, "
              "98 KiB available (--max-memory)");
    EXPECT_NO_THROW(read_dem(p, {.max_memory = 200000}));
}

}  // namespace
}  // namespace penink

namespace penink {
namespace {

// Everything a heights-only read gives, x, y included (xy_rows), against DemRows' meta, rows and
// xy, read in bands of `band_rows` for the opening pass and in pieces of `piece` rows after.
void expect_rows_as_read(const std::string& p, int band_rows, int piece) {
    DemOptions heights;
    heights.heights_only = true;
    const DemSize size = read_dem_size(p);
    std::vector<glm::vec2> xy(std::size_t(size.cols) * std::size_t(size.rows));
    // rows in parallel, each into its own part of xy
    heights.xy_rows = [&](const Terrain& t, int r, const glm::vec2* row) {
        std::copy(row, row + t.cols, xy.begin() + std::ptrdiff_t(t.index(0, r)));
    };
    const Terrain want = read_dem(p, heights);
    DemRows rows(p, {}, band_rows);
    const Terrain& m = rows.meta();
    const std::string at = p + " bands of " + std::to_string(band_rows);
    EXPECT_EQ(m.cols, want.cols) << at;
    ASSERT_EQ(m.rows, want.rows) << at;
    EXPECT_EQ(m.origin, want.origin) << at;
    EXPECT_EQ(m.xy_unit, want.xy_unit) << at;
    EXPECT_EQ(m.elevation_min, want.elevation_min) << at;
    EXPECT_EQ(m.elevation_max, want.elevation_max) << at;
    EXPECT_EQ(m.crs_wkt, want.crs_wkt) << at;
    EXPECT_EQ(m.utm_zone, want.utm_zone) << at;
    EXPECT_EQ(m.north, want.north) << at;
    EXPECT_EQ(m.source_geographic, want.source_geographic) << at;
    EXPECT_EQ(m.geotransform, want.geotransform) << at;
    EXPECT_TRUE(m.z.empty() && m.valid.empty() && m.pos.empty() && m.xy.empty()) << at;
    const std::size_t w = std::size_t(m.cols);
    std::vector<float> z(w * std::size_t(piece));
    std::vector<std::uint8_t> valid(z.size());
    std::vector<glm::vec2> line(w);
    for (int y0 = 0; y0 < m.rows; y0 += piece) {
        const int y1 = std::min(m.rows, y0 + piece);
        rows.rows(y0, y1, z.data(), valid.data());
        for (std::size_t i = 0; i < std::size_t(y1 - y0) * w; ++i) {
            const std::size_t j = std::size_t(y0) * w + i;
            ASSERT_EQ(std::bit_cast<std::uint32_t>(z[i]), std::bit_cast<std::uint32_t>(want.z[j])) << at << " node " << j;
            ASSERT_EQ(valid[i], want.valid[j]) << at << " node " << j;
        }
        for (int y = y0; y < y1; ++y) {
            rows.xy(y, line.data());
            for (std::size_t c = 0; c < w; ++c) ASSERT_EQ(line[c], xy[std::size_t(y) * w + c]) << at << " row " << y;
        }
    }
}

// A south-up Int32 GeoTIFF (values read as doubles) with a nodata value, NaN-free, scale, offset
// and heights in feet: every conversion a read makes.
std::string int_feet_tif(const std::string& path) {
    GDALAllRegister();
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    const int w = 5, h = 7;
    GDALDatasetUniquePtr ds(drv->Create(path.c_str(), w, h, 1, GDT_Int32, nullptr));
    double gt[6] = {1000, 10, 0, 5000, 0, 10};  // south up
    ds->SetGeoTransform(gt);
    OGRSpatialReference srs;
    srs.importFromEPSG(2193);
    ds->SetSpatialRef(&srs);
    GDALRasterBand* b = ds->GetRasterBand(1);
    b->SetNoDataValue(-32768);
    b->SetScale(0.5), b->SetOffset(10.0), b->SetUnitType("ft");
    std::vector<std::int32_t> v(std::size_t(w) * h);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::int32_t((i * 7919) % 1000) - 300;
    v[3] = v[17] = v[34] = -32768;
    EXPECT_EQ(b->RasterIO(GF_Write, 0, 0, w, h, v.data(), w, h, GDT_Int32, 0, 0), CE_None);
    return path;
}

TEST(DemRows, RowsMetaAndXYAreAHeightsOnlyReadsBitForBit) {
    TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const double nodata = -9999;
    std::vector<float> v(6 * 9);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = float(std::sin(double(i)) * 40.0 + 100.0);
    v[0] = nan, v[10] = -9999, v[53] = -9999;
    const std::string south = test::write_tif(dir.file("s.tif"), 6, 9, v, {500, 10, 0, 100, 0, 10}, 2193, &nodata);
    const std::string ints = int_feet_tif(dir.file("i.tif"));
    // south up, more rows than rows() reads at once (256): a piece crosses two of its reads
    std::vector<float> tall(4 * 300);
    for (std::size_t i = 0; i < tall.size(); ++i) tall[i] = float(std::cos(double(i) * 0.01) * 30.0 + double(i / 4));
    tall[1001] = -9999;
    const std::string south_tall = test::write_tif(dir.file("t.tif"), 4, 300, tall, {500, 10, 0, 100, 0, 10}, 2193, &nodata);
    for (const std::string& p : {std::string(PENINK_SOURCE_DIR "/examples/volcano.asc"),
                                 std::string(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), south, ints, south_tall})
        for (const auto& [band, piece] : {std::pair{0, 1000}, std::pair{1, 1}, std::pair{3, 2}, std::pair{7, 5}})
            expect_rows_as_read(p, band, piece);
}

TEST(DemRows, ErrorsAreReadDemsWhateverTheBands) {
    TempDir dir;
    std::vector<std::string> files;
    // a value out of range in the last row (the last band), and two in different bands: the first
    // in the file's order is named
    files.push_back(test::write_text(dir.file("far.asc"), "ncols 3\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1\n"
                                                          "1 2 3\n4 5 6\n7 8 9\n1 2e7 3\n"));
    files.push_back(test::write_text(dir.file("two.asc"), "ncols 3\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1\n"
                                                          "1 2 3\n4 5 -3e6\n7 8 9\n1 2e7 3\n"));
    files.push_back(test::write_asc(dir.file("none.asc"), 2, {{-1, -1}, {-1, -1}, {-1, -1}}, 0, 0, 1, "NODATA_value -1\n"));
    files.push_back(test::write_asc(dir.file("diag.asc"), 3, {{1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, 0, 0, 1,
                                    "NODATA_value -1\n"));
    files.push_back(dir.file("missing.tif"));
    for (const std::string& p : files) {
        const std::string want = error_of(p);
        EXPECT_NE(want, "no error") << p;
        for (int band : {0, 1, 2}) {
            std::string got = "no error";
            try {
                DemRows rows(p, {}, band);
            } catch (const Error& e) {
                got = e.what();
            }
            EXPECT_EQ(got, want) << p << " bands of " << band;
        }
    }
    // the grid's one cell with data at its four corners straddles two bands of one row
    const std::string straddle = test::write_asc(dir.file("straddle.asc"), 3, {{-1, -1, -1}, {-1, 4, 5}, {-1, 6, 7}}, 0,
                                                 0, 1, "NODATA_value -1\n");
    EXPECT_EQ(error_of(straddle), "no error");
    for (int band : {1, 2}) EXPECT_NO_THROW(DemRows(straddle, {}, band)) << band;
}

}  // namespace
}  // namespace penink
