// PostScript / EPS writer (DSC 3.0): one page, y flipped by one `concat` so the body keeps
// image-pixel coordinates; each layer bracketed by `%%BeginLayer: NAME` / `%%EndLayer` and
// Illustrator-style `%AI5_BeginLayer ... (NAME) Ln ... %AI5_EndLayer--` markers. PostScript
// has no transparency: a stroke's colour is blended toward the background (default white)
// by its opacity.
#pragma once
#include <string>

#include "export/page.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// The PostScript text; `eps` selects the EPSF-3.0 header (no setpagedevice). Deterministic.
std::string ps_document(const StyledDrawing& drawing, const PageOptions& page, bool eps,
                        const std::string& path = "");


}  // namespace penink
