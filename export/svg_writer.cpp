// SVG writer (svg_writer.hpp).
#include "export/svg_writer.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/polyline_simplify.hpp"
#include "export/stroke_outline.hpp"

namespace penink {

namespace {

void attr(std::string& o, const char* name, const std::string& value) {
    o += ' ';
    o += name;
    o += "=\"";
    o += value;
    o += '"';
}

void attr_num(std::string& o, const char* name, double value, int decimals) {
    o += ' ';
    o += name;
    o += "=\"";
    append_number(o, value, decimals);
    o += '"';
}

std::string dash_text(const std::vector<double>& dash) {
    std::string s;
    for (size_t i = 0; i < dash.size(); ++i) {
        if (i) s += ',';
        append_number(s, dash[i], 3);
    }
    return s;
}

void append_point(std::string& o, glm::vec2 p, int decimals = 2) {
    append_number(o, p.x, decimals);
    o += ' ';
    append_number(o, p.y, decimals);
}

void header(std::string& o, const StyledDrawing& d, const PageLayout& L, const PageOptions& page) {
    o += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
    o += "<!-- Created with penink (pen-and-ink landscapes) -->\n<svg";
    attr(o, "xmlns", "http://www.w3.org/2000/svg");
    attr(o, "xmlns:inkscape", "http://www.inkscape.org/namespaces/inkscape");
    attr(o, "xmlns:sodipodi", "http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd");
    attr(o, "xmlns:rdf", "http://www.w3.org/1999/02/22-rdf-syntax-ns#");
    attr(o, "xmlns:cc", "http://creativecommons.org/ns#");
    attr(o, "xmlns:dc", "http://purl.org/dc/elements/1.1/");
    attr(o, "xmlns:penink", "urn:penink");
    attr(o, "version", "1.1");
    attr(o, "width", format_number(L.page_w_mm, 4) + "mm");
    attr(o, "height", format_number(L.page_h_mm, 4) + "mm");
    const double vw = L.page_w_mm / L.scale_mm, vh = L.page_h_mm / L.scale_mm;
    attr(o, "viewBox", format_number(-L.offset_x_mm / L.scale_mm, 4) + " " +
                           format_number(-L.offset_y_mm / L.scale_mm, 4) + " " +
                           format_number(vw, 4) + " " + format_number(vh, 4));
    o += ">\n";
    o += "<sodipodi:namedview id=\"namedview\" pagecolor=\"" + rgb_hex(d.background) +
         "\" inkscape:document-units=\"mm\"/>\n";
    const std::map<std::string, std::string> meta = merged_metadata(d.metadata, page.metadata);
    const std::string title = drawing_title(meta, "");  // none without the scene's
    if (!title.empty()) o += "<title id=\"title\">" + xml_escape(title) + "</title>\n";
    if (const std::string desc = drawing_description(meta); !desc.empty())
        o += "<desc id=\"desc\">" + xml_escape(desc) + "</desc>\n";
    // Dublin Core in RDF, as Inkscape's Document Properties read and write it, and penink's own
    // parameters (its namespace declared on the root).
    o += "<metadata id=\"metadata\">\n<rdf:RDF>\n<cc:Work rdf:about=\"\">\n<dc:format>image/svg+xml</dc:format>\n";
    o += "<dc:type rdf:resource=\"http://purl.org/dc/dcmitype/StillImage\"/>\n";
    if (!title.empty()) o += "<dc:title>" + xml_escape(title) + "</dc:title>\n";
    if (const std::string desc = drawing_description(meta); !desc.empty())
        o += "<dc:description>" + xml_escape(desc) + "</dc:description>\n";
    if (const auto it = meta.find("source"); it != meta.end()) o += "<dc:source>" + xml_escape(it->second) + "</dc:source>\n";
    if (const auto it = meta.find("generator"); it != meta.end())
        o += "<dc:creator><cc:Agent><dc:title>" + xml_escape(it->second) + "</dc:title></cc:Agent></dc:creator>\n";
    // inside the RDF, which Inkscape keeps as it is (elsewhere it warns "unknown type" for each)
    for (const auto& [k, v] : meta)
        o += "<penink:param name=\"" + xml_escape(k) + "\">" + xml_escape(v) + "</penink:param>\n";
    o += "</cc:Work>\n</rdf:RDF>\n</metadata>\n";
    if (!(d.background == Rgb{255, 255, 255})) {
        o += "<rect id=\"background\"";
        attr_num(o, "x", -L.offset_x_mm / L.scale_mm, 4);
        attr_num(o, "y", -L.offset_y_mm / L.scale_mm, 4);
        attr_num(o, "width", vw, 4);
        attr_num(o, "height", vh, 4);
        attr(o, "fill", rgb_hex(d.background));
        o += "/>\n";
    }
}

void surface_fill(std::string& o, const StyledLayer& l) {
    if (l.fill.empty()) return;
    o += "<path fill=\"" + rgb_hex(l.fill_color) + "\" fill-rule=\"evenodd\" stroke=\"none\" d=\"";
    for (const Ring& r : l.fill) {
        if (r.size() < 3) continue;
        o += 'M';
        append_point(o, r[0]);
        o += " L";
        for (size_t i = 1; i < r.size(); ++i) {
            if (i > 1) o += ' ';
            append_point(o, r[i]);
        }
        o += 'Z';
    }
    o += "\"/>\n";
}

void append_points_d(std::string& o, const std::vector<glm::vec2>& pts, int decimals = 2) {
    o += 'M';
    append_point(o, pts[0], decimals);
    o += " L";
    if (pts.size() == 1) append_point(o, pts[0], decimals);
    for (size_t i = 1; i < pts.size(); ++i) {
        if (i > 1) o += ' ';
        append_point(o, pts[i], decimals);
    }
}

// Decimals of a filled outline's coordinates (image pixels): the fewest (1 to 3) whose rounding,
// half the last place, stays within outline_rounding_mm on the page (under a 1200 dpi printer's
// dot, 0.021 mm): 1 at 96 dpi (0.05 px = 0.013 mm).
constexpr double outline_rounding_mm = 0.02;
int outline_decimals(const PageLayout& L) {
    int d = 1;
    while (d < 3 && 0.5 * std::pow(10.0, -d) * L.scale_mm > outline_rounding_mm) ++d;
    return d;
}

// What a variable-width path writes besides its outline: its centre line simplified (the
// points the taper inserted, and those within centre_tolerance_px of the chord, left out), the
// width at each of those vertices, and Inkscape's power-stroke offset points ("t,half-width |
// ..."; t the simplified centre line's path time, the segment index plus the fraction of its
// length, written to within 0.05 px along it, and 0.01 from either end) at the knots of the
// width profile: the points a Douglas-Peucker of half-width against arc length keeps within
// knot_tolerance_px (linear between knots; Inkscape draws a smooth curve through them).
constexpr float centre_tolerance_px = 0.05f;
constexpr float knot_tolerance_px = 0.05f;

struct PowerStroke {
    std::vector<std::size_t> centre;  // indices of the centre line's vertices in the path's points
    std::string offsets;
};

PowerStroke power_stroke(const StyledPath& p) {
    PowerStroke out;
    const size_t n = p.points.size();
    out.centre = douglas_peucker_indices(p.points, centre_tolerance_px);
    std::vector<double> arc(n, 0.0);
    for (size_t i = 1; i < n; ++i) arc[i] = arc[i - 1] + double(glm::length(p.points[i] - p.points[i - 1]));
    std::vector<glm::vec2> profile(n);  // (arc, 0): the knots' error is the half-width's alone
    std::vector<float> half(n);
    for (size_t i = 0; i < n; ++i) profile[i] = glm::vec2(float(arc[i]), 0.0f), half[i] = float(0.5 * p.widths[i]);
    const double last = double(out.centre.size() - 1);
    // t's decimals: the fewest (2 to 5) that place a knot within 0.05 px along the longest segment
    double longest = 0.0;
    for (size_t j = 0; j + 1 < out.centre.size(); ++j) longest = std::max(longest, arc[out.centre[j + 1]] - arc[out.centre[j]]);
    int t_decimals = 2;
    while (t_decimals < 5 && 0.5 * std::pow(10.0, -t_decimals) * longest > 0.05) ++t_decimals;
    size_t seg = 0;
    for (size_t k : douglas_peucker_indices(profile, knot_tolerance_px, half, knot_tolerance_px)) {
        while (seg + 1 < out.centre.size() - 1 && out.centre[seg + 1] <= k) ++seg;
        const size_t a = out.centre[seg], b = out.centre[std::min(seg + 1, out.centre.size() - 1)];
        const double t = b > a && arc[b] > arc[a] ? double(seg) + (arc[k] - arc[a]) / (arc[b] - arc[a]) : double(seg);
        if (!out.offsets.empty()) out.offsets += " | ";
        append_number(out.offsets, std::clamp(t, 0.01, std::max(0.01, last - 0.01)), t_decimals);
        out.offsets += ',';
        append_number(out.offsets, 0.5 * p.widths[k], 2);
    }
    return out;
}

// The power-stroke effects of a document: one <inkscape:path-effect> per distinct set of offset
// points, shared by every path that has it (Inkscape forks a shared effect when one of its paths
// is edited), numbered in order of first use. The parameters every Inkscape version defaults
// alike (is_visible true, sort_points true, not_jump false, interpolator_beta 0.2, scale_width 1,
// miter_limit 4) are not written; those whose defaults changed between versions are.
struct PathEffects {
    std::string defs;
    std::unordered_map<std::string, std::size_t> ids;

    std::string id_for(const std::string& offsets) {
        const auto [it, added] = ids.emplace(offsets, ids.size());
        const std::string id = "powerstroke-" + std::to_string(it->second);
        if (added)
            defs += "<inkscape:path-effect effect=\"powerstroke\" id=\"" + id + "\" lpeversion=\"1\" offset_points=\"" + offsets +
                    "\" interpolator_type=\"CentripetalCatmullRom\" start_linecap_type=\"round\" end_linecap_type=\"round\" "
                    "linejoin_type=\"round\"/>\n";
        return id;
    }
};

// A variable-width path: the filled outline (d, what every viewer draws), its centre line
// (inkscape:original-d) and widths, and Inkscape's power-stroke effect that keeps it a stroke.
void outline_path(std::string& o, PathEffects& effects, const StyledPath& p, const LayerStyle& ls, int decimals) {
    const PowerStroke ps = power_stroke(p);
    const std::string effect_id = effects.id_for(ps.offsets);
    o += "<path d=\"";
    const std::vector<glm::vec2> outline = stroke_outline(p.points, p.widths);
    append_points_d(o, outline, decimals);
    o += "Z\"";
    if (!(p.color == ls.color)) attr(o, "fill", rgb_hex(p.color));
    if (p.opacity < 1.0) attr_num(o, "opacity", p.opacity, 3);
    attr(o, "inkscape:path-effect", "#" + effect_id);
    std::vector<glm::vec2> centre;
    centre.reserve(ps.centre.size());
    for (size_t i : ps.centre) centre.push_back(p.points[i]);
    o += " inkscape:original-d=\"";
    append_points_d(o, centre);
    o += '"';
    attr(o, "data-kind", xml_escape(p.kind));
    attr_num(o, "data-depth", p.depth, 2);
    attr_num(o, "data-strength", p.strength, 3);
    o += " data-widths=\"";
    for (size_t k = 0; k < ps.centre.size(); ++k) {
        if (k) o += ' ';
        append_number(o, p.widths[ps.centre[k]], 2);
    }
    o += "\"/>\n";
}

// A single-width path; in a layer of variable-width paths (filled, `filled`) its stroke and no
// fill written on it.
void stroke_path(std::string& o, const StyledPath& p, const LayerStyle& ls, bool filled) {
    o += "<path d=\"M";
    append_point(o, p.points[0]);
    o += " L";
    if (p.points.size() == 1) append_point(o, p.points[0]);
    for (size_t i = 1; i < p.points.size(); ++i) {
        if (i > 1) o += ' ';
        append_point(o, p.points[i]);
    }
    o += '"';
    if (filled) attr(o, "fill", "none");
    if (filled || !(p.color == ls.color)) attr(o, "stroke", rgb_hex(p.color));
    if (format_number(p.width, 3) != format_number(ls.width, 3)) attr_num(o, "stroke-width", p.width, 3);
    if (p.opacity < 1.0) attr_num(o, "opacity", p.opacity, 3);
    if (p.dash != ls.dash) attr(o, "stroke-dasharray", p.dash.empty() ? "none" : dash_text(p.dash));
    attr(o, "data-kind", xml_escape(p.kind));
    attr_num(o, "data-depth", p.depth, 2);
    attr_num(o, "data-strength", p.strength, 3);
    o += "/>\n";
}

void layer_open(std::string& o, const std::string& name) {
    o += "<g inkscape:groupmode=\"layer\" inkscape:label=\"" + name + "\" id=\"" + name + "\"";
}

// A label as SVG text, editable in Inkscape: Helvetica (or the viewer's metric-compatible sans).
void text_label(std::string& o, const StyledLabel& t) {
    o += "<text";
    attr_num(o, "x", t.at.x, 2);
    attr_num(o, "y", t.at.y, 2);
    attr_num(o, "font-size", t.size_px, 3);
    attr(o, "font-family", "Helvetica, Arial, sans-serif");
    if (t.anchor != TextAnchor::start) attr(o, "text-anchor", t.anchor == TextAnchor::middle ? "middle" : "end");
    attr(o, "fill", rgb_hex(t.color));
    attr(o, "stroke", "none");
    attr(o, "data-kind", xml_escape(t.kind));
    o += '>';
    o += xml_escape(t.text);
    o += "</text>\n";
}

// A layer's <g>: the common attributes of its paths, the pen's stroke; a layer of variable-width
// paths (their outlines filled) fills in the pen's colour instead and strokes none.
void layer(std::string& o, const StyledLayer& l, bool split, PathEffects& effects, int outline_decimals) {
    const bool filled = variable_width(l.style);
    layer_open(o, l.name);
    attr(o, "fill", filled ? rgb_hex(l.style.color) : "none");
    attr(o, "stroke", filled ? "none" : rgb_hex(l.style.color));
    attr_num(o, "stroke-width", l.style.width, 3);
    attr(o, "stroke-linecap", "round");
    attr(o, "stroke-linejoin", "round");
    if (!l.style.dash.empty()) attr(o, "stroke-dasharray", dash_text(l.style.dash));
    o += ">\n";
    surface_fill(o, l);
    for (const StyledGroup& g : l.groups) {
        if (split) {
            layer_open(o, g.name);
            o += ">\n";
        }
        for (const StyledPath& p : g.paths) {
            if (p.widths.empty()) stroke_path(o, p, l.style, filled);
            else outline_path(o, effects, p, l.style, outline_decimals);
        }
        if (split) o += "</g>\n";
    }
    for (const StyledLabel& t : l.labels) text_label(o, t);
    o += "</g>\n";
}

}  // namespace

namespace {

// Length of the well-formed UTF-8 sequence at text[i] that XML 1.0 allows (no surrogates, no
// U+FFFE/U+FFFF, nothing over U+10FFFF), 0 when there is none.
std::size_t xml_char_length(const std::string& text, std::size_t i) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
    const unsigned char c = b(0);
    std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (n == 0 || i + n > text.size()) return 0;
    std::uint32_t cp = n == 1 ? c : n == 2 ? c & 0x1F : n == 3 ? c & 0x0F : c & 0x07;
    for (std::size_t k = 1; k < n; ++k) {
        if ((b(k) >> 6) != 0x2) return 0;
        cp = (cp << 6) | (b(k) & 0x3F);
    }
    const std::uint32_t min[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < min[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF) || cp == 0xFFFE || cp == 0xFFFF) return 0;
    if (cp < 0x20 && cp != '\t' && cp != '\n' && cp != '\r') return 0;  // not XML 1.0 characters
    return n;
}

}  // namespace

std::string xml_escape(const std::string& text) {
    std::string s;
    s.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t n = xml_char_length(text, i);
        if (n == 0) {  // a byte that is not UTF-8, or a control character: U+FFFD
            s += "\xEF\xBF\xBD";
            ++i;
            continue;
        }
        switch (text[i]) {
            case '&': s += "&amp;"; break;
            case '<': s += "&lt;"; break;
            case '>': s += "&gt;"; break;
            case '"': s += "&quot;"; break;
            case '\'': s += "&apos;"; break;
            default: s.append(text, i, n);
        }
        i += n;
    }
    return s;
}

std::string svg_document(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    const PageLayout L = page_layout(d.width, d.height, page, path);
    std::string o;
    o.reserve(4096 + path_count(d) * 64);
    header(o, d, L, page);
    PathEffects effects;
    std::string layers;  // the power-stroke effects go in <defs>, before the layers
    layers.reserve(path_count(d) * 64);
    for (const StyledLayer& l : d.layers)
        if (layer_written(d, l)) layer(layers, l, d.split == LayerSplit::kind_distance, effects, outline_decimals(L));
    if (!effects.defs.empty()) o += "<defs id=\"defs\">\n" + effects.defs + "</defs>\n";
    o += layers;
    o += "</svg>\n";
    return o;
}

}  // namespace penink
