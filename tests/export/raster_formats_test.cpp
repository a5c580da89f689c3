// Raster output through the OpenImageIO module (penink_oiio.so): every raster extension writes a
// file that OpenImageIO reads back as the format it names, at the size and resolution asked for
// (PNG pHYs, TIFF/JPEG/EXR XResolution; WebP carries none), with penink's pixels (exactly for the
// lossless formats, within a stated tolerance for JPEG and WebP, which Debian 12's OpenImageIO
// writes lossy), and with the drawing's metadata as ImageDescription. The same drawing written
// through the same rasteriser as PNG is the reference.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "core/error.hpp"
#include "export/export_drawing.hpp"
#include "export/raster_writer.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;

namespace {

struct ReadBack {
    std::string format;
    int width = 0, height = 0, channels = 0;
    std::string unit, description, date;
    float xres = 0, yres = 0;
    std::vector<float> pixels;  // 0..1, channels interleaved
};

ReadBack read_back(const std::string& path) {
    ReadBack r;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return r;
    const OIIO::ImageSpec& s = in->spec();
    r.format = in->format_name();
    r.width = s.width, r.height = s.height, r.channels = s.nchannels;
    r.unit = s.get_string_attribute("ResolutionUnit");
    r.xres = s.get_float_attribute("XResolution"), r.yres = s.get_float_attribute("YResolution");
    r.description = s.get_string_attribute("ImageDescription");
    r.date = s.get_string_attribute("DateTime");
    r.pixels.resize(std::size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, r.pixels.data());
    return r;
}

// Mean |difference| over all values, in levels of 255.
double mean_diff(const ReadBack& a, const ReadBack& b) {
    if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return 255.0;
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(a.pixels[i] - b.pixels[i]);
    return 255.0 * sum / double(a.pixels.size());
}

}  // namespace

TEST(RasterFormats, EachExtensionWritesItsFormatWithSizeAndDpi) {
    TempDir dir;
    PageOptions page;
    page.dpi = 150;  // 200x160 image pixels at 150/96: 313x250 output pixels
    const StyledDrawing d = style_drawing(small_drawing(), default_style());
    std::vector<std::string> paths;
    for (const std::string& ext : raster_extensions()) paths.push_back(dir.file("out" + ext));
    export_drawings(d, page, paths);
    const ReadBack png = read_back(dir.file("out.png"));
    ASSERT_EQ(png.width, 313);
    ASSERT_EQ(png.height, 250);
    struct Expect {
        const char* ext;
        const char* format;
        bool dpi;
        double max_mean_diff;  // levels of 255 against the PNG
    };
    for (const Expect& e : {Expect{".png", "png", true, 0.0}, Expect{".tif", "tiff", true, 0.0},
                            Expect{".tiff", "tiff", true, 0.0}, Expect{".jpg", "jpeg", true, 2.0},
                            Expect{".jpeg", "jpeg", true, 2.0}, Expect{".webp", "webp", false, 2.0},
                            Expect{".exr", "openexr", true, 0.5}}) {
        SCOPED_TRACE(e.ext);
        const ReadBack r = read_back(dir.file(std::string("out") + e.ext));
        EXPECT_EQ(r.format, e.format);
        EXPECT_EQ(r.width, 313);
        EXPECT_EQ(r.height, 250);
        EXPECT_EQ(r.channels, 3);
        if (e.dpi) {
            EXPECT_NEAR(r.xres, 150.0, 0.02);  // PNG stores pixels per metre: 5905 -> 149.99
            EXPECT_NEAR(r.yres, 150.0, 0.02);
            EXPECT_TRUE(r.unit == "in" || r.unit == "inch") << r.unit;
            EXPECT_NE(r.description.find("source: synthetic"), std::string::npos) << r.description;
        }
        EXPECT_LE(mean_diff(r, png), e.max_mean_diff);
        // no clock in the file: the same drawing written a second later gives the same bytes
        // (OpenImageIO's TIFF and OpenEXR writers stamp the time of writing where not told otherwise)
        EXPECT_EQ(r.date, "");
    }
    // The drawing is there: the PNG is not blank (its strokes are dark on white paper).
    int dark = 0;
    for (std::size_t i = 0; i < png.pixels.size(); i += 3) dark += png.pixels[i] < 0.5f;
    EXPECT_GT(dark, 300);
}

TEST(RasterFormats, UppercaseExtensionAndPageSize) {
    TempDir dir;
    PageOptions page;
    page.page = "A6";  // 148 x 105 mm landscape drawing at 100 dpi: 583 x 413 px
    page.dpi = 100;
    export_drawing(style_drawing(small_drawing(), default_style()), page, dir.file("a.TIF"));
    const ReadBack r = read_back(dir.file("a.TIF"));
    EXPECT_EQ(r.format, "tiff");
    EXPECT_EQ(r.width, 583);
    EXPECT_EQ(r.height, 413);
    EXPECT_FLOAT_EQ(r.xres, 100.0f);
}

TEST(RasterFormats, TooLargeNamesTheFormat) {
    PageOptions page;
    page.dpi = 100000;
    EXPECT_EQ(error_of([&] { raster_transform(1000, 750, page, "/tmp/b.tiff"); }),
              "penink: export: /tmp/b.tiff: TIFF of 1041667x781250 pixels is too large (lower --dpi)");
}
