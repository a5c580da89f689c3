// One render of volcano (200x150, field-sketch: coloured paper, opacity falling with distance,
// width bands) written as SVG, PS, EPS, PDF and PNG in a single run; the vector files are
// rasterised by independent renderers (rsvg-convert, Ghostscript, pdftoppm) at the same size
// and compared with our PNG. Tolerance: renderers differ only in anti-aliasing along stroke edges
// (coverage filters differ, and PS has no transparency, so the PS writer blends opacity toward
// the paper colour instead of compositing: overlapping translucent strokes come out lighter),
// so we require mean |diff| < 2.5 % of full scale and > 98.5 % of pixels within 64 levels (of
// 255) on every channel. A missing layer, a flipped or shifted drawing (1 px shifts ~15 %
// of stroke pixels), or wrong colours fail both bounds. The PDF's optional content groups are
// listed by Ghostscript's PDF interpreter (poppler's pdfinfo does not print OCGs).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "support/raster_image.hpp"
#include "cli_support.hpp"

using namespace penink::test;

namespace {

namespace fs = std::filesystem;

using Image = RasterImage;

Image read_png(const fs::path& path) { return read_rgb_over_white(path.string()); }

class Formats : public ::testing::Test {
protected:
    static inline fs::path dir;
    static inline Image ours;
    static void SetUpTestSuite() {
        dir = fresh_dir("formats");
        for (const char* f : {"volcano.asc", "volcano.prj"})  // the drainage cache goes beside the DEM
            fs::copy_file(fs::path(PENINK_SOURCE_DIR "/examples") / f, dir / f);
        const RunResult r = run_penink("render volcano.asc --width 200 --height 150 "
                                       "--style field-sketch -o v.svg -o v.ps -o v.eps -o v.pdf -o v.png", dir);
        ASSERT_EQ(r.code, 0) << r.output;
        ours = read_png(dir / "v.png");
    }
    void expect_match(const std::string& what, const std::string& command) {
        ASSERT_EQ(ours.w, 200);
        ASSERT_EQ(ours.h, 150);
        const std::string cmd = "cd '" + dir.string() + "' && " + command + " 2>err.txt";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << read_text(dir / "err.txt");
        const Image theirs = read_png(dir / "out.png");
        ASSERT_EQ(theirs.w, 200) << what;
        ASSERT_EQ(theirs.h, 150) << what;
        const RasterDiff d = raster_diff(ours, theirs);
        std::printf("%s vs our PNG: mean |diff| %.3f %%, within 64 levels %.3f %%\n", what.c_str(), 100 * d.mean,
                    100 * d.within);
        EXPECT_LT(d.mean, 0.025) << what;
        EXPECT_GT(d.within, 0.985) << what;
        std::remove((dir / "out.png").c_str());
    }
};

}  // namespace

TEST_F(Formats, PngIsNotBlankAndAShiftIsCaught) {
    ASSERT_EQ(ours.w, 200);
    size_t dark = 0;
    for (size_t i = 0; i < ours.rgb.size(); i += 3) dark += ours.rgb[i] < 128.0f;
    EXPECT_GT(dark, 200u);  // strokes are there (269 on Mesa 22.3.6)
    Image shifted = ours;   // the same picture moved 2 px right must fail the tolerance
    for (int y = 0; y < ours.h; ++y)
        for (int x = 0; x < ours.w; ++x)
            for (int c = 0; c < 3; ++c)
                shifted.rgb[3 * size_t(y * ours.w + x) + c] = ours.rgb[3 * size_t(y * ours.w + std::max(x - 2, 0)) + c];
    const RasterDiff d = raster_diff(ours, shifted);
    EXPECT_TRUE(d.mean >= 0.025 || d.within <= 0.985) << d.mean << " " << d.within;
}

TEST_F(Formats, SvgByRsvgConvert) {
    if (!have_tool("rsvg-convert")) GTEST_SKIP() << "rsvg-convert not installed";
    expect_match("svg", "rsvg-convert -w 200 -h 150 -o out.png v.svg");
}

TEST_F(Formats, PsByGhostscript) {
    if (!have_tool("gs")) GTEST_SKIP() << "ghostscript not installed";
    expect_match("ps", "gs -q -dSAFER -dBATCH -dNOPAUSE -sDEVICE=png16m -r96 -dGraphicsAlphaBits=4 "
                       "-sOutputFile=out.png v.ps");
}

TEST_F(Formats, EpsByGhostscript) {
    if (!have_tool("gs")) GTEST_SKIP() << "ghostscript not installed";
    // the EPS's box is its ink: drawn on the image's page (200 x 150 px at 96 dpi = 150 x 112.5 pt)
    expect_match("eps", "gs -q -dSAFER -dBATCH -dNOPAUSE -dDEVICEWIDTHPOINTS=150 -dDEVICEHEIGHTPOINTS=112.5 "
                        "-dFIXEDMEDIA -sDEVICE=png16m -r96 -dGraphicsAlphaBits=4 -sOutputFile=out.png v.eps");
}

TEST_F(Formats, PdfByPdftoppm) {
    if (!have_tool("pdftoppm")) GTEST_SKIP() << "pdftoppm not installed";
    expect_match("pdf", "pdftoppm -r 96 -png -singlefile v.pdf out");
}

TEST_F(Formats, PdfLayersListedByGhostscript) {
    if (!have_tool("gs")) GTEST_SKIP() << "ghostscript not installed";
    // Ghostscript's PostScript-side PDF reader walks /Root /OCProperties /OCGs and prints names.
    const std::string cmd = "cd '" + dir.string() +
                            "' && gs -q -dNODISPLAY -dNOSAFER -dNEWPDF=false -c \"(v.pdf) (r) file runpdfbegin "
                            "Trailer /Root oget /OCProperties oget /OCGs oget {oforce /Name oget =} forall quit\" "
                            "> ocgs.txt 2>err.txt";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(dir / "err.txt");
    EXPECT_EQ(read_text(dir / "ocgs.txt"),
              "surface\ncoastline\nhachures\nridges\ncreases\npels\ntextures\nfeature-edges\nsilhouettes\n");
}
