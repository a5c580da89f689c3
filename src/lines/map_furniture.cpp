// Map furniture geometry (map_furniture.hpp).
#include "lines/map_furniture.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/helvetica_metrics.hpp"

namespace penink {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double foot_m = 0.3048, mile_ft = 5280.0;

// Fixed-point text with `decimals` decimals, trailing zeros removed (locale-independent).
std::string fixed_text(double v, int decimals) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
    std::string s(buf, r.ptr);
    if (s.find('.') != std::string::npos) {
        while (s.back() == '0') s.pop_back();
        if (s.back() == '.') s.pop_back();
    }
    return s == "-0" ? "0" : s;
}

// "100 000": an integer with its thousands apart.
std::string grouped(double v) {
    std::string digits = fixed_text(std::round(std::abs(v)), 0), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ' ';
        out += digits[i];
    }
    return (v < 0 ? "-" : "") + out;
}

// A number of the scale bar: as many decimals as its division needs.
std::string bar_number(double v, double step) {
    int decimals = 0;
    while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) > 1e-9)
        ++decimals;
    return fixed_text(v, decimals);
}

double text_width(const std::string& text, double size) { return helvetica_advance_em(text) * size; }

Stroke line(std::initializer_list<glm::dvec2> points, const char* kind) {
    Stroke s;
    for (const glm::dvec2& p : points) s.points.emplace_back(float(p.x), float(p.y));
    s.kind = kind;
    return s;
}

struct Box {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

Ring box_ring(const Box& b) {
    return {{float(b.x0), float(b.y0)}, {float(b.x1), float(b.y0)}, {float(b.x1), float(b.y1)}, {float(b.x0), float(b.y1)}};
}

// A layer's content drawn about (0, 0) and moved into place once its box is known.
void shift(Layer& layer, std::size_t strokes_from, std::size_t labels_from, glm::dvec2 by) {
    const glm::vec2 d(float(by.x), float(by.y));
    for (std::size_t i = strokes_from; i < layer.strokes.size(); ++i)
        for (glm::vec2& p : layer.strokes[i].points) p += d;
    for (std::size_t i = labels_from; i < layer.labels.size(); ++i) layer.labels[i].at += d;
}

Label label(glm::dvec2 at, std::string text, double size, TextAnchor anchor, const char* kind) {
    return Label{glm::vec2(float(at.x), float(at.y)), std::move(text), float(size), anchor, kind};
}

// Scales of the layout: millimetres on the page to image pixels, shrunk on small maps.
struct Layout {
    double px_per_mm = 1.0, factor = 1.0;
    double mm(double v) const { return v * px_per_mm * factor; }
};

void add_scale_bar(Layer& layer, const FurnitureFrame& f, const Layout& L, const MapFurnitureOptions& o, Box inner) {
    const double max_px = std::min(L.mm(40.0), 0.35 * (inner.x1 - inner.x0));
    const ScaleBarLength bar = scale_bar_length(ground_metres_per_px(f), max_px, o.imperial);
    if (!(bar.length_px > 0.0)) return;
    const double ts = f.scale_text_px * L.factor, h = L.mm(1.2), tick = L.mm(1.0), pad = L.mm(2.0);
    const double step = bar.length / bar.divisions, step_px = bar.length_px / bar.divisions;
    // the bar drawn with its left end at (0, 0), its baseline on y = 0
    const std::size_t s0 = layer.strokes.size(), l0 = layer.labels.size();
    layer.strokes.push_back(line({{0.0, 0.0}, {bar.length_px, 0.0}}, "scale-bar"));
    layer.strokes.push_back(line({{0.0, -h}, {bar.length_px, -h}}, "scale-bar-edge"));
    // labelled divisions: all when their labels fit between the ticks, else the ends (and the middle)
    double widest = 0.0;
    for (int i = 0; i <= bar.divisions; ++i) widest = std::max(widest, text_width(bar_number(i * step, step), ts));
    const bool all = widest + L.mm(1.5) <= step_px;
    for (int i = 0; i <= bar.divisions; ++i) {
        const double x = i * step_px;
        const bool labelled = ts > 0.0 && (all || i == 0 || i == bar.divisions || 2 * i == bar.divisions);
        layer.strokes.push_back(line({{x, 0.0}, {x, -h - (labelled ? tick : 0.0)}}, "scale-tick"));
        if (i < bar.divisions && i % 2 == 0)  // alternate divisions shaded with two pen lines
            for (double y : {-h / 3.0, -2.0 * h / 3.0})
                layer.strokes.push_back(line({{x, y}, {x + step_px, y}}, "scale-bar-shade"));
        if (labelled)
            layer.labels.push_back(label({x, -h - tick - L.mm(0.6)}, bar_number(i * step, step), ts, TextAnchor::middle,
                                         "scale-label"));
    }
    double right = bar.length_px, bottom = 0.0;
    const double top = -h - tick - L.mm(0.6) - (ts > 0.0 ? 0.75 * ts : 0.0);
    double left = 0.0;
    if (ts > 0.0) {
        layer.labels.push_back(label({bar.length_px + L.mm(1.5), 0.0}, bar.unit, ts, TextAnchor::start, "scale-unit"));
        right += L.mm(1.5) + text_width(bar.unit, ts);
        left = -0.5 * text_width("0", ts);
        right = std::max(right, bar.length_px + 0.5 * text_width(bar_number(bar.length, step), ts));
        if (f.map_scale > 0.0) {
            const std::string ratio = "1:" + grouped(f.map_scale);
            layer.labels.push_back(label({0.5 * bar.length_px, L.mm(1.2) + 0.75 * ts}, ratio, ts, TextAnchor::middle,
                                         "scale-ratio"));
            bottom = L.mm(1.2) + 0.75 * ts;
            left = std::min(left, 0.5 * bar.length_px - 0.5 * text_width(ratio, ts));
            right = std::max(right, 0.5 * bar.length_px + 0.5 * text_width(ratio, ts));
        }
    }
    // the panel in the bottom-left corner of the inner frame
    const glm::dvec2 by(inner.x0 + pad - left, inner.y1 - pad - bottom);
    shift(layer, s0, l0, by);
    layer.fill.push_back(box_ring({inner.x0, inner.y1 - (bottom - top) - 2.0 * pad, inner.x0 + (right - left) + 2.0 * pad, inner.y1}));
}

void add_north_arrow(Layer& layer, const FurnitureFrame& f, const Layout& L, Box inner) {
    const glm::dvec2 u = true_north_direction(f.geotransform, f.convergence_deg);
    const glm::dvec2 side(-u.y, u.x);
    const double length = L.mm(14.0), ts = f.arrow_text_px * L.factor, pad = L.mm(2.0);
    const double reach = 0.5 * length + (ts > 0.0 ? L.mm(1.0) + ts : 0.0);  // from the centre, any turn
    const double half = reach + pad;
    const glm::dvec2 c(inner.x1 - half, inner.y0 + half);
    const glm::dvec2 tip = c + u * (0.5 * length), tail = c - u * (0.5 * length);
    const double head = 0.3 * length, barb = 0.12 * length;
    const glm::dvec2 base = tip - u * head, left = base - side * barb, right = base + side * barb;
    layer.strokes.push_back(line({tail, tip}, "north-arrow"));
    layer.strokes.push_back(line({tip, left, right, tip}, "north-arrow-head"));
    for (double t : {0.25, 0.5, 0.75})  // one half of the head shaded, as on a compass
        layer.strokes.push_back(line({tip, base + (left - base) * t}, "north-arrow-shade"));
    if (ts > 0.0) {
        const glm::dvec2 at = tip + u * (L.mm(1.0) + 0.4 * ts);
        layer.labels.push_back(label({at.x, at.y + 0.36 * ts}, "N", ts, TextAnchor::middle, "north-label"));
    }
    layer.fill.push_back(box_ring({c.x - half, c.y - half, c.x + half, c.y + half}));
}

void add_title(Layer& layer, const FurnitureFrame& f, const Layout& L, const std::string& title, Box inner) {
    double ts = f.title_text_px * L.factor;
    if (title.empty() || !(ts > 0.0)) return;
    const double pad = L.mm(2.0), room = 0.6 * (inner.x1 - inner.x0) - 2.0 * pad;
    const double w = text_width(title, ts);
    if (w > room && room > 0.0) ts *= room / w;  // a long title set smaller to fit
    const double width = text_width(title, ts);
    layer.labels.push_back(label({inner.x0 + pad, inner.y0 + pad + 0.75 * ts}, title, ts, TextAnchor::start, "title"));
    layer.fill.push_back(box_ring({inner.x0, inner.y0, inner.x0 + width + 2.0 * pad, inner.y0 + ts + 2.0 * pad}));
}

// A nice interval of map coordinates: about four across the larger side's span.
double map_grid_interval(const FurnitureFrame& f) {
    const std::array<double, 6>& g = f.geotransform;
    const double w = f.width, h = f.height;
    const double span = std::max(std::hypot(g[1] * w, g[4] * w), std::hypot(g[2] * h, g[5] * h));
    return nice_length(span / 4.0);
}

bool overlaps(const Box& a, const Box& b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }

// The box of a ring (a panel).
Box ring_box(const Ring& r) {
    Box b{1e300, 1e300, -1e300, -1e300};
    for (const glm::vec2& p : r) b = {std::min(b.x0, double(p.x)), std::min(b.y0, double(p.y)), std::max(b.x1, double(p.x)), std::max(b.y1, double(p.y))};
    return b;
}

// Ticks and labels (each on a small panel) where they miss the other pieces' panels.
void add_grid(Layer& layer, const FurnitureFrame& f, const Layout& L, MapGrid grid, double inset, const std::vector<Box>& taken) {
    const double W = f.width, H = f.height;
    const glm::dvec2 corners[4] = {{inset, inset}, {W - inset, inset}, {W - inset, H - inset}, {inset, H - inset}};
    const double tick = L.mm(2.0), ts = f.grid_text_px * L.factor, clear = L.mm(3.0);
    std::array<std::vector<glm::dvec2>, 4> samples;
    double interval[2] = {0.0, 0.0};
    if (grid == MapGrid::map) {
        for (int e = 0; e < 4; ++e) {
            const glm::dvec2 a = corners[e], b = corners[(e + 1) % 4];
            const auto to_map = [&](glm::dvec2 p) {
                const std::array<double, 6>& g = f.geotransform;
                return glm::dvec2(g[0] + p.x * g[1] + p.y * g[2], g[3] + p.x * g[4] + p.y * g[5]);
            };
            samples[e] = {to_map(a), to_map(b)};  // affine: two samples are exact
        }
        interval[0] = interval[1] = map_grid_interval(f);
    } else {
        for (int e = 0; e < 4; ++e)
            if (f.edge_lon_lat[e].size() < 2) return;
        samples = f.edge_lon_lat;
        for (int axis = 0; axis < 2; ++axis) {
            double lo = 1e300, hi = -1e300;
            for (const auto& s : samples)
                for (const glm::dvec2& p : s) lo = std::min(lo, p[axis]), hi = std::max(hi, p[axis]);
            interval[axis] = graticule_interval_deg((hi - lo) / 4.0);
        }
    }
    for (int e = 0; e < 4; ++e) {
        const int axis = e % 2 == 0 ? 0 : 1;  // eastings (longitudes) on the top and bottom sides
        const glm::dvec2 a = corners[e], b = corners[(e + 1) % 4];
        const glm::dvec2 along = glm::normalize(b - a), in(-along.y, along.x);
        for (const EdgeTick& t : edge_ticks(a, b, samples[e], axis, interval[axis])) {
            if (glm::length(t.at - a) < clear || glm::length(t.at - b) < clear) continue;
            const glm::dvec2 end = t.at + in * tick;
            const Box tick_box{std::min(t.at.x, end.x), std::min(t.at.y, end.y), std::max(t.at.x, end.x), std::max(t.at.y, end.y)};
            if (std::any_of(taken.begin(), taken.end(), [&](const Box& other) { return overlaps(other, tick_box); })) continue;
            layer.strokes.push_back(line({t.at, end}, "grid-tick"));
            if (!(ts > 0.0)) continue;
            const std::string text = grid == MapGrid::map ? (interval[axis] >= 1.0 ? fixed_text(t.value, 0) : fixed_text(t.value, 3))
                                                          : lon_lat_label(t.value, axis == 0);
            const glm::dvec2 at = end + in * L.mm(0.8);
            Label l = e == 0   ? label({at.x, at.y + 0.72 * ts}, text, ts, TextAnchor::middle, "grid-label")
                      : e == 2 ? label(at, text, ts, TextAnchor::middle, "grid-label")
                               : label({at.x, at.y + 0.36 * ts}, text, ts, e == 1 ? TextAnchor::end : TextAnchor::start, "grid-label");
            const double w = text_width(text, ts), x0 = l.at.x - (e % 2 == 0 ? 0.5 * w : e == 1 ? w : 0.0);
            const double pad = L.mm(0.4);
            const Box box{x0 - pad, l.at.y - 0.75 * ts - pad, x0 + w + pad, l.at.y + 0.22 * ts + pad};
            if (std::any_of(taken.begin(), taken.end(), [&](const Box& other) { return overlaps(other, box); })) continue;
            layer.labels.push_back(std::move(l));
            layer.fill.push_back(box_ring(box));  // the label on paper, not on the hachures
        }
    }
}

}  // namespace

double nice_length(double at_most) {
    if (!(at_most > 0.0) || !std::isfinite(at_most)) return 0.0;
    const double p = std::pow(10.0, std::floor(std::log10(at_most)));
    for (double m : {5.0, 2.0, 1.0})
        if (m * p <= at_most * (1.0 + 1e-12)) return m * p;
    return p / 2.0;  // rounding in log10 at an exact power
}

ScaleBarLength scale_bar_length(double metres_per_px, double max_px, bool imperial) {
    ScaleBarLength bar;
    if (!(metres_per_px > 0.0) || !(max_px > 0.0)) return bar;
    const double max_m = metres_per_px * max_px;
    if (imperial) {
        const double max_ft = max_m / foot_m;
        if (max_ft >= mile_ft) bar.unit = "mi", bar.unit_m = foot_m * mile_ft;
        else bar.unit = "ft", bar.unit_m = foot_m;
    } else if (max_m >= 1000.0) {
        bar.unit = "km", bar.unit_m = 1000.0;
    }
    bar.length = nice_length(max_m / bar.unit_m);
    const double lead = bar.length / std::pow(10.0, std::floor(std::log10(bar.length) + 1e-9));
    bar.divisions = std::abs(lead - 2.0) < 1e-6 ? 4 : 5;
    bar.length_px = bar.length * bar.unit_m / metres_per_px;
    return bar;
}

double ground_metres_per_px(const FurnitureFrame& frame) {
    return std::hypot(frame.geotransform[1], frame.geotransform[4]) * frame.map_unit_m;
}

glm::dvec2 true_north_direction(const std::array<double, 6>& g, double convergence_deg) {
    const double gamma = convergence_deg * pi / 180.0;
    const glm::dvec2 v(-std::sin(gamma), std::cos(gamma));  // true north in map (east, north)
    const double det = g[1] * g[5] - g[2] * g[4];
    if (det == 0.0) return {0.0, -1.0};
    const glm::dvec2 d((g[5] * v.x - g[2] * v.y) / det, (-g[4] * v.x + g[1] * v.y) / det);
    return glm::normalize(d);
}

std::vector<EdgeTick> edge_ticks(glm::dvec2 from, glm::dvec2 to, const std::vector<glm::dvec2>& samples, int axis,
                                 double interval) {
    std::vector<EdgeTick> ticks;
    if (samples.size() < 2 || !(interval > 0.0)) return ticks;
    const double n = double(samples.size() - 1);
    for (std::size_t i = 0; i + 1 < samples.size(); ++i) {
        const double a = samples[i][axis], b = samples[i + 1][axis];
        if (!std::isfinite(a) || !std::isfinite(b) || a == b) continue;
        const double lo = std::min(a, b), hi = std::max(a, b);
        // multiples in this piece, its end left to the next piece but on the last; at most 1000
        const double k0 = std::ceil(lo / interval), k1 = std::floor(hi / interval);
        for (double k = k0; k <= k1 && k - k0 < 1000.0; ++k) {
            const double v = k * interval;
            if (v == b && i + 2 < samples.size()) continue;  // the next piece's start
            const double t = (double(i) + (v - a) / (b - a)) / n;
            ticks.push_back({from + (to - from) * t, v});
        }
    }
    std::stable_sort(ticks.begin(), ticks.end(), [&](const EdgeTick& p, const EdgeTick& q) {  // along the segment
        return glm::dot(p.at - from, to - from) < glm::dot(q.at - from, to - from);
    });
    return ticks;
}

double graticule_interval_deg(double at_most) {
    const double steps[] = {1.0 / 60, 2.0 / 60, 5.0 / 60, 10.0 / 60, 15.0 / 60, 30.0 / 60,
                            1.0,      2.0,      5.0,      10.0,      15.0,      30.0,      45.0};
    double best = steps[0];
    for (double s : steps)
        if (s <= at_most * (1.0 + 1e-9)) best = s;
    return best;
}

std::string lon_lat_label(double degrees, bool longitude) {
    const char hemisphere = longitude ? (degrees < 0 ? 'W' : 'E') : (degrees < 0 ? 'S' : 'N');
    const long total = std::lround(std::abs(degrees) * 3600.0);  // seconds
    const long d = total / 3600, m = (total / 60) % 60, s = total % 60;
    std::string out = std::to_string(d) + "\xC2\xB0";
    if (m || s) out += std::to_string(m) + "'";
    if (s) out += std::to_string(s) + "\"";
    return out + hemisphere;
}

void add_map_furniture(Drawing& drawing, const FurnitureFrame& f, const MapFurnitureOptions& o) {
    drawing.furniture = true;
    if (f.width <= 0 || f.height <= 0 || !(f.mm_per_px > 0.0)) return;
    Layout L;
    L.px_per_mm = 1.0 / f.mm_per_px;
    L.factor = std::clamp(std::min(f.width, f.height) * f.mm_per_px / 150.0, 0.4, 1.0);
    const double inset = std::clamp(f.neatline_inset_px, 0.0, 0.25 * std::min(f.width, f.height));
    if (o.neatline) {
        const double W = f.width - inset, H = f.height - inset;
        drawing.layer(LayerKind::neatline)
            .strokes.push_back(line({{inset, inset}, {W, inset}, {W, H}, {inset, H}, {inset, inset}}, "neatline"));
    }
    const double m = L.mm(4.0);
    const Box inner{inset + m, inset + m, f.width - inset - m, f.height - inset - m};
    if (inner.x1 > inner.x0 && inner.y1 > inner.y0) {  // room inside the frame
        if (o.scale_bar) add_scale_bar(drawing.layer(LayerKind::scale_bar), f, L, o, inner);
        if (o.north_arrow) add_north_arrow(drawing.layer(LayerKind::north_arrow), f, L, inner);
        add_title(drawing.layer(LayerKind::title), f, L, o.title, inner);
    }
    std::vector<Box> panels;  // the grid keeps clear of them
    for (LayerKind k : {LayerKind::scale_bar, LayerKind::north_arrow, LayerKind::title})
        for (const Ring& r : drawing.layer(k).fill) panels.push_back(ring_box(r));
    if (o.grid != MapGrid::none) add_grid(drawing.layer(LayerKind::grid), f, L, o.grid, inset, panels);
}

}  // namespace penink
