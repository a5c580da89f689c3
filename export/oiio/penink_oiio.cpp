// penink_oiio.so: the raster writer module (export/raster_module.hpp). Encodes penink's 8-bit
// RGB rasters with OpenImageIO into memory (an IOProxy), with resolution and text metadata;
// the only code of penink that links OpenImageIO.
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "export/raster_module.hpp"

namespace {

void set_error(char* error, std::size_t error_size, std::string what) {
    if (!error || error_size == 0) return;
    for (char& c : what)
        if (c == '\n' || c == '\r') c = ' ';  // errors are one line
    while (!what.empty() && what.back() == ' ') what.pop_back();
    std::strncpy(error, what.c_str(), error_size - 1);
    error[error_size - 1] = '\0';
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int penink_raster_encode(const char* format,
                                                                          const PeninkRasterImage* image,
                                                                          unsigned char** bytes, std::size_t* size,
                                                                          char* error, std::size_t error_size) {
    try {
        // A name with the extension makes OpenImageIO pick its writer for it (".tif" -> tiff).
        const std::string name = std::string("penink.") + format;
        // OpenImageIO's debug lines (Debian's prints them) stay off penink's stderr: what a writer
        // cannot do reaches the caller as an error, and the null DateTime below is one it notes
        OIIO::attribute("debug", 0);
        std::vector<unsigned char> buffer;
        OIIO::Filesystem::IOVecOutput proxy(buffer);
        auto out = OIIO::ImageOutput::create(name, &proxy);
        if (!out) {
            set_error(error, error_size, "OpenImageIO has no writer for ." + std::string(format) + " (" + OIIO::geterror() + ")");
            return 1;
        }
        OIIO::ImageSpec spec(image->width, image->height, 3, OIIO::TypeDesc::UINT8);
        if (std::strcmp(out->format_name(), "openexr") == 0) spec.set_format(OIIO::TypeDesc::HALF);
        spec.attribute("ResolutionUnit", "in");
        spec.attribute("XResolution", float(image->dpi));
        spec.attribute("YResolution", float(image->dpi));
        spec.attribute("PixelAspectRatio", 1.0f);
        spec.attribute("Software", image->software ? image->software : "penink");
        if (image->description && *image->description) spec.attribute("ImageDescription", image->description);
        // No clock in the file: OpenImageIO's TIFF and OpenEXR writers stamp the time of writing
        // where DateTime is not given, so the same drawing written a second later differed; a
        // DateTime whose string is null is given but written by none of them (no tag at all).
        const char* no_date = nullptr;
        spec.attribute("DateTime", OIIO::TypeDesc::STRING, &no_date);
        OIIO::Filesystem::IOProxy* proxy_ptr = &proxy;
        spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_ptr);
        out->set_ioproxy(&proxy);
        if (std::strcmp(out->format_name(), "jpeg") == 0) spec.attribute("Compression", "jpeg:95");
        if (std::strcmp(out->format_name(), "tiff") == 0) spec.attribute("Compression", "zip");
        if (!out->open(name, spec)) {
            set_error(error, error_size, out->geterror());
            return 1;
        }
        if (!out->write_image(OIIO::TypeDesc::UINT8, image->rgb) || !out->close()) {
            set_error(error, error_size, out->geterror());
            return 1;
        }
        out.reset();
        *size = buffer.size();
        *bytes = static_cast<unsigned char*>(std::malloc(buffer.empty() ? 1 : buffer.size()));
        if (!*bytes) {
            set_error(error, error_size, "out of memory");
            return 1;
        }
        if (!buffer.empty()) std::memcpy(*bytes, buffer.data(), buffer.size());
        return 0;
    } catch (const std::exception& e) {
        set_error(error, error_size, e.what());
        return 1;
    }
}
