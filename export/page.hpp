// Page options shared by the writers, and the page layout they imply: the physical page size
// in millimetres and the uniform image-pixel -> millimetre mapping that centres the drawing
// inside the margins. Also the locale-independent number formatting every writer uses.
#pragma once
#include <map>
#include <string>
#include <string_view>

namespace penink {

struct PageOptions {
    std::string page;       // "" = image size at dpi; "A4", "A3", ..., "letter", "WxHmm"
    double dpi = 96.0;      // image pixels per inch (no page) and PNG resolution (scale dpi/96)
    double margin_mm = 0.0; // blank border on each side (only with a page)
    std::map<std::string, std::string> metadata;  // extra entries (source, camera, light, ...)
};

// The drawing's placement: page size (mm) and image pixels -> mm as x_mm = offset + x * scale.
struct PageLayout {
    double page_w_mm = 0.0, page_h_mm = 0.0;
    double scale_mm = 0.0;               // millimetres per image pixel
    double offset_x_mm = 0.0, offset_y_mm = 0.0;  // where image pixel (0, 0) lands, from top-left
};

// Largest page side, mm (PDF's own limit is 200 inches).
constexpr double max_page_mm = 5000.0;

// Parses a page name to (width, height) mm, portrait; throws std::invalid_argument (also for a
// side over max_page_mm).
// Names: A0-A6, B4, B5, letter, legal, tabloid (case-insensitive), or "WxHmm" e.g. "300x200mm".
void page_size_mm(const std::string& page, double& w_mm, double& h_mm);

// Layout for an image of width x height pixels. Named sizes turn landscape for wide images;
// "WxHmm" is used as given. Throws penink::Error("export", path, ...) for a bad page or dpi.
PageLayout page_layout(int width, int height, const PageOptions& options, const std::string& path);

// Fixed-point text with at most `decimals` decimals, trailing zeros and "-0" removed
// ("12.5", "3", "-0.25"), via std::to_chars (locale-independent).
void append_number(std::string& out, double value, int decimals = 2);
std::string format_number(double value, int decimals = 2);

// Merges the drawing's metadata with the page options' (options win), sorted by key.
std::map<std::string, std::string> merged_metadata(const std::map<std::string, std::string>& a,
                                                   const std::map<std::string, std::string>& b);

// The title every format carries (SVG <title>, PDF /Title, PS %%Title): the metadata's "title"
// (the scene layer's: the scene or DEM and the view), else the output file's name.
std::string drawing_title(const std::map<std::string, std::string>& metadata, const std::string& path);
// The description (SVG <desc>, PDF /Subject): the metadata's "description", else "".
std::string drawing_description(const std::map<std::string, std::string>& metadata);

constexpr double mm_per_inch = 25.4;
constexpr double points_per_mm = 72.0 / 25.4;

}  // namespace penink
