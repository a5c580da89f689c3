// `penink render --map`, `--scale 1:N` and `--vertical-exaggeration auto` from the command line:
// a plan view at a scale on a page writes its files and records the view (the Jacksboro DEM at
// 1:100 000 on A4, read back by GDAL); what cannot be a map is one error line, exit 2, no output.
#include <cmath>
#include <memory>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <gtest/gtest.h>

#include "cli_support.hpp"

using namespace penink::test;

namespace {

const std::string volcano = PENINK_SOURCE_DIR "/examples/volcano.asc";
const std::string house = PENINK_SOURCE_DIR "/examples/house.toml";

}  // namespace

TEST(MapViewCli, PlanViewAtAScaleOnAPage) {
    const auto dir = fresh_dir("map_page");
    const RunResult r = run_penink("render '" + volcano + "' --map --scale 1:10000 --page A5 --dpi 100 -o m.svg -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string svg = read_text(dir / "m.svg");
    // A5 landscape at 100 dpi: 210 x 148 mm = 827 x 583 px (whole pixels); the page holds them at
    // min(210/827, 148/583) = 0.25386 mm a pixel, so 1:10 000 makes the image 2099.42 m across.
    EXPECT_NE(svg.find("altitude -90, orthographic, 2099.41"), std::string::npos);
    EXPECT_NE(svg.find(", 827x583"), std::string::npos);
    EXPECT_NE(svg.find("map scale 1:10000"), std::string::npos);
    EXPECT_NE(svg.find("vertical_exaggeration 1 (auto)"), std::string::npos);
}

TEST(MapViewCli, VerboseSaysTheChosenExaggeration) {
    const auto dir = fresh_dir("map_auto");
    const RunResult r = run_penink("render '" + volcano + "' --vertical-exaggeration auto --width 200 --height 150 -o a.svg -v", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("penink: relief 101 m over 860 m: vertical exaggeration 1 (auto)"), std::string::npos) << r.output;
    const RunResult n = run_penink("render '" + volcano + "' --vertical-exaggeration 3 --width 200 --height 150 -o n.svg -v", dir);
    ASSERT_EQ(n.code, 0) << n.output;
    EXPECT_EQ(n.output.find("(auto)"), std::string::npos);
    EXPECT_NE(read_text(dir / "n.svg").find("vertical_exaggeration 3,"), std::string::npos);
}

TEST(MapViewCli, WhatCannotBeAMapIsAnError) {
    const auto dir = fresh_dir("map_errors");
    RunResult r = run_penink("render '" + volcano + "' --scale 1:5000 -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: " + volcano +
                            ": a map scale needs an orthographic view ([camera] projection = \"orthographic\", or --map)\n");
    r = run_penink("render '" + volcano + "' --map --scale 1:abc -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("must be a map scale 1:N"), std::string::npos) << r.output;
    r = run_penink("render '" + volcano + "' --vertical-exaggeration flat -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("must be auto or > 0 and at most 1000 (got \"flat\")"), std::string::npos) << r.output;
    write_text(dir / "p.toml", "[terrain]\ndem = '" + volcano + "'\n[camera]\nprojection = 'isometric'\n");
    r = run_penink("render p.toml -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: p.toml: [camera] projection must be \"perspective\" or \"orthographic\" (got \"isometric\")\n");
    write_text(dir / "e.toml", "[terrain]\ndem = '" + volcano + "'\nvertical_exaggeration = 'lots'\n");
    r = run_penink("render e.toml -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.output, "penink: scene: e.toml: [terrain] vertical_exaggeration: expected a number or \"auto\"\n");
    r = run_penink("render '" + house + "' --map -o x.svg", dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("orthographic views are for DEMs"), std::string::npos) << r.output;
    EXPECT_EQ(file_count(dir), 2u);  // the two scene files: no output left
}

// The README's map: Jacksboro (geographic, drawn in UTM 16N) at 1:100 000 on A4 as a PDF and a
// PNG. GDAL reads both back: the CRS is UTM 16N, a GDAL pixel of the PDF (150 dpi) is
// 100 000 x 25.4 / 150 mm = 16.93 m, the PNG's pixel (150 dpi) the same, and the page's centre
// is the centre of the DEM's projected plan box (the plan view frames it), computed here from the
// DEM's edge node centres with OGR, not with penink's projection.
TEST(MapViewCli, JacksboroAtOneToOneHundredThousandOnA4IsWhereGdalSaysItIs) {
    const auto dir = fresh_dir("map_jacksboro");
    const std::string dem = PENINK_SOURCE_DIR "/examples/jacksboro.tif";
    const RunResult r = run_penink("render '" + dem + "' --map --scale 1:100000 --page A4 --dpi 150 -o map.pdf -o map.png -q", dir);
    ASSERT_EQ(r.code, 0) << r.output;
    GDALAllRegister();
    OGRSpatialReference utm;
    utm.importFromEPSG(32616);
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    // The DEM's plan box in UTM 16N from its edge node centres.
    double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
    {
        std::unique_ptr<GDALDataset> src(GDALDataset::Open(dem.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
        ASSERT_TRUE(src);
        double gt[6];
        ASSERT_EQ(src->GetGeoTransform(gt), CE_None);
        OGRSpatialReference wgs;
        wgs.importFromEPSG(4326);
        wgs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&wgs, &utm));
        ASSERT_TRUE(ct);
        const int w = src->GetRasterXSize(), h = src->GetRasterYSize();
        for (int i = 0; i < 2 * (w + h); ++i) {
            const int c = i < 2 * w ? i % w : (i - 2 * w < h ? 0 : w - 1);
            const int row = i < 2 * w ? (i < w ? 0 : h - 1) : (i - 2 * w) % h;
            double x = gt[0] + (c + 0.5) * gt[1], y = gt[3] + (row + 0.5) * gt[5];
            ASSERT_TRUE(ct->Transform(1, &x, &y));
            lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
        }
    }
    for (const char* name : {"map.pdf", "map.png"}) {
        SCOPED_TRACE(name);
        std::unique_ptr<GDALDataset> ds(GDALDataset::Open((dir / name).c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
        ASSERT_TRUE(ds);
        const OGRSpatialReference* srs = ds->GetSpatialRef();
        ASSERT_NE(srs, nullptr);
        EXPECT_TRUE(srs->IsSame(&utm));
        double gt[6];
        ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
        const double pixel = 100000.0 * 25.4 / 150.0 / 1000.0;
        EXPECT_NEAR(gt[1], pixel, pixel * 0.005);  // the page rounds to whole drawing pixels
        EXPECT_NEAR(gt[5], -pixel, pixel * 0.005);
        EXPECT_NEAR(gt[2], 0.0, 1e-6);
        EXPECT_NEAR(gt[4], 0.0, 1e-6);
        // A4 landscape (297 x 210 mm) at 150 dpi: 1754 x 1240 pixels, the page's centre the DEM's.
        EXPECT_NEAR(ds->GetRasterXSize(), 1754, 1);
        EXPECT_NEAR(ds->GetRasterYSize(), 1240, 1);
        const double cx = gt[0] + 0.5 * ds->GetRasterXSize() * gt[1], cy = gt[3] + 0.5 * ds->GetRasterYSize() * gt[5];
        EXPECT_NEAR(cx, 0.5 * (lo_x + hi_x), pixel);
        EXPECT_NEAR(cy, 0.5 * (lo_y + hi_y), pixel);
    }
}
