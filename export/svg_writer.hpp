// SVG 1.1 writer with Inkscape layers: viewBox in image pixels, width/height in millimetres
// (page or image size at dpi), one <g inkscape:groupmode="layer"> per layer in conventions.md
// order (sublayers near/middle/far with --layers kind+distance), surface mask as an even-odd
// white path, strokes as round-capped paths carrying data-kind/data-depth/data-strength;
// variable-width strokes as their filled outlines with Inkscape's power stroke (the centre line,
// its widths and offset points: styles/README.md, "How the formats show a style").
#pragma once
#include <string>

#include "export/page.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// The SVG text (byte-deterministic). `path` only names the file in errors.
std::string svg_document(const StyledDrawing& drawing, const PageOptions& page,
                         const std::string& path = "");


// XML text escaping (& < > " '); bytes that are not UTF-8 and characters XML 1.0 does not allow
// (control characters but tab, newline and carriage return; surrogates, U+FFFE, U+FFFF) become
// U+FFFD, so text from any input (file names, CRS names, titles) makes a well-formed document.
std::string xml_escape(const std::string& text);

}  // namespace penink
