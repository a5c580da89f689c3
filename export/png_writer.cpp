// PNG output (png_writer.hpp), encoded by export/png_encode.hpp.
#include "export/png_writer.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "export/png_encode.hpp"

namespace penink {

RasterTransform png_transform(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    return png_transform(d.width, d.height, page, path);
}

RasterTransform png_transform(int width, int height, const PageOptions& page, const std::string& path) {
    const PageLayout L = page_layout(width, height, page, path);
    RasterTransform t;
    // Output pixels per millimetre: the page at dpi, or 96 dpi image pixels scaled by dpi/96.
    const double px_per_mm = page.page.empty() ? (page.dpi / 96.0) / L.scale_mm : page.dpi / 25.4;
    const double w = std::max(1.0, std::round(L.page_w_mm * px_per_mm)), h = std::max(1.0, std::round(L.page_h_mm * px_per_mm));
    if (!(w * h <= max_png_pixels)) {
        char size[64];
        std::snprintf(size, sizeof size, "%.0fx%.0f", w, h);
        throw Error("export", path, std::string("PNG of ") + size + " pixels is too large (lower --dpi)");
    }
    t.width = int(w), t.height = int(h);
    t.scale = L.scale_mm * px_per_mm;
    t.offset_x = L.offset_x_mm * px_per_mm;
    t.offset_y = L.offset_y_mm * px_per_mm;
    return t;
}

std::string png_document(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    const RasterTransform t = png_transform(d, page, path);
    const RgbImage img = rasterise(d, t);
    std::string description;
    for (const auto& [k, v] : merged_metadata(d.metadata, page.metadata)) description += k + ": " + v + "\n";
    std::vector<std::pair<std::string, std::string>> text = {{"Software", "penink"}};
    if (!description.empty()) text.emplace_back("Description", description);
    std::string bytes;
    try {
        bytes = encode_png(img, page.dpi, text);
    } catch (const std::runtime_error& e) {
        throw Error("export", path, std::string("cannot write file (") + e.what() + ")");
    }
    return bytes;
}

void write_png(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    write_file_atomically(path, png_document(d, page, path));
}

}  // namespace penink
