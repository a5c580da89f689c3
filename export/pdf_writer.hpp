// Hand-written PDF 1.5 writer: one page (MediaBox in points from the page layout), the body in
// image pixels under one flipping `cm`, every layer (and near/middle/far sublayer) an Optional
// Content Group named exactly like the layer, listed in /OCProperties /D /Order bottom to top;
// opacity via ExtGState /CA. A georeferenced plan view's page (one with a CRS) carries a
// geospatial viewport: /VP, a /GEO measure over the drawn image (Adobe, "Supplement to ISO
// 32000", ExtensionLevel 3, sec. 8.8.1; part of PDF 2.0), which GDAL and GIS tools read.
// Uncompressed, no CreationDate: byte-deterministic.
#pragma once
#include <string>

#include "export/page.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// The PDF bytes. `path` only names the file in errors and the /Title.
std::string pdf_document(const StyledDrawing& drawing, const PageOptions& page,
                         const std::string& path = "");


// A PDF literal string "(...)" with ( ) \ escaped and bytes outside printable ASCII as \ooo.
std::string pdf_string(const std::string& text);

}  // namespace penink
