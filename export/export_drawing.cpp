// Format dispatch and plot statistics (export_drawing.hpp).
#include "export/export_drawing.hpp"

#include <cctype>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "export/pdf_writer.hpp"
#include "export/png_writer.hpp"
#include "export/ps_writer.hpp"
#include "export/svg_writer.hpp"

namespace penink {

namespace {

std::string extension(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

void check_output_format(const std::string& path) {
    const std::string ext = extension(path);
    if (ext != ".svg" && ext != ".ps" && ext != ".eps" && ext != ".pdf" && ext != ".png")
        throw Error("export", path, "unknown output format \"" + ext + "\" (use .svg, .ps, .eps, .pdf or .png)");
}

void export_drawing(const StyledDrawing& drawing, const PageOptions& page, const std::string& path) {
    check_output_format(path);
    const std::string ext = extension(path);
    if (ext == ".svg") return write_svg(drawing, page, path);
    if (ext == ".ps" || ext == ".eps") return write_ps(drawing, page, path);
    if (ext == ".pdf") return write_pdf(drawing, page, path);
    return write_png(drawing, page, path);
}

PlotStats plot_stats(const StyledDrawing& drawing) {
    PlotStats s;
    bool have_pen = false;
    glm::vec2 pen(0.0f);
    for (const StyledLayer& l : drawing.layers)
        for (const StyledGroup& g : l.groups)
            for (const StyledPath& p : g.paths) {
                if (p.points.empty()) continue;
                ++s.paths;
                if (have_pen) s.travel_px += glm::length(p.points.front() - pen);
                for (size_t i = 1; i < p.points.size(); ++i)
                    s.length_px += glm::length(p.points[i] - p.points[i - 1]);
                pen = p.points.back();
                have_pen = true;
            }
    return s;
}

}  // namespace penink
