// PostScript/PDF operator text (pen_ops.hpp).
#include "export/pen_ops.hpp"

#include <cmath>

#include "core/helvetica_metrics.hpp"
#include "export/page.hpp"
#include "export/stroke_outline.hpp"

namespace penink {

namespace {

void append_xy(std::string& o, glm::vec2 p, const char* op) {
    append_number(o, p.x);
    o += ' ';
    append_number(o, p.y);
    o += op;
}

}  // namespace

void append_polyline_ops(std::string& o, const std::vector<glm::vec2>& pts) {
    if (pts.empty()) return;
    append_xy(o, pts[0], " m\n");
    if (pts.size() == 1) append_xy(o, pts[0], " l\n");
    for (size_t i = 1; i < pts.size(); ++i) append_xy(o, pts[i], " l\n");
}

void append_outline_ops(std::string& o, const StyledPath& p) {
    const std::vector<glm::vec2> outline = stroke_outline(p.points, p.widths);
    if (outline.empty()) return;
    append_xy(o, outline[0], " m\n");
    for (size_t i = 1; i < outline.size(); ++i) append_xy(o, outline[i], " l\n");
    o += "h\n";
}

void append_ring_ops(std::string& o, const std::vector<Ring>& rings) {
    for (const Ring& r : rings) {
        if (r.size() < 3) continue;
        append_xy(o, r[0], " m\n");
        for (size_t i = 1; i < r.size(); ++i) append_xy(o, r[i], " l\n");
        o += "h\n";
    }
}

void append_rgb_op(std::string& o, Rgb c, const char* op) {
    for (std::uint8_t v : {c.r, c.g, c.b}) {
        append_number(o, v / 255.0, 3);
        o += ' ';
    }
    o += op;
    o += '\n';
}

void append_dash_op(std::string& o, const std::vector<double>& dash) {
    o += '[';
    for (size_t i = 0; i < dash.size(); ++i) {
        if (i) o += ' ';
        append_number(o, dash[i], 3);
    }
    o += "] 0 d\n";
}

Rgb blend_toward(Rgb c, Rgb paper, double opacity) {
    const auto mix = [&](std::uint8_t v, std::uint8_t p) {
        return static_cast<std::uint8_t>(std::lround(v * opacity + p * (1.0 - opacity)));
    };
    return Rgb{mix(c.r, paper.r), mix(c.g, paper.g), mix(c.b, paper.b)};
}

void append_layer_fill(std::string& o, const StyledLayer& l) {
    if (l.fill.empty()) return;
    append_rgb_op(o, l.fill_color, "rg");
    append_ring_ops(o, l.fill);
    o += "f*\n";
}

void append_page_setup(std::string& o, const StyledDrawing& d, const PageLayout& L, const char* rect_fill) {
    const double w = L.page_w_mm * points_per_mm, h = L.page_h_mm * points_per_mm;
    if (!(d.background == Rgb{255, 255, 255})) {
        append_rgb_op(o, d.background, "rg");
        o += "0 0 " + format_number(w, 3) + " " + format_number(h, 3) + " " + rect_fill + "\n";
    }
    const double k = L.scale_mm * points_per_mm;
    o += format_number(k, 6) + " 0 0 " + format_number(-k, 6) + " " +
         format_number(L.offset_x_mm * points_per_mm, 4) + " " +
         format_number(h - L.offset_y_mm * points_per_mm, 4) + " cm\n1 J 1 j\n";
}

double label_start_x(const StyledLabel& label) {
    const double w = helvetica_advance_em(label.text) * label.size_px;
    return label.at.x - (label.anchor == TextAnchor::middle ? 0.5 * w : label.anchor == TextAnchor::end ? w : 0.0);
}

std::string label_string(const StyledLabel& label) {
    std::string o = "(";
    for (const char ch : latin1_text(label.text)) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c == '(' || c == ')' || c == '\\') o += '\\';
        if (c >= 32 && c < 127) {
            o += ch;
        } else {
            o += '\\';
            o += char('0' + (c >> 6));
            o += char('0' + ((c >> 3) & 7));
            o += char('0' + (c & 7));
        }
    }
    return o + ")";
}

}  // namespace penink
