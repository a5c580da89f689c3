// PNG output (png_writer.hpp), encoded by export/png_encode.hpp.
#include "export/png_writer.hpp"

#include <cmath>
#include <stdexcept>

#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "export/png_encode.hpp"

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
    write_file_atomically(path, bytes);
}

}  // namespace penink
