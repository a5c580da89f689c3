// Format dispatch and plot statistics (export_drawing.hpp).
#include "export/export_drawing.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "export/pdf_writer.hpp"
#include "export/ps_writer.hpp"
#include "export/raster_writer.hpp"
#include "export/svg_writer.hpp"
#include "export/world_file.hpp"

namespace penink {

void check_output_format(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".svg" || ext == ".ps" || ext == ".eps" || ext == ".pdf" || is_raster_extension(ext)) return;
    std::string raster;
    for (const std::string& e : raster_extensions()) raster += (raster.empty() ? "" : " ") + e;
    throw Error("export", path, "unknown output format \"" + ext + "\" (use .svg .ps .eps .pdf, or a raster: " + raster + ")");
}

void export_drawing(const StyledDrawing& drawing, const PageOptions& page, const std::string& path) {
    export_drawings(drawing, page, {path});
}

std::string export_document(const StyledDrawing& drawing, const PageOptions& page, const std::string& path) {
    check_output_format(path);
    if (drawing.widths_mm) {  // millimetres on this page, as image pixels at its scale
        const PageLayout layout = page_layout(drawing.width, drawing.height, page, path);
        StyledDrawing px = drawing;
        px.widths_mm = false;
        for (StyledLayer& l : px.layers) {
            l.style.width /= layout.scale_mm, l.style.width_far /= layout.scale_mm;
            for (double& d : l.style.dash) d /= layout.scale_mm;
            for (StyledGroup& g : l.groups)
                for (StyledPath& p : g.paths) {
                    p.width /= layout.scale_mm;
                    for (double& w : p.widths) w /= layout.scale_mm;
                    for (double& d : p.dash) d /= layout.scale_mm;
                }
        }
        return export_document(px, page, path);
    }
    const std::string ext = lower_extension(path);
    if (ext == ".svg") return svg_document(drawing, page, path);
    if (ext == ".ps" || ext == ".eps") return ps_document(drawing, page, ext == ".eps", path);
    if (ext == ".pdf") return pdf_document(drawing, page, path);
    return raster_document(drawing, page, path);
}

void export_drawings(const StyledDrawing& drawing, const PageOptions& page, const std::vector<std::string>& paths) {
    for (const std::string& p : paths) check_output_format(p);
    // A georeferenced raster's world file and .aux.xml go in the same set as the outputs.
    std::vector<std::string> all = paths;
    std::vector<std::string> side_bytes;
    for (const std::string& p : paths)
        for (SideFile& f : raster_side_files(drawing, page, p)) {
            if (std::find(all.begin(), all.end(), f.path) != all.end()) continue;
            all.push_back(std::move(f.path));
            side_bytes.push_back(std::move(f.bytes));
        }
    std::vector<std::string> stale;  // side files of an earlier raster that this one does not replace
    for (const std::string& p : paths)
        for (std::string& f : raster_side_file_names(p))
            if (std::find(all.begin(), all.end(), f) == all.end() && std::find(stale.begin(), stale.end(), f) == stale.end())
                stale.push_back(std::move(f));
    write_files_together(all, [&](std::size_t i) {
        return i < paths.size() ? export_document(drawing, page, paths[i]) : side_bytes[i - paths.size()];
    });
    for (const std::string& f : stale)
        if (::unlink(f.c_str()) != 0 && errno != ENOENT)
            throw Error("export", f, std::string("cannot remove the earlier raster's side file (") + std::strerror(errno) + ")");
}

void check_output_targets(const std::vector<std::string>& paths, const PageOptions& page, int width, int height) {
    namespace fs = std::filesystem;
    for (const std::string& p : paths) {
        check_output_format(p);
        const fs::path dir = fs::path(p).parent_path();
        const std::string folder = dir.empty() ? "." : dir.string();
        std::error_code ec;
        if (!fs::is_directory(folder, ec)) throw Error("export", p, "cannot write file (no such directory)");
        if (fs::is_directory(p, ec)) throw Error("export", p, "cannot write file (is a directory)");
        if (::access(folder.c_str(), W_OK | X_OK) != 0)
            throw Error("export", p, std::string("cannot write file (") + std::strerror(errno) + ")");
        page_layout(width, height, page, p);
        if (is_raster_extension(lower_extension(p))) {
            raster_transform(width, height, page, p);
            check_raster_writer(p);
            // GDAL reads m.tfw before m.tiffw: a .tfw beside a .tiff that this command does not
            // write (another raster's, a DEM's) would georeference it wrongly.
            const std::string shadow = shadowing_world_file(p);
            bool written_here = false;
            for (const std::string& q : paths)
                written_here = written_here || (is_raster_extension(lower_extension(q)) && world_file_path(q) == shadow);
            if (!shadow.empty() && !written_here && fs::exists(fs::symlink_status(shadow, ec)))
                throw Error("export", p, fs::path(shadow).filename().string() + " beside it is another raster's world file, "
                                         "which GDAL would read as this one's (name the output ." +
                                         std::string(lower_extension(p) == ".tiff" ? "tif" : "jpg") + " or move that file)");
        }
    }
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

WidthStats width_stats(const StyledLayer& layer) {
    WidthStats s;
    double sum = 0.0, sum2 = 0.0;
    std::size_t open = 0, tapered = 0;
    for (const StyledGroup& g : layer.groups)
        for (const StyledPath& p : g.paths) {
            ++s.paths;
            const auto width_at = [&](std::size_t i) { return p.widths.empty() ? p.width : p.widths[i]; };
            for (std::size_t i = 1; i < p.points.size(); ++i) {
                const double len = glm::length(p.points[i] - p.points[i - 1]);
                const double a = width_at(i - 1), b = width_at(i);
                s.length_px += len, sum += len * 0.5 * (a + b), sum2 += len * (a * a + a * b + b * b) / 3.0;
            }
            const std::size_t n = p.points.size();
            if (n < 2 || (n > 2 && p.points.front() == p.points.back())) continue;
            ++open;
            double widest = 0.0;
            for (std::size_t i = 0; i < n; ++i) widest = std::max(widest, width_at(i));
            if (width_at(0) < 0.75 * widest && width_at(n - 1) < 0.75 * widest) ++tapered;
        }
    if (s.length_px > 0.0) {
        s.mean_width = sum / s.length_px;
        const double var = std::max(0.0, sum2 / s.length_px - s.mean_width * s.mean_width);
        s.cv = s.mean_width > 0.0 ? std::sqrt(var) / s.mean_width : 0.0;
    }
    s.tapered_share = open ? double(tapered) / double(open) : 0.0;
    return s;
}

std::vector<std::string> width_report(const StyledDrawing& drawing) {
    std::vector<std::string> lines;
    const auto fixed = [](double v, int decimals) { return format_number(v, decimals); };
    for (const StyledLayer& l : drawing.layers) {
        if (l.kind == LayerKind::surface) continue;
        const WidthStats s = width_stats(l);
        if (s.paths == 0) continue;
        lines.push_back(l.name + ": " + std::to_string(s.paths) + " paths, widths " + fixed(s.mean_width, 2) +
                        (drawing.widths_mm ? " mm" : " px") + " mean, CV " + fixed(s.cv, 2) + ", " + fixed(100.0 * s.tapered_share, 0) +
                        " % tapered at both ends");
    }
    const WidthStats sil = width_stats(drawing.layers[static_cast<std::size_t>(LayerKind::silhouettes)]);
    const WidthStats cre = width_stats(drawing.layers[static_cast<std::size_t>(LayerKind::creases)]);
    if (sil.length_px > 0.0 && cre.mean_width > 0.0)
        lines.push_back("silhouette / crease width ratio " + fixed(sil.mean_width / cre.mean_width, 2));
    return lines;
}

}  // namespace penink
