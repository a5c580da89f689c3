// Raster output (raster_writer.hpp): penink's rasteriser, encoded by the OpenImageIO module
// penink_oiio.so, loaded with dlopen on first use.
#include "export/raster_writer.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "export/raster_module.hpp"

namespace penink {

namespace {

constexpr const char* module_name = "penink_oiio.so";


// The format's name in messages: the extension in capitals ("PNG", "TIFF", "JPG").
std::string format_label(const std::string& path) {
    std::string ext = lower_extension(path);
    if (ext.empty()) return "image";
    ext.erase(0, 1);
    for (char& c : ext) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return ext;
}

// Where the module is looked for, in order: beside the executable (the build tree), then
// ../lib/penink/ (an installed tree: bin/penink, lib/penink/penink_oiio.so).
std::vector<std::filesystem::path> module_candidates() {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return {};
    const std::filesystem::path dir = exe.parent_path();
    return {dir / module_name, (dir / ".." / "lib" / "penink" / module_name).lexically_normal()};
}

// The module's path, or "" with `error` set when it is found nowhere.
std::string find_module(std::string& error) {
    std::string tried;
    for (const auto& candidate : module_candidates()) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
        tried += (tried.empty() ? "" : ", ") + candidate.string();
    }
    error = std::string("cannot write raster images: ") + module_name + " (OpenImageIO) not found (looked for " +
            (tried.empty() ? std::string("it beside the executable") : tried) + ")";
    return "";
}

struct Module {
    PeninkRasterEncodeFn encode = nullptr;
    std::string error;  // why it could not be loaded
};

Module open_module() {
    Module m;
    const std::string path = find_module(m.error);
    if (path.empty()) return m;
    void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char* why = dlerror();
        m.error = "cannot write raster images: cannot load " + path + " (" + (why ? why : "dlopen failed") + ")";
        return m;
    }
    m.encode = reinterpret_cast<PeninkRasterEncodeFn>(dlsym(lib, PENINK_RASTER_ENCODE_SYMBOL));
    if (!m.encode) m.error = "cannot write raster images: " + path + " lacks " + PENINK_RASTER_ENCODE_SYMBOL;
    return m;
}

// Loaded once per process, on the first raster written; the handle stays open.
const Module& raster_module() {
    static const Module m = open_module();
    return m;
}

}  // namespace

const std::vector<std::string>& raster_extensions() {
    static const std::vector<std::string> exts = {".png", ".tif", ".tiff", ".jpg", ".jpeg", ".webp", ".exr"};
    return exts;
}

std::string lower_extension(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

bool is_raster_extension(const std::string& ext) {
    const auto& exts = raster_extensions();
    return std::find(exts.begin(), exts.end(), ext) != exts.end();
}

RasterTransform raster_transform(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    return raster_transform(d.width, d.height, page, path);
}

RasterTransform raster_transform(int width, int height, const PageOptions& page, const std::string& path) {
    const PageLayout L = page_layout(width, height, page, path);
    RasterTransform t;
    // Output pixels per millimetre: the page at dpi, or 96 dpi image pixels scaled by dpi/96.
    const double px_per_mm = page.page.empty() ? (page.dpi / 96.0) / L.scale_mm : page.dpi / 25.4;
    const double w = std::max(1.0, std::round(L.page_w_mm * px_per_mm)), h = std::max(1.0, std::round(L.page_h_mm * px_per_mm));
    if (!(w * h <= max_raster_pixels)) {
        char size[64];
        std::snprintf(size, sizeof size, "%.0fx%.0f", w, h);
        throw Error("export", path, format_label(path) + " of " + size + " pixels is too large (lower --dpi)");
    }
    t.width = int(w), t.height = int(h);
    t.scale = L.scale_mm * px_per_mm;
    t.offset_x = L.offset_x_mm * px_per_mm;
    t.offset_y = L.offset_y_mm * px_per_mm;
    return t;
}

void check_raster_writer(const std::string& path) {
    std::string error;
    if (find_module(error).empty()) throw Error("export", path, error);
}

void load_raster_writer(const std::string& path) {
    const Module& m = raster_module();
    if (!m.encode) throw Error("export", path, m.error);
}

std::string raster_document(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    load_raster_writer(path);
    const RasterTransform t = raster_transform(d, page, path);
    const RgbImage img = rasterise(d, t);
    std::string description;
    for (const auto& [k, v] : merged_metadata(d.metadata, page.metadata)) description += k + ": " + v + "\n";
    const PeninkRasterImage image{img.width, img.height, img.rgb.data(), page.dpi, "penink", description.c_str()};
    const std::string format = lower_extension(path).substr(1);
    unsigned char* bytes = nullptr;
    std::size_t size = 0;
    char error[512] = "";
    if (raster_module().encode(format.c_str(), &image, &bytes, &size, error, sizeof error) != 0)
        throw Error("export", path, std::string("cannot write file (") + error + ")");
    const std::unique_ptr<unsigned char, decltype(&std::free)> owned(bytes, &std::free);
    return std::string(reinterpret_cast<const char*>(bytes), size);
}

void write_raster(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    write_file_atomically(path, raster_document(d, page, path));
}

}  // namespace penink
