// PNG encoding of an 8-bit RGB image (export/rasterise.hpp) without an image library: IHDR,
// pHYs (dpi), tEXt (Software, Description, ...), IDAT (per-row adaptive filter, zlib level 6),
// IEND (PNG spec, ISO/IEC 15948). zlib is opened at run time (dlopen "libz.so.1") on the first
// PNG, so a penink process that writes no PNG loads nothing for it; OpenImageIO is not needed
// to write PNGs (its ~260 shared libraries cost ~0.2 s of start-up in every process).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "export/rasterise.hpp"

namespace penink {

// The PNG file's bytes. `text`: tEXt key/value pairs (Latin-1 keys of 1-79 characters).
// Throws std::runtime_error("zlib: ...") when zlib cannot be loaded or fails.
std::string encode_png(const RgbImage& image, double dpi,
                       const std::vector<std::pair<std::string, std::string>>& text);

}  // namespace penink
