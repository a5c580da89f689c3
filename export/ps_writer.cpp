// PostScript / EPS writer (ps_writer.hpp).
#include "export/ps_writer.hpp"

#include <algorithm>
#include <cmath>

#include "core/helvetica_metrics.hpp"
#include "export/pen_ops.hpp"
#include "core/version.hpp"

namespace penink {

namespace {

// Procedures named like the PDF operators, so pen_ops text works in both formats; Lb/Ln/LB
// are Illustrator's layer operators, defined here as no-ops so any interpreter accepts them.
constexpr const char* prolog =
    "%%BeginProlog\n"
    "%%BeginResource: procset penink 1.0 0\n"
    "/penink_dict 24 dict def penink_dict begin\n"
    "/m /moveto load def /l /lineto load def /h /closepath load def\n"
    "/S /stroke load def /f* /eofill load def /w /setlinewidth load def\n"
    "/RG /setrgbcolor load def /rg /setrgbcolor load def /d /setdash load def\n"
    "/J /setlinecap load def /j /setlinejoin load def /q /gsave load def /Q /grestore load def\n"
    "/cm { 6 array astore concat } bind def\n"
    "/Lb { 10 { pop } repeat } bind def /Ln { pop } bind def /LB { } bind def\n"
    "end\n"
    "%%EndResource\n"
    "%%EndProlog\n";

// A PostScript string literal: ( ) and \ escaped, non-printing bytes dropped.
std::string ps_string(const std::string& s) {
    std::string o = "(";
    for (char c : s) {
        if (c == '(' || c == ')' || c == '\\') o += '\\';
        if (static_cast<unsigned char>(c) >= 32 && static_cast<unsigned char>(c) < 127) o += c;
    }
    return o + ")";
}

// One-line comment text (no line breaks, printable ASCII).
std::string comment_text(const std::string& s) {
    std::string o;
    for (char c : s) o += (static_cast<unsigned char>(c) >= 32 && static_cast<unsigned char>(c) < 127) ? c : ' ';
    return o;
}

// The ink's box on the page, points from the bottom-left: every fill ring and stroke (grown by
// half its width), then the page margin all round, within the page; the whole page when there is
// no ink.
void ink_box_pt(const StyledDrawing& d, const PageLayout& L, double margin_mm, double box[4]) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;  // mm from the top-left
    auto add = [&](glm::vec2 p, double half_px) {
        const double x = L.offset_x_mm + double(p.x) * L.scale_mm, y = L.offset_y_mm + double(p.y) * L.scale_mm;
        const double r = half_px * L.scale_mm;
        x0 = std::min(x0, x - r), y0 = std::min(y0, y - r), x1 = std::max(x1, x + r), y1 = std::max(y1, y + r);
    };
    for (const StyledLayer& l : d.layers) {
        for (const Ring& r : l.fill)
            for (const glm::vec2& p : r) add(p, 0.0);
        for (const StyledGroup& g : l.groups)
            for (const StyledPath& path : g.paths)
                for (const glm::vec2& p : path.points) add(p, 0.5 * path.width);
        for (const StyledLabel& t : l.labels) {  // the text's advance, from its descent to its cap height
            const float left = float(label_start_x(t)), right = float(left + helvetica_advance_em(t.text) * t.size_px);
            add({left, t.at.y - 0.75f * float(t.size_px)}, 0.0), add({right, t.at.y + 0.25f * float(t.size_px)}, 0.0);
        }
    }
    if (x0 > x1) x0 = 0.0, y0 = 0.0, x1 = L.page_w_mm, y1 = L.page_h_mm;
    x0 = std::max(0.0, x0 - margin_mm), y0 = std::max(0.0, y0 - margin_mm);
    x1 = std::min(L.page_w_mm, x1 + margin_mm), y1 = std::min(L.page_h_mm, y1 + margin_mm);
    box[0] = x0 * points_per_mm, box[1] = (L.page_h_mm - y1) * points_per_mm;
    box[2] = x1 * points_per_mm, box[3] = (L.page_h_mm - y0) * points_per_mm;
}

bool has_labels(const StyledDrawing& d) {
    for (const StyledLayer& l : d.layers)
        if (layer_written(d, l) && !l.labels.empty()) return true;
    return false;
}

// Helvetica re-encoded as ISO Latin-1 with ASCII's own quote, hyphen and grave (so that its codes
// mean what PDF's WinAnsiEncoding and latin1_text mean).
constexpr const char* label_font =
    "/Helvetica findfont dup length dict begin\n"
    "{ 1 index /FID ne { def } { pop pop } ifelse } forall\n"
    "/Encoding ISOLatin1Encoding 256 array copy dup 39 /quotesingle put dup 45 /hyphen put dup 96 /grave put def\n"
    "currentdict end /PeninkHelvetica exch definefont pop\n";

bool has_outlines(const StyledDrawing& d) {
    for (const StyledLayer& l : d.layers)
        for (const StyledGroup& g : l.groups)
            for (const StyledPath& p : g.paths)
                if (!p.widths.empty()) return true;
    return false;
}

void header(std::string& o, const StyledDrawing& d, const PageLayout& L, bool eps,
            const PageOptions& page, const std::string& path) {
    const double w = L.page_w_mm * points_per_mm, h = L.page_h_mm * points_per_mm;
    o += eps ? "%!PS-Adobe-3.0 EPSF-3.0\n" : "%!PS-Adobe-3.0\n";
    o += "%%Creator: penink " + std::string(penink_version) + "\n%%Title: " + comment_text(drawing_title(d.metadata, path)) + "\n";
    // A placed EPS brings the ink (and the margin) only; a PostScript page is the page.
    double box[4] = {0.0, 0.0, w, h};
    if (eps) ink_box_pt(d, L, page.margin_mm, box);
    o += "%%BoundingBox: " + std::to_string(int(std::floor(box[0] + 1e-6))) + " " +
         std::to_string(int(std::floor(box[1] + 1e-6))) + " " + std::to_string(int(std::ceil(box[2] - 1e-6))) + " " +
         std::to_string(int(std::ceil(box[3] - 1e-6))) + "\n";
    o += "%%HiResBoundingBox: " + format_number(box[0], 3) + " " + format_number(box[1], 3) + " " +
         format_number(box[2], 3) + " " + format_number(box[3], 3) + "\n";
    o += "%%LanguageLevel: 2\n%%DocumentData: Clean7Bit\n%%Pages: 1\n";
    if (has_labels(d)) o += "%%DocumentNeededResources: font Helvetica\n";
    if (!eps) o += "%%DocumentMedia: penink " + format_number(w, 3) + " " + format_number(h, 3) + " 0 () ()\n";
    o += "%%EndComments\n";
    for (const auto& [k, v] : merged_metadata(d.metadata, page.metadata))
        o += "% penink " + comment_text(k) + ": " + comment_text(v) + "\n";
    o += prolog;
    o += "%%BeginSetup\npenink_dict begin\n";
    if (has_outlines(d)) o += "/f /fill load def\n";  // variable-width paths: filled outlines
    if (has_labels(d)) o += std::string("%%IncludeResource: font Helvetica\n") + label_font;
    if (!eps) o += "<< /PageSize [" + format_number(w, 3) + " " + format_number(h, 3) + "] >> setpagedevice\n";
    o += "%%EndSetup\n%%Page: 1 1\n%%BeginPageSetup\nq\n";
    append_page_setup(o, d, L, "rectfill");
    o += "%%EndPageSetup\n";
}

void set_pen(std::string& o, PenState& pen, const StyledPath& p, Rgb paper) {
    const Rgb c = blend_toward(p.color, paper, p.opacity);
    const std::string width = format_number(p.width, 3);
    if (!pen.valid || !(pen.color == c)) append_rgb_op(o, c, "RG");
    if (!pen.valid || pen.width != width) o += width + " w\n";
    if (!pen.valid || pen.dash != p.dash) append_dash_op(o, p.dash);
    pen = PenState{true, c, width, "", p.dash};
}

void layer_body(std::string& o, const StyledLayer& l, bool split, Rgb paper) {
    append_layer_fill(o, l);
    PenState pen;
    for (const StyledGroup& g : l.groups) {
        if (split) o += "%%BeginLayer: " + g.name + "\n";
        for (const StyledPath& p : g.paths) {
            if (!p.widths.empty()) {  // the outline filled (nonzero), in the colour the pen would have
                const Rgb c = blend_toward(p.color, paper, p.opacity);
                if (!pen.valid || !(pen.color == c)) append_rgb_op(o, c, "rg");
                if (pen.valid) pen.color = c;  // rg and RG are one setrgbcolor in PostScript
                append_outline_ops(o, p);
                o += "f\n";
                continue;
            }
            set_pen(o, pen, p, paper);
            append_polyline_ops(o, p.points);
            o += "S\n";
        }
        if (split) o += "%%EndLayer\n";
    }
    for (const StyledLabel& t : l.labels) {  // upright text in the page's y-down pixels
        o += "q\n";
        append_rgb_op(o, t.color, "rg");
        o += "/PeninkHelvetica " + format_number(t.size_px, 3) + " selectfont\n";
        o += format_number(label_start_x(t), 3) + " " + format_number(t.at.y, 3) + " translate 1 -1 scale 0 0 moveto " +
             label_string(t) + " show\nQ\n";
    }
}

void layer(std::string& o, const StyledLayer& l, bool split, Rgb paper) {
    o += "%%BeginLayer: " + l.name + "\n%AI5_BeginLayer\n1 1 1 1 0 0 -1 0 0 0 Lb\n" +
         ps_string(l.name) + " Ln\nq\n";
    layer_body(o, l, split, paper);
    o += "Q\nLB\n%AI5_EndLayer--\n%%EndLayer\n";
}

}  // namespace

std::string ps_document(const StyledDrawing& d, const PageOptions& page, bool eps,
                        const std::string& path) {
    const PageLayout L = page_layout(d.width, d.height, page, path);
    std::string o;
    o.reserve(8192 + path_count(d) * 64);
    header(o, d, L, eps, page, path);
    for (const StyledLayer& l : d.layers)
        if (layer_written(d, l)) layer(o, l, d.split == LayerSplit::kind_distance, d.background);
    o += "Q\nshowpage\n%%PageTrailer\n%%Trailer\nend\n%%EOF\n";
    return o;
}

}  // namespace penink
