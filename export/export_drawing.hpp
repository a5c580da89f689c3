// Export entry points: choose the writer by the output file's extension (.svg .ps .eps .pdf, and
// the rasters of raster_writer.hpp: .png .tif .tiff .jpg .jpeg .webp .exr), and plotting
// statistics of a StyledDrawing (path count, inked length and pen-up travel in drawing order,
// image pixels) for --verbose.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "export/page.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// Writes `drawing` to `path` in the format named by its extension (case-insensitive).
// Throws penink::Error("export", path, "unknown output format \".xyz\" (use .svg .ps .eps .pdf, or
// a raster: .png .tif ...)") unless the extension (case-insensitive) is one export_drawing writes.
void check_output_format(const std::string& path);

void export_drawing(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

// The bytes of `drawing` in the format named by path's extension (check_output_format's error).
std::string export_document(const StyledDrawing& drawing, const PageOptions& page, const std::string& path);

// Writes `drawing` to every path together (write_files_together): all of them or, on any
// error, none (no path touched, no temp file left). A georeferenced raster brings its side files
// (world_file.hpp: world file, .aux.xml) into the same set.
void export_drawings(const StyledDrawing& drawing, const PageOptions& page, const std::vector<std::string>& paths);

// What can be known about the outputs before anything is drawn, for a drawing of width x height
// image pixels: each path's format (check_output_format), its folder exists and may be written
// ("cannot write file (no such directory)", "cannot write file (<the system's reason>)"), the
// path is not a folder ("cannot write file (is a directory)"), the page and margin fit
// (page_layout), a raster's size is within max_raster_pixels, and the raster writer module is
// found when a raster is asked for (check_raster_writer; it is loaded only to write). Throws
// Error("export", path, ...).
void check_output_targets(const std::vector<std::string>& paths, const PageOptions& page, int width, int height);

struct PlotStats {
    std::size_t paths = 0;
    double length_px = 0.0;  // pen-down length of all strokes
    double travel_px = 0.0;  // pen-up moves from each path's end to the next path's start
};

// Stats in drawing order (layers bottom to top, groups, paths); surface fill rings excluded.
PlotStats plot_stats(const StyledDrawing& drawing);

// The weight of a layer's lines (styles/README.md, "Weight"): the widths along every segment of
// every path, linear between its ends as the writers draw them (a path's width where it has
// one), weighted by length: a segment of length l from width a to b adds l (a + b) / 2 to the
// integral of the width and l (a^2 + ab + b^2) / 3 to that of its square, whatever the points
// between (a path's collinear points change nothing).
struct WidthStats {
    std::size_t paths = 0;
    double length_px = 0.0;
    double mean_width = 0.0;      // length-weighted, px
    double cv = 0.0;              // length-weighted coefficient of variation of the widths
    double tapered_share = 0.0;   // share of open paths of >= 2 points thinner at both ends
                                  // (each end's width under 0.75 of the path's widest)
};
WidthStats width_stats(const StyledLayer& layer);
// One line per layer with lines ("creases: 339 paths, widths 0.52 px mean, CV 0.41, 93 % tapered
// at both ends"), then the silhouette / crease mean-width ratio when both have lines.
std::vector<std::string> width_report(const StyledDrawing& drawing);

}  // namespace penink
