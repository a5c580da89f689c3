// The interface between export/ and the raster writer module penink_oiio.so (export/oiio/): a
// plain C function that encodes an 8-bit RGB image into a file format with OpenImageIO, in
// memory. The module is dlopen()ed on the first raster output only (raster_writer.cpp), so a
// process that writes only vector files never loads OpenImageIO and its ~260 shared libraries.
#pragma once
#include <cstddef>

extern "C" {

struct PeninkRasterImage {
    int width, height;
    const unsigned char* rgb;  // row-major, 3 bytes per pixel, top row first
    double dpi;                // written as ResolutionUnit "in" + XResolution/YResolution
    const char* software;      // "Software" metadata
    const char* description;   // "ImageDescription" metadata ("" for none)
};

// Encodes `image` in the format OpenImageIO associates with `format` (a file extension without
// the dot, e.g. "png", "tif", "jpg", "webp", "exr"). On success returns 0 and sets *bytes to a
// malloc()ed buffer of *size bytes (the caller frees it with free()). On failure returns
// nonzero and writes a one-line reason, NUL-terminated, into error[0..error_size).
using PeninkRasterEncodeFn = int (*)(const char* format, const PeninkRasterImage* image, unsigned char** bytes,
                                     std::size_t* size, char* error, std::size_t error_size);

// The module's exported symbol.
#define PENINK_RASTER_ENCODE_SYMBOL "penink_raster_encode"

}  // extern "C"
