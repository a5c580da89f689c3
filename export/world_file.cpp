// World file and .aux.xml beside a georeferenced raster (world_file.hpp).
#include "export/world_file.hpp"

#include "export/raster_writer.hpp"
#include "export/svg_writer.hpp"

namespace penink {

std::array<double, 6> raster_geotransform(const std::array<double, 6>& g, const RasterTransform& t) {
    // Raster pixel (u, v) is drawing pixel ((u - offset_x) / scale, (v - offset_y) / scale).
    const double s = t.scale, c0 = -t.offset_x / s, r0 = -t.offset_y / s;
    return {g[0] + c0 * g[1] + r0 * g[2], g[1] / s, g[2] / s, g[3] + c0 * g[4] + r0 * g[5], g[4] / s, g[5] / s};
}

std::string world_file_path(const std::string& raster_path) {
    const std::string ext = lower_extension(raster_path);
    const std::string stem = raster_path.substr(0, raster_path.size() - ext.size());
    if (ext == ".tiff" || ext == ".jpeg") return stem + ext + "w";  // .tfw, .jgw are .tif's, .jpg's
    if (ext.size() < 3) return stem + ".wld";
    return stem + "." + ext[1] + ext.back() + "w";  // .pgw .tfw .jgw .wpw .erw
}

std::string shadowing_world_file(const std::string& raster_path) {
    const std::string ext = lower_extension(raster_path);
    if (ext != ".tiff" && ext != ".jpeg") return "";
    return raster_path.substr(0, raster_path.size() - ext.size()) + "." + ext[1] + ext.back() + "w";
}

std::string world_file_text(const std::array<double, 6>& corner_gt) {
    const std::array<double, 6> g = tidy_geotransform(corner_gt);
    const double c = g[0] + 0.5 * g[1] + 0.5 * g[2], f = g[3] + 0.5 * g[4] + 0.5 * g[5];  // centre of (0, 0)
    std::string s;
    for (double v : {g[1], g[4], g[2], g[5], c, f}) s += exact_decimal(v) + "\n";
    return s;
}

std::string aux_xml_text(const std::string& crs_wkt) {
    return "<PAMDataset>\n  <SRS>" + xml_escape(crs_wkt) + "</SRS>\n</PAMDataset>\n";
}

std::vector<std::string> raster_side_file_names(const std::string& path) {
    if (!is_raster_extension(lower_extension(path))) return {};
    return {world_file_path(path), path + ".aux.xml"};
}

std::vector<SideFile> raster_side_files(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    if (!d.georeference || !is_raster_extension(lower_extension(path))) return {};
    const RasterTransform t = raster_transform(d, page, path);
    std::vector<SideFile> files = {{world_file_path(path), world_file_text(raster_geotransform(d.georeference->geotransform, t))}};
    if (!d.georeference->crs_wkt.empty()) files.push_back({path + ".aux.xml", aux_xml_text(d.georeference->crs_wkt)});
    return files;
}

}  // namespace penink
