// Georeferenced plan views in every format: GDAL opens the PDF (geospatial measure) and the rasters
// (world file + .aux.xml) and reports the drawing's CRS and a geotransform that puts the drawing's
// corners where the plan view's transform does, north up and rotated, with and without a page and
// margin; the SVG's RDF metadata and the EPS's comments carry the CRS and the six numbers; the
// side files are written with the outputs, all or none.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "core/error.hpp"
#include "export/export_drawing.hpp"
#include "export/pdf_writer.hpp"
#include "export/ps_writer.hpp"
#include "export/raster_writer.hpp"
#include "export/svg_writer.hpp"
#include "export/world_file.hpp"
#include "fixture.hpp"
#include "input/crs_util.hpp"

using namespace penink;
using namespace penink::test;

namespace {

std::string epsg_wkt(int code) {
    OGRSpatialReference srs;
    srs.importFromEPSG(code);
    return srs_wkt(srs);
}

// small_drawing() (200 x 160 px) as an orthographic plan view, 10 m a pixel, turned by `azimuth`,
// in NZTM2000 (EPSG:2193, the volcano DEM's CRS) around Maunga Whau.
StyledDrawing plan_drawing(double azimuth, const std::string& wkt) {
    Drawing d = small_drawing();
    Camera c;
    c.projection = Projection::orthographic;
    c.altitude = -90.0, c.azimuth = azimuth;
    c.width = d.width, c.height = d.height;
    c.view_width = 2000.0;
    c.eye = {300.0, -200.0, 1000.0};
    d.georeference = plan_view_georeference(c, {1756970.0, 5917870.0}, wkt);
    EXPECT_TRUE(d.georeference);
    add_geographic_corners(*d.georeference, d.width, d.height);
    d.metadata.merge(georeference_metadata(c, d.georeference));
    return style_drawing(d, visible_style());
}

struct GdalView {
    bool opened = false;
    std::unique_ptr<OGRSpatialReference> srs;
    double gt[6] = {0, 1, 0, 0, 0, 1};
    bool has_gt = false;
    int width = 0, height = 0;
};

GdalView gdal_view(const std::string& path) {
    GDALAllRegister();
    GdalView v;
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds) return v;
    v.opened = true;
    if (const OGRSpatialReference* s = ds->GetSpatialRef()) v.srs.reset(s->Clone());
    v.has_gt = ds->GetGeoTransform(v.gt) == CE_None;
    v.width = ds->GetRasterXSize(), v.height = ds->GetRasterYSize();
    return v;
}

::testing::AssertionResult same_crs(const OGRSpatialReference* a, const std::string& wkt) {
    if (!a) return ::testing::AssertionFailure() << "GDAL reports no CRS";
    const auto b = srs_from_wkt(wkt);  // x = easting, as GDAL gives a raster's CRS
    if (!b) return ::testing::AssertionFailure() << "bad WKT " << wkt;
    if (a->IsSame(b.get())) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "GDAL reports " << srs_wkt(*a) << "\nnot " << wkt;
}

glm::dvec2 apply(const double gt[6], double x, double y) {
    return {gt[0] + x * gt[1] + y * gt[2], gt[3] + x * gt[4] + y * gt[5]};
}

const double corners[4][2] = {{0, 0}, {0, 160}, {200, 160}, {200, 0}};

std::vector<PageOptions> pages() {
    PageOptions plain, a4;
    a4.page = "A4", a4.margin_mm = 15.0;
    PageOptions custom = a4;
    custom.page = "300x200mm", custom.margin_mm = 40.0;
    return {plain, a4, custom};
}

// Text of the SVG's <penink:param name="NAME">, XML entities decoded.
std::string svg_param(const std::string& svg, const std::string& name) {
    const std::string open = "<penink:param name=\"" + name + "\">";
    const size_t a = svg.find(open);
    if (a == std::string::npos) return "";
    const size_t b = svg.find("</penink:param>", a);
    std::string v = svg.substr(a + open.size(), b - a - open.size()), out;
    for (size_t i = 0; i < v.size(); ++i) {
        const std::pair<const char*, char> ents[] = {{"&quot;", '"'}, {"&apos;", '\''}, {"&lt;", '<'}, {"&gt;", '>'}, {"&amp;", '&'}};
        bool done = false;
        for (const auto& [e, c] : ents)
            if (v.compare(i, std::strlen(e), e) == 0) {
                out += c, i += std::strlen(e) - 1, done = true;
                break;
            }
        if (!done) out += v[i];
    }
    return out;
}

std::string comment_value(const std::string& ps, const std::string& key) {
    const std::string tag = "\n% penink " + key + ": ";
    const size_t a = ps.find(tag);
    if (a == std::string::npos) return "";
    return ps.substr(a + tag.size(), ps.find('\n', a + tag.size()) - a - tag.size());
}

std::array<double, 6> parse_six(const std::string& text) {
    std::istringstream in(text);
    std::array<double, 6> v{};
    for (double& x : v) in >> x;
    return v;
}

}  // namespace

TEST(GeoreferencedPdf, GdalReadsTheCrsAndPutsTheCornersWithinOnePixel) {
    TempDir dir;
    const std::string wkt = epsg_wkt(2193);
    for (double azimuth : {0.0, 30.0})
        for (const PageOptions& page : pages()) {
            SCOPED_TRACE("azimuth " + std::to_string(azimuth) + ", page \"" + page.page + "\"");
            const StyledDrawing d = plan_drawing(azimuth, wkt);
            ASSERT_EQ(d.georeference->corner_lat_lon.size(), 4u);
            const std::string path = dir.file("map.pdf");
            export_drawings(d, page, {path});
            const GdalView v = gdal_view(path);
            ASSERT_TRUE(v.opened);
            EXPECT_TRUE(same_crs(v.srs.get(), wkt));
            ASSERT_TRUE(v.has_gt);
            // GDAL renders the page at its DPI: page millimetres -> GDAL pixels per axis.
            const PageLayout L = page_layout(d.width, d.height, page, path);
            const double kx = v.width / L.page_w_mm, ky = v.height / L.page_h_mm;
            const double gdal_pixel_m = std::hypot(v.gt[1], v.gt[4]);
            EXPECT_GT(gdal_pixel_m, 0.0);
            for (const auto& c : corners) {
                const glm::dvec2 want = map_point(*d.georeference, c[0], c[1]);
                const glm::dvec2 got = apply(v.gt, (L.offset_x_mm + c[0] * L.scale_mm) * kx, (L.offset_y_mm + c[1] * L.scale_mm) * ky);
                EXPECT_LT(glm::length(got - want), gdal_pixel_m) << "corner " << c[0] << "," << c[1];
            }
            // Rotation survives: the image's x axis points along azimuth + 90 in the map.
            const double turn = std::atan2(-v.gt[4], v.gt[1]) * 180.0 / M_PI;
            // Half a degree: one GDAL pixel (the corners' bound) across the drawing's ~150 GDAL pixels.
            EXPECT_NEAR(turn, azimuth, 0.5);
        }
}

TEST(GeoreferencedPdf, InfoCarriesTheTransformAndADrawingWithoutCrsHasNoViewport) {
    const std::string wkt = epsg_wkt(2193);
    StyledDrawing d = plan_drawing(0.0, wkt);
    const std::string pdf = pdf_document(d, PageOptions{});
    EXPECT_NE(pdf.find("/VP [<< /Type /Viewport"), std::string::npos);
    EXPECT_NE(pdf.find("/Subtype /GEO"), std::string::npos);
    EXPECT_NE(pdf.find("/EPSG 2193"), std::string::npos);
    EXPECT_NE(pdf.find("/penink_geotransform " + pdf_string(geotransform_text(*d.georeference))), std::string::npos);
    EXPECT_NE(pdf.find("/penink_georeferenced (yes \\(plan view\\))"), std::string::npos);
    d.georeference->crs_wkt.clear();
    d.georeference->corner_lat_lon.clear();
    EXPECT_EQ(pdf_document(d, PageOptions{}).find("/VP"), std::string::npos);
}

TEST(GeoreferencedRaster, GdalReadsWorldFileAndCrsAtAnyDpiAndPage) {
    TempDir dir;
    const std::string wkt = epsg_wkt(2193);
    std::vector<PageOptions> cases = pages();
    cases[0].dpi = 192.0;  // two raster pixels a drawing pixel
    cases[1].dpi = 100.0;
    for (double azimuth : {0.0, 30.0})
        for (const PageOptions& page : cases)
            // TIFF is left to WorldFileBesideEachRasterFormat: once GDAL has opened a TIFF in this
            // process, OpenImageIO's TIFF writes through the same libtiff report unknown tags.
            for (const std::string name : {"map.png", "map.jpg"}) {
                SCOPED_TRACE(name + ", azimuth " + std::to_string(azimuth) + ", page \"" + page.page + "\"");
                const StyledDrawing d = plan_drawing(azimuth, wkt);
                const std::string path = dir.file(name);
                export_drawings(d, page, {path});
                ASSERT_TRUE(std::filesystem::exists(world_file_path(path)));
                ASSERT_TRUE(std::filesystem::exists(path + ".aux.xml"));
                const GdalView v = gdal_view(path);
                ASSERT_TRUE(v.opened);
                EXPECT_TRUE(same_crs(v.srs.get(), wkt));
                ASSERT_TRUE(v.has_gt);
                const RasterTransform t = raster_transform(d, page, path);
                EXPECT_EQ(v.width, t.width);
                for (const auto& c : corners) {
                    const glm::dvec2 want = map_point(*d.georeference, c[0], c[1]);
                    const glm::dvec2 got = apply(v.gt, t.offset_x + c[0] * t.scale, t.offset_y + c[1] * t.scale);
                    // A millimetre: the world file's decimals read back as the same doubles; what
                    // is left is the pixel-centre shift's rounding on coordinates of ~6e6 m.
                    EXPECT_LT(glm::length(got - want), 1e-3) << "corner " << c[0] << "," << c[1];
                }
                std::filesystem::remove(path + ".aux.xml");  // GDAL may rewrite it; the next case writes its own
            }
}

TEST(GeoreferencedRaster, WorldFileBesideEachRasterFormat) {
    TempDir dir;
    const StyledDrawing d = plan_drawing(30.0, epsg_wkt(2193));
    PageOptions page;
    page.dpi = 144.0;
    const std::vector<std::string> names = {"m.png", "m.tif", "m.tiff", "m.jpg", "m.jpeg", "m.webp", "m.exr"};
    std::vector<std::string> paths;
    for (const std::string& n : names) paths.push_back(dir.file(n));
    export_drawings(d, page, paths);
    const std::string world = read_text(dir.file("m.pgw"));
    const std::array<double, 6> gt = raster_geotransform(d.georeference->geotransform, raster_transform(d, page));
    EXPECT_EQ(world, world_file_text(gt));
    for (const char* w : {"m.tfw", "m.tiffw", "m.jgw", "m.jpegw", "m.wpw", "m.erw"}) EXPECT_EQ(read_text(dir.file(w)), world) << w;
    for (const std::string& p : paths) EXPECT_EQ(read_text(p + ".aux.xml"), aux_xml_text(d.georeference->crs_wkt)) << p;
    // Each raster has its own world file (one world file belongs to one raster).
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path), {}), 7 + 7 + 7);
}

TEST(GeoreferencedRaster, WorldFileIsThePixelCentreTransform) {
    const std::array<double, 6> gt = {1000.0, 2.0, 0.5, 5000.0, 0.25, -3.0};
    RasterTransform t;
    t.scale = 2.0, t.offset_x = 10.0, t.offset_y = 4.0;
    const std::array<double, 6> r = raster_geotransform(gt, t);
    // Raster pixel corner (10, 4) is drawing pixel (0, 0); one raster pixel is half a drawing pixel.
    EXPECT_DOUBLE_EQ(r[0] + 10 * r[1] + 4 * r[2], 1000.0);
    EXPECT_DOUBLE_EQ(r[3] + 10 * r[4] + 4 * r[5], 5000.0);
    EXPECT_DOUBLE_EQ(r[1], 1.0);
    EXPECT_DOUBLE_EQ(r[5], -1.5);
    std::istringstream lines(world_file_text(r));
    double a, dd, b, e, c, f;
    lines >> a >> dd >> b >> e >> c >> f;
    EXPECT_DOUBLE_EQ(a, r[1]);
    EXPECT_DOUBLE_EQ(dd, r[4]);
    EXPECT_DOUBLE_EQ(b, r[2]);
    EXPECT_DOUBLE_EQ(e, r[5]);
    EXPECT_DOUBLE_EQ(c, r[0] + 0.5 * r[1] + 0.5 * r[2]);
    EXPECT_DOUBLE_EQ(f, r[3] + 0.5 * r[4] + 0.5 * r[5]);
    EXPECT_EQ(world_file_path("a/b.PNG"), "a/b.pgw");
    EXPECT_EQ(world_file_path("b.tiff"), "b.tiffw");  // b.tfw is b.tif's
    EXPECT_EQ(world_file_path("b.tif"), "b.tfw");
    EXPECT_EQ(world_file_path("b.jpeg"), "b.jpegw");
    EXPECT_EQ(world_file_path("b.jpg"), "b.jgw");
    EXPECT_EQ(world_file_path("b.webp"), "b.wpw");
    EXPECT_EQ(world_file_path("b.exr"), "b.erw");
    EXPECT_EQ(shadowing_world_file("b.tiff"), "b.tfw");
    EXPECT_EQ(shadowing_world_file("b.tif"), "");
}

// A raster re-rendered over an earlier georeferenced one takes its side files with it: an oblique
// view (no georeference) removes the world file and .aux.xml, which would otherwise place the new
// pixels on the old map; a georeference without a CRS removes the .aux.xml. A failing render
// touches none of them.
TEST(GeoreferencedRaster, ARerenderRemovesTheEarlierRastersSideFiles) {
    TempDir dir;
    const StyledDrawing map = plan_drawing(0.0, epsg_wkt(2193));
    const std::string png = dir.file("view.png"), world = dir.file("view.pgw"), aux = png + ".aux.xml";
    export_drawings(map, PageOptions{}, {png});
    ASSERT_TRUE(std::filesystem::exists(world) && std::filesystem::exists(aux));
    StyledDrawing oblique = map;
    oblique.georeference.reset();
    EXPECT_THROW(export_drawings(oblique, PageOptions{}, {png, dir.file("missing/view.svg")}), Error);
    EXPECT_TRUE(std::filesystem::exists(world) && std::filesystem::exists(aux));
    export_drawings(oblique, PageOptions{}, {png, dir.file("view.svg")});
    EXPECT_TRUE(std::filesystem::exists(png));
    EXPECT_FALSE(std::filesystem::exists(world));
    EXPECT_FALSE(std::filesystem::exists(aux));
    export_drawings(map, PageOptions{}, {png});
    StyledDrawing no_crs = map;
    no_crs.georeference->crs_wkt.clear();
    export_drawings(no_crs, PageOptions{}, {png});
    EXPECT_TRUE(std::filesystem::exists(world));
    EXPECT_FALSE(std::filesystem::exists(aux));
    // a vector output has no side files: an unrelated view.svg.aux.xml stays
    write_text(dir.file("view.svg.aux.xml"), "x");
    export_drawings(oblique, PageOptions{}, {dir.file("view.svg")});
    EXPECT_TRUE(std::filesystem::exists(dir.file("view.svg.aux.xml")));
}

TEST(GeoreferencedRaster, SideFilesAreWrittenWithTheOutputsOrNotAtAll) {
    TempDir dir;
    const StyledDrawing d = plan_drawing(0.0, epsg_wkt(2193));
    const std::string png = dir.file("map.png");
    EXPECT_THROW(export_drawings(d, PageOptions{}, {png, dir.file("missing/map.svg")}), Error);
    EXPECT_FALSE(std::filesystem::exists(png));
    EXPECT_FALSE(std::filesystem::exists(dir.file("map.pgw")));
    EXPECT_FALSE(std::filesystem::exists(png + ".aux.xml"));
    EXPECT_TRUE(std::filesystem::is_empty(dir.path));  // no temp file left either
    // Not georeferenced: the raster alone.
    const StyledDrawing plain = style_drawing(small_drawing(), visible_style());
    export_drawings(plain, PageOptions{}, {png, dir.file("map.svg")});
    EXPECT_TRUE(std::filesystem::exists(png));
    EXPECT_FALSE(std::filesystem::exists(dir.file("map.pgw")));
    EXPECT_FALSE(std::filesystem::exists(png + ".aux.xml"));
}

TEST(GeoreferencedVector, SvgAndEpsMetadataCarryCrsAndTransform) {
    const std::string wkt = epsg_wkt(2193);
    const StyledDrawing d = plan_drawing(30.0, wkt);
    const std::array<double, 6> want = tidy_geotransform(d.georeference->geotransform);
    const std::string svg = svg_document(d, PageOptions{});
    EXPECT_EQ(svg_param(svg, "crs"), wkt);
    EXPECT_EQ(svg_param(svg, "georeferenced"), "yes (plan view)");
    EXPECT_NE(svg_param(svg, "geotransform_order").find("X = g0 + col*g1 + row*g2"), std::string::npos);
    EXPECT_EQ(parse_six(svg_param(svg, "geotransform")), want);  // exact decimals read back exactly
    const std::string eps = ps_document(d, PageOptions{}, true);
    EXPECT_EQ(comment_value(eps, "crs"), wkt);
    EXPECT_EQ(comment_value(eps, "georeferenced"), "yes (plan view)");
    EXPECT_EQ(parse_six(comment_value(eps, "geotransform")), want);
}
