// PDF 1.5 writer with optional content groups (pdf_writer.hpp).
#include "export/pdf_writer.hpp"

#include <cctype>
#include <cstdio>
#include <map>

#include "core/version.hpp"
#include "export/pen_ops.hpp"

namespace penink {

namespace {

// Optional content groups in drawing order: (object number, name, parent index or -1).
struct Ocg {
    int object;
    std::string name;
    int parent;
};

std::vector<Ocg> make_ocgs(const StyledDrawing& d, int first_object) {
    std::vector<Ocg> ocgs;
    const bool split = d.split == LayerSplit::kind_distance;
    for (const StyledLayer& l : d.layers) {
        if (!layer_written(d, l)) continue;
        const int parent = static_cast<int>(ocgs.size());
        ocgs.push_back({first_object + parent, l.name, -1});
        if (split)
            for (const StyledGroup& g : l.groups)
                ocgs.push_back({first_object + int(ocgs.size()), g.name, parent});
    }
    return ocgs;
}

std::string ref(int object) { return std::to_string(object) + " 0 R"; }

// Opacity text -> ExtGState resource name (/GS0, /GS1, ... in first-use order).
using AlphaNames = std::map<std::string, std::string>;

void set_pen(std::string& o, PenState& pen, const StyledPath& p, AlphaNames& alphas) {
    const std::string width = format_number(p.width, 3), alpha = format_number(p.opacity, 3);
    if (!pen.valid || !(pen.color == p.color)) append_rgb_op(o, p.color, "RG");
    if (!pen.valid || pen.width != width) o += width + " w\n";
    if (!pen.valid || pen.dash != p.dash) append_dash_op(o, p.dash);
    if (pen.valid ? pen.opacity != alpha : alpha != "1") {
        auto it = alphas.find(alpha);
        if (it == alphas.end()) it = alphas.emplace(alpha, "GS" + std::to_string(alphas.size())).first;
        o += "/" + it->second + " gs\n";
    }
    pen = PenState{true, p.color, width, alpha, p.dash};
}

// A variable-width path: its outline filled in the pen's colour (the fill's opacity /ca, its own
// ExtGState, keyed "f" + opacity).
void fill_outline(std::string& o, PenState& fill, const StyledPath& p, AlphaNames& alphas) {
    const std::string alpha = format_number(p.opacity, 3);
    if (!fill.valid || !(fill.color == p.color)) append_rgb_op(o, p.color, "rg");
    if (fill.valid ? fill.opacity != alpha : alpha != "1") {
        auto it = alphas.find("f" + alpha);
        if (it == alphas.end()) it = alphas.emplace("f" + alpha, "GS" + std::to_string(alphas.size())).first;
        o += "/" + it->second + " gs\n";
    }
    fill = PenState{true, p.color, "", alpha, {}};
    append_outline_ops(o, p);
    o += "f\n";
}

void group_body(std::string& o, const StyledGroup& g, PenState& pen, PenState& fill, AlphaNames& alphas) {
    for (const StyledPath& p : g.paths) {
        if (!p.widths.empty()) {  // fill colour and /ca leave the stroke's RG and /CA as they are
            fill_outline(o, fill, p, alphas);
            continue;
        }
        set_pen(o, pen, p, alphas);
        append_polyline_ops(o, p.points);
        o += "S\n";
    }
}

std::string content(const StyledDrawing& d, const PageLayout& L, const std::vector<Ocg>& ocgs,
                    AlphaNames& alphas) {
    std::string o;
    o.reserve(4096 + path_count(d) * 64);
    o += "q\n";
    append_page_setup(o, d, L, "re f");
    size_t oc = 0;
    for (const StyledLayer& l : d.layers) {
        if (!layer_written(d, l)) continue;
        o += "/OC /oc" + std::to_string(oc++) + " BDC\nq\n";
        append_layer_fill(o, l);
        PenState pen, fill;
        for (const StyledGroup& g : l.groups) {
            const bool split = d.split == LayerSplit::kind_distance;
            if (split) o += "/OC /oc" + std::to_string(oc++) + " BDC\n";
            group_body(o, g, pen, fill, alphas);
            if (split) o += "EMC\n";
        }
        for (const StyledLabel& t : l.labels) {  // Helvetica (/Fh), upright in the y-down pixels
            o += "q\n";
            append_rgb_op(o, t.color, "rg");
            o += "BT /Fh " + format_number(t.size_px, 3) + " Tf 1 0 0 -1 " + format_number(label_start_x(t), 3) + " " +
                 format_number(t.at.y, 3) + " Tm " + label_string(t) + " Tj ET\nQ\n";
        }
        o += "Q\nEMC\n";
    }
    o += "Q\n";
    return o;
}

std::string oc_properties(const std::vector<Ocg>& ocgs) {
    std::string all, order;
    for (size_t i = 0; i < ocgs.size(); ++i) {
        const bool first_child = ocgs[i].parent >= 0 && (i == 0 || ocgs[i - 1].parent < 0);
        const bool last_child = ocgs[i].parent >= 0 && (i + 1 == ocgs.size() || ocgs[i + 1].parent < 0);
        if (i) all += ' ', order += ' ';
        all += ref(ocgs[i].object);
        if (first_child) order += '[';
        order += ref(ocgs[i].object);
        if (last_child) order += ']';
    }
    return "/OCProperties << /OCGs [" + all + "] /D << /Name (penink layers) /Order [" + order +
           "] /ON [" + all + "] /OFF [] >> >>";
}

std::string info_dict(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    const std::string creator = std::string("penink ") + penink_version;
    std::string o = "<< /Producer " + pdf_string(creator) + " /Creator " + pdf_string(creator) + " /Title " +
                    pdf_string(drawing_title(d.metadata, path));
    if (const std::string subject = drawing_description(d.metadata); !subject.empty())
        o += " /Subject " + pdf_string(subject);
    for (const auto& [k, v] : merged_metadata(d.metadata, page.metadata)) {
        std::string name = "/penink_";
        for (char c : k) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
        o += " " + name + " " + pdf_string(v);
    }
    return o + " >>";
}

// The page's /VP entry: one viewport over the drawn image (BBox in points, y up) whose
// geospatial measure (Adobe, "Supplement to ISO 32000", ExtensionLevel 3, sec. 8.8.1) ties the BBox corners
// (LPTS, unit square, y up) to their latitude/longitude (GPTS) in the CRS (GCS); "" when the
// drawing has no CRS or no geographic corners.
std::string viewport_entry(const StyledDrawing& d, const PageLayout& L) {
    if (!d.georeference || d.georeference->crs_wkt.empty() || d.georeference->corner_lat_lon.size() != 4) return "";
    const Georeference& g = *d.georeference;
    const double x0 = L.offset_x_mm * points_per_mm, x1 = (L.offset_x_mm + d.width * L.scale_mm) * points_per_mm;
    const double y1 = (L.page_h_mm - L.offset_y_mm) * points_per_mm, y0 = y1 - d.height * L.scale_mm * points_per_mm;
    std::string gpts;
    for (const glm::dvec2& p : g.corner_lat_lon)  // top-left, bottom-left, bottom-right, top-right
        gpts += (gpts.empty() ? "" : " ") + exact_decimal(p.x) + " " + exact_decimal(p.y);
    std::string gcs = std::string("<< /Type ") + (g.geographic ? "/GEOGCS" : "/PROJCS");
    if (g.epsg > 0) gcs += " /EPSG " + std::to_string(g.epsg);
    gcs += " /WKT " + pdf_string(g.crs_wkt) + " >>";
    return " /VP [<< /Type /Viewport /Name (penink map) /BBox [" + format_number(x0, 4) + " " + format_number(y0, 4) +
           " " + format_number(x1, 4) + " " + format_number(y1, 4) +
           "] /Measure << /Type /Measure /Subtype /GEO /Bounds [0 0 0 1 1 1 1 0] /GPTS [" + gpts +
           "] /LPTS [0 1 0 0 1 0 1 1] /GCS " + gcs + " >> >>]";
}

struct PdfBuilder {
    std::string out = "%PDF-1.5\n%\xe2\xe3\xcf\xd3\n";
    std::vector<size_t> offsets;  // by object number - 1
    void object(const std::string& body) {
        offsets.push_back(out.size());
        out += std::to_string(offsets.size()) + " 0 obj\n" + body + "\nendobj\n";
    }
    std::string finish(int root, int info) {
        const size_t xref = out.size();
        out += "xref\n0 " + std::to_string(offsets.size() + 1) + "\n0000000000 65535 f \n";
        char line[32];
        for (size_t off : offsets) {
            std::snprintf(line, sizeof line, "%010zu 00000 n \n", off);
            out += line;
        }
        out += "trailer\n<< /Size " + std::to_string(offsets.size() + 1) + " /Root " + ref(root) +
               " /Info " + ref(info) + " >>\nstartxref\n" + std::to_string(xref) + "\n%%EOF\n";
        return std::move(out);
    }
};

}  // namespace

std::string pdf_string(const std::string& text) {
    std::string o = "(";
    for (char ch : text) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c == '(' || c == ')' || c == '\\') o += '\\';
        if (c >= 32 && c < 127) {
            o += ch;
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\%03o", c);
            o += buf;
        }
    }
    return o + ")";
}

std::string pdf_document(const StyledDrawing& d, const PageOptions& page, const std::string& path) {
    const PageLayout L = page_layout(d.width, d.height, page, path);
    const std::vector<Ocg> ocgs = make_ocgs(d, 6);
    bool labels = false;  // Helvetica's font object (after the OCGs) only when there is text
    for (const StyledLayer& l : d.layers) labels = labels || (layer_written(d, l) && !l.labels.empty());
    const int font_object = 6 + int(ocgs.size());
    AlphaNames alphas;
    const std::string stream = content(d, L, ocgs, alphas);
    std::string gs, props;
    for (const auto& [key, name] : alphas)
        gs += " /" + name + (key[0] == 'f' ? " << /Type /ExtGState /ca " + key.substr(1) : " << /Type /ExtGState /CA " + key) +
              " >>";
    for (size_t i = 0; i < ocgs.size(); ++i) props += " /oc" + std::to_string(i) + " " + ref(ocgs[i].object);
    const std::string box = "[0 0 " + format_number(L.page_w_mm * points_per_mm, 3) + " " +
                            format_number(L.page_h_mm * points_per_mm, 3) + "]";
    PdfBuilder b;
    b.object("<< /Type /Catalog /Pages 2 0 R " + oc_properties(ocgs) + " >>");
    b.object("<< /Type /Pages /Kids [3 0 R] /Count 1 >>");
    b.object("<< /Type /Page /Parent 2 0 R /MediaBox " + box + viewport_entry(d, L) + " /Resources << /ExtGState <<" + gs +
             " >>" + (labels ? " /Font << /Fh " + ref(font_object) + " >>" : std::string()) + " /Properties <<" + props + " >> >> /Contents 4 0 R >>");
    b.object("<< /Length " + std::to_string(stream.size()) + " >>\nstream\n" + stream + "endstream");
    b.object(info_dict(d, page, path));
    for (const Ocg& g : ocgs) b.object("<< /Type /OCG /Name " + pdf_string(g.name) + " >>");
    if (labels) b.object("<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>");
    return b.finish(1, 5);
}

}  // namespace penink
