// Our PNG against independent renderers of our SVG (rsvg-convert), PS/EPS (Ghostscript) and PDF
// (pdftoppm) at the same size. Tolerance: anti-aliasing differs only along edges (each renderer
// has its own coverage filter and PS blends opacity toward white instead of compositing), so we
// require the mean absolute difference < 2 % of full scale and > 99 % of pixels within 64 levels:
// a missing/misplaced stroke, wrong width, colour or flipped y breaks both by a wide margin.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "export/export_drawing.hpp"
#include "export/raster_writer.hpp"
#include "support/raster_image.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;

namespace {

using Image = RasterImage;

Image read_png(const std::string& path) { return read_rgb_over_white(path); }

void expect_close(const Image& ours, const Image& theirs, const std::string& what) {
    ASSERT_EQ(theirs.w, ours.w) << what;
    ASSERT_EQ(theirs.h, ours.h) << what;
    const RasterDiff d = raster_diff(ours, theirs);
    std::printf("%s: mean |diff| %.3f %%, within 64 levels %.3f %%\n", what.c_str(), 100 * d.mean, 100.0 * d.within);
    EXPECT_LT(d.mean, 0.02) << what;
    EXPECT_GT(d.within, 0.99) << what;
}

class RasterCompare : public ::testing::Test {
protected:
    TempDir dir{"raster"};
    StyledDrawing drawing = style_drawing(small_drawing(), visible_style());
    Image ours;
    void SetUp() override {
        export_drawing(drawing, PageOptions{}, dir.file("ours.png"));
        ours = read_png(dir.file("ours.png"));
        ASSERT_EQ(ours.w, 200);
        ASSERT_EQ(ours.h, 160);
    }
    Image render(const std::string& ext, const std::string& command) {
        export_drawing(drawing, PageOptions{}, dir.file("in" + ext));
        const std::string cmd = "cd '" + dir.path.string() + "' && " + command + " 2>err.txt";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << read_text(dir.file("err.txt"));
        EXPECT_EQ(read_text(dir.file("err.txt")), "") << ext;  // no warnings from the renderer
        return read_png(dir.file("out.png"));
    }
};

}  // namespace

TEST_F(RasterCompare, OurPngHasTheDrawing) {
    // Pixel (100, 20) is on the silhouette (#203080), (100, 110) inside the mask hole (white).
    const size_t on = 3 * size_t(20 * 200 + 100), hole = 3 * size_t(110 * 200 + 100);
    EXPECT_LT(ours.rgb[on], 80.0f);
    EXPECT_NEAR(ours.rgb[hole], 255.0f, 0.01f);
    EXPECT_NEAR(ours.rgb[3 * size_t(140 * 200 + 60)], 216.0f, 0.01f);  // surface fill #d8d8d8
}

TEST_F(RasterCompare, SvgByRsvg) {
    if (!have_tool("rsvg-convert")) GTEST_SKIP() << "rsvg-convert not installed";
    expect_close(ours, render(".svg", "rsvg-convert -w 200 -h 160 -b white -o out.png in.svg"), "svg");
}

TEST_F(RasterCompare, PsByGhostscript) {
    if (!have_tool("gs")) GTEST_SKIP() << "ghostscript not installed";
    expect_close(ours, render(".ps", "gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 "
                                     "-dGraphicsAlphaBits=4 -sOutputFile=out.png in.ps"), "ps");
}

TEST_F(RasterCompare, EpsByGhostscript) {
    if (!have_tool("gs")) GTEST_SKIP() << "ghostscript not installed";
    // The EPS's bounding box is its ink (plus the margin): rendered on the drawing's whole page
    // (200 x 160 px at 96 dpi = 150 x 120 pt), where its coordinates place it.
    expect_close(ours, render(".eps", "gs -q -dSAFER -dBATCH -dNOPAUSE -dDEVICEWIDTHPOINTS=150 "
                                      "-dDEVICEHEIGHTPOINTS=120 -dFIXEDMEDIA -sDEVICE=png16m -r96 "
                                      "-dGraphicsAlphaBits=4 -sOutputFile=out.png in.eps"), "eps");
}

TEST_F(RasterCompare, PdfByPdftoppm) {
    if (!have_tool("pdftoppm")) GTEST_SKIP() << "pdftoppm not installed";
    expect_close(ours, render(".pdf", "pdftoppm -r 96 -png -singlefile in.pdf out"), "pdf");
}

TEST(PngWriter, CapsuleAndFillCoverage) {
    Drawing d;
    d.width = 64;
    d.height = 32;
    d.layer(LayerKind::surface).fill = {{{4, 4}, {24, 4}, {24, 24}, {4, 24}}, {{9, 9}, {19, 9}, {19, 19}, {9, 19}}};
    d.layer(LayerKind::ridges).strokes.push_back(make_stroke({{30, 10}, {60, 10}}, {1, 1}, 1, "r"));
    Style s = default_style();
    s.fill = Rgb{0, 0, 0};
    s.layer(LayerKind::ridges).width = s.layer(LayerKind::ridges).width_far = 4.0;
    s.layer(LayerKind::ridges).taper = 0.0;  // a plain capsule stroke of one width
    s.layer(LayerKind::ridges).weight_min = s.layer(LayerKind::ridges).weight_max = 1.0;
    const RgbImage img = rasterise(style_drawing(d, s), RasterTransform{64, 32, 1.0, 0.0, 0.0});
    const auto at = [&](int x, int y) { return int(img.rgb[3 * size_t(y * 64 + x)]); };
    for (int y = 8; y <= 11; ++y) EXPECT_EQ(at(45, y), 0) << y;  // line covers y in [8, 12]
    EXPECT_EQ(at(45, 7), 255);
    EXPECT_EQ(at(45, 12), 255);
    EXPECT_EQ(at(29, 10), 0);    // round cap reaches x = 28
    EXPECT_EQ(at(27, 10), 255);
    EXPECT_EQ(at(5, 5), 0);      // ring
    EXPECT_EQ(at(14, 14), 255);  // hole (even-odd)
    EXPECT_EQ(at(25, 5), 255);
    int black = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 28; ++x) black += at(x, y) == 0;
    EXPECT_EQ(black, 400 - 100);
}

TEST(PngWriter, DpiScalesTheImage) {
    PageOptions o;
    o.dpi = 192;
    const RasterTransform t = raster_transform(style_drawing(small_drawing(), default_style()), o);
    EXPECT_EQ(t.width, 400);
    EXPECT_EQ(t.height, 320);
    EXPECT_DOUBLE_EQ(t.scale, 2.0);
}
