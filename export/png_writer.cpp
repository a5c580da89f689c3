// PNG output through OpenImageIO (png_writer.hpp).
#include "export/png_writer.hpp"

#include <OpenImageIO/imageio.h>

#include <cmath>

#include "core/error.hpp"
#include "export/atomic_file.hpp"

namespace penink {

RasterTransform png_transform(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    const PageLayout L = page_layout(d.width, d.height, page, path);
    RasterTransform t;
    // Output pixels per millimetre: the page at dpi, or 96 dpi image pixels scaled by dpi/96.
    const double px_per_mm = page.page.empty() ? (page.dpi / 96.0) / L.scale_mm : page.dpi / 25.4;
    t.width = std::max(1, int(std::lround(L.page_w_mm * px_per_mm)));
    t.height = std::max(1, int(std::lround(L.page_h_mm * px_per_mm)));
    t.scale = L.scale_mm * px_per_mm;
    t.offset_x = L.offset_x_mm * px_per_mm;
    t.offset_y = L.offset_y_mm * px_per_mm;
    if (double(t.width) * t.height > 1.0e9)
        throw Error("export", path, "PNG of " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                        " pixels is too large (lower --dpi)");
    return t;
}

void write_png(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    const RasterTransform t = png_transform(d, page, path);
    const RgbImage img = rasterise(d, t);
    const auto fail = [&](const std::string& why) {
        return Error("export", path, "cannot write file (" + why + ")");
    };
    write_atomically(path, [&](const std::string& temp) {
        auto out = OIIO::ImageOutput::create("png");
        if (!out) throw fail("no PNG support in OpenImageIO");
        OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("ResolutionUnit", "in");
        spec.attribute("XResolution", float(page.dpi));
        spec.attribute("YResolution", float(page.dpi));
        spec.attribute("Software", "penink");
        std::string description;
        for (const auto& [k, v] : merged_metadata(d.metadata, page.metadata))
            description += k + ": " + v + "\n";
        if (!description.empty()) spec.attribute("ImageDescription", description);
        if (!out->open(temp, spec)) throw fail(out->geterror());
        const bool ok = out->write_image(OIIO::TypeDesc::UINT8, img.rgb.data());
        const bool closed = out->close();
        if (!ok || !closed) throw fail(out->geterror());
    });
}

}  // namespace penink
