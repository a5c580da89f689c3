// Operator text shared by the PostScript and PDF writers: the body of both uses PDF operator
// names (m l S h f* w RG rg d J j q Q cm), which the PostScript prolog defines as procedures.
// Coordinates are image pixels (the page transform is set once with `cm`).
#pragma once
#include <string>
#include <vector>

#include "export/page.hpp"
#include "export/styled_drawing.hpp"

namespace penink {

// "x y m x y l ... " for a polyline (a single point becomes a zero-length segment = a dot).
void append_polyline_ops(std::string& out, const std::vector<glm::vec2>& points);
// A variable-width path's outline (stroke_outline.hpp) as "x y m ... h" (for a nonzero fill, f).
void append_outline_ops(std::string& out, const StyledPath& path);
// Closed rings "x y m ... h" for an even-odd fill (rings with < 3 points are skipped).
void append_ring_ops(std::string& out, const std::vector<Ring>& rings);
// "r g b OP" with components in [0, 1], 3 decimals.
void append_rgb_op(std::string& out, Rgb c, const char* op);
// "[a b] 0 d" (an empty array is solid).
void append_dash_op(std::string& out, const std::vector<double>& dash);
// The layer's surface mask (even-odd fill in its colour), when it has one.
void append_layer_fill(std::string& out, const StyledLayer& layer);
// Page background (when not white; `rect_fill` is "re f" in PDF, "rectfill" in PS) and the
// transform from image pixels (y down) to page points (y up), with round caps and joins.
void append_page_setup(std::string& out, const StyledDrawing& d, const PageLayout& layout, const char* rect_fill);
// `c` blended toward the paper colour by `opacity` (how PostScript shows opacity: exact for
// a stroke over the bare page, default white).
Rgb blend_toward(Rgb c, Rgb paper, double opacity);

// The x where a label's text starts (its anchor moved back by Helvetica's advance of its text:
// core/helvetica_metrics.hpp), image pixels.
double label_start_x(const StyledLabel& label);
// The label's text as a literal string of WinAnsi / ISO Latin-1 bytes, "(...)" with ( ) \ and
// bytes outside printable ASCII escaped (octal): the same syntax in PDF and PostScript.
std::string label_string(const StyledLabel& label);

// Pen state of a content stream, to emit only changed operators.
struct PenState {
    bool valid = false;
    Rgb color;
    std::string width, opacity;  // formatted, so equal text means no change
    std::vector<double> dash;
};

}  // namespace penink
