// Export entry points: choose the writer by the output file's extension (.svg .ps .eps .pdf
// .png), and plotting statistics of a StyledDrawing (path count, inked length and pen-up
// travel in drawing order, image pixels) for --verbose.
#pragma once
#include <cstddef>
#include <string>

#include "export/page.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// Writes `drawing` to `path` in the format named by its extension (case-insensitive).
// Unknown: Error("export", path, "unknown output format \".xyz\" (use .svg, .ps, .eps, .pdf or .png)").
// Throws penink::Error("export", path, "unknown output format ...") unless the extension
// (case-insensitive) is one export_drawing writes: .svg .ps .eps .pdf .png.
void check_output_format(const std::string& path);

void export_drawing(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

struct PlotStats {
    std::size_t paths = 0;
    double length_px = 0.0;  // pen-down length of all strokes
    double travel_px = 0.0;  // pen-up moves from each path's end to the next path's start
};

// Stats in drawing order (layers bottom to top, groups, paths); surface fill rings excluded.
PlotStats plot_stats(const StyledDrawing& drawing);

}  // namespace penink
