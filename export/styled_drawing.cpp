// Styling a Drawing: width bands, colours, dashes, sublayers (styled_drawing.hpp).
#include "export/styled_drawing.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/error.hpp"

namespace penink {

namespace {

// Maps eye distances to t in [0, 1] between the style's near and far distances.
struct DistanceMap {
    double max_depth = 0.0, near = 0.0, far = 1.0;
    double t(double depth) const {
        if (max_depth <= 0.0) return 0.0;
        return std::clamp((depth / max_depth - near) / (far - near), 0.0, 1.0);
    }
};

double lerp(double a, double b, double t) { return a + (b - a) * t; }

bool uniform(const LayerStyle& s) { return s.width == s.width_far && s.opacity == s.opacity_far; }

int level_of(double t, int bands) {
    return bands <= 1 ? 0 : static_cast<int>(std::lround(t * (bands - 1)));
}

double level_t(int level, int bands) { return bands <= 1 ? 0.0 : double(level) / (bands - 1); }

double mean_depth(const Stroke& s, size_t from, size_t to) {  // [from, to]
    if (s.depth.size() < s.points.size()) return 0.0;
    double sum = 0.0;
    for (size_t i = from; i <= to; ++i) sum += s.depth[i];
    return sum / double(to - from + 1);
}

StyledPath band_path(const Stroke& s, size_t from, size_t to, int level, const LayerStyle& ls,
                     int bands) {
    StyledPath p;
    p.points.assign(s.points.begin() + from, s.points.begin() + to + 1);
    const double t = level_t(level, bands);
    p.width = lerp(ls.width, ls.width_far, t) * ls.weight_max;  // weight_min == weight_max here
    p.opacity = lerp(ls.opacity, ls.opacity_far, t);
    p.color = ls.color;
    p.dash = ls.dash;
    p.kind = s.kind;
    p.depth = mean_depth(s, from, to);
    p.strength = s.strength;
    return p;
}

// Splits a stroke into runs of segments of equal quantised level; runs share end points.
std::vector<StyledPath> split_bands(const Stroke& s, const LayerStyle& ls, const DistanceMap& dm,
                                    int bands) {
    const size_t n = s.points.size();
    const bool has_depth = s.depth.size() >= n;
    const int nb = uniform(ls) ? 1 : bands;
    const auto depth_at = [&](size_t i) { return has_depth ? double(s.depth[i]) : 0.0; };
    std::vector<StyledPath> out;
    if (n == 1) {
        out.push_back(band_path(s, 0, 0, level_of(dm.t(depth_at(0)), nb), ls, nb));
        return out;
    }
    size_t start = 0;
    int current = level_of(dm.t(0.5 * (depth_at(0) + depth_at(1))), nb);
    for (size_t j = 1; j + 1 < n; ++j) {
        const int level = level_of(dm.t(0.5 * (depth_at(j) + depth_at(j + 1))), nb);
        if (level == current) continue;
        out.push_back(band_path(s, start, j, current, ls, nb));
        start = j;
        current = level;
    }
    out.push_back(band_path(s, start, n - 1, current, ls, nb));
    return out;
}

// A stroke's length, px.
double stroke_length(const Stroke& s) {
    double total = 0.0;
    for (size_t i = 1; i < s.points.size(); ++i) total += glm::length(s.points[i] - s.points[i - 1]);
    return total;
}

// The arc lengths (ascending, strictly inside (0, total)) where a stroke of `total` px is cut for
// its taper: every taper / 4 px from either end up to where the taper stops (`taper` px in, or
// the middle of a shorter stroke) and there. None without a taper.
std::vector<double> taper_cuts(double total, double taper) {
    std::vector<double> cuts;
    if (!(taper > 0.0)) return cuts;
    const double zone = std::min(taper, 0.5 * total), step = taper / 4.0;
    for (int j = 1; j * step < zone; ++j) cuts.push_back(j * step), cuts.push_back(total - j * step);
    cuts.push_back(zone), cuts.push_back(total - zone);
    std::sort(cuts.begin(), cuts.end());
    std::vector<double> out;
    for (double c : cuts)
        if (c > 0.0 && c < total && (out.empty() || c - out.back() > 1e-6)) out.push_back(c);
    return out;
}

// Calls emit(point, depth, weight, arc length) for the points of `s` in order, with a point
// inserted at each of `cuts` (arc lengths, ascending) that is not within 1e-3 px of a vertex;
// depth and weight interpolated.
template <class Emit>
void densify(const Stroke& s, const std::vector<double>& cuts, Emit&& emit) {
    const size_t n = s.points.size();
    const auto depth_at = [&](size_t i) { return i < s.depth.size() ? double(s.depth[i]) : 0.0; };
    constexpr double apart = 1e-3;  // px: a cut this close to a vertex is the vertex
    size_t c = 0;
    double arc = 0.0;
    emit(s.points[0], depth_at(0), double(weight_at(s, 0)), 0.0);
    for (size_t i = 1; i < n; ++i) {
        const double len = glm::length(s.points[i] - s.points[i - 1]);
        for (; c < cuts.size() && cuts[c] < arc + len; ++c) {
            if (cuts[c] - arc < apart || arc + len - cuts[c] < apart) continue;
            const double f = (cuts[c] - arc) / len;
            emit(s.points[i - 1] + (s.points[i] - s.points[i - 1]) * float(f), depth_at(i - 1) + (depth_at(i) - depth_at(i - 1)) * f,
                 weight_at(s, i - 1) + (weight_at(s, i) - weight_at(s, i - 1)) * f, cuts[c]);
        }
        arc += len;
        emit(s.points[i], depth_at(i), double(weight_at(s, i)), arc);
    }
}

// One path per stroke, a width per point: distance (continuous), weight and taper; points
// inserted where the taper changes the width (taper_cuts).
StyledPath variable_path(const Stroke& s, const LayerStyle& ls, const DistanceMap& dm, int bands) {
    const bool tapered = ls.taper > 0.0 && !is_closed(s);
    const double total = stroke_length(s);
    const std::vector<double> cuts = taper_cuts(total, tapered ? ls.taper : 0.0);
    StyledPath p;
    p.color = ls.color;
    p.kind = s.kind;
    p.strength = s.strength;
    p.depth = mean_depth(s, 0, s.points.size() - 1);  // of the stroke's own points, as a band's
    p.opacity = lerp(ls.opacity, ls.opacity_far, level_t(level_of(dm.t(p.depth), bands), bands));
    p.points.reserve(s.points.size() + cuts.size());
    p.widths.reserve(s.points.size() + cuts.size());
    p.width = 0.0;
    densify(s, cuts, [&](glm::vec2 q, double depth, double weight, double arc) {
        double w = lerp(ls.width, ls.width_far, dm.t(depth)) * lerp(ls.weight_min, ls.weight_max, weight);
        if (tapered) w *= taper_factor(arc, total, ls.taper, ls.taper_min);
        p.points.push_back(q);
        p.widths.push_back(w);
        p.width = std::max(p.width, w);
    });
    return p;
}

size_t distance_group(double depth, double max_depth) {
    if (max_depth <= 0.0) return 0;
    const double f = depth / max_depth;
    return f < 1.0 / 3.0 ? 0 : (f < 2.0 / 3.0 ? 1 : 2);
}

StyledLayer style_layer(const Layer& layer, const Style& style, const DistanceMap& dm, LayerSplit split) {
    StyledLayer out;
    out.kind = layer.kind;
    out.name = std::string(layer_name(layer.kind));
    if (!style.no_fill) out.fill = layer.fill;
    out.fill_color = style.fill;
    out.style = style.layer(layer.kind);
    const LayerStyle& ls = out.style;
    if (split == LayerSplit::kind) out.groups.push_back({out.name, {}});
    else for (const char* g : {"-near", "-middle", "-far"}) out.groups.push_back({out.name + g, {}});
    if (!ls.visible) return out;
    const bool variable = variable_width(ls);
    for (const Stroke& s : layer.strokes) {
        if (s.points.empty()) continue;
        if (variable && s.points.size() >= 2) {
            StyledPath p = variable_path(s, ls, dm, uniform(ls) ? 1 : style.bands);
            const size_t g = split == LayerSplit::kind ? 0 : distance_group(p.depth, dm.max_depth);
            out.groups[g].paths.push_back(std::move(p));
            continue;
        }
        for (const StyledPath& p : split_bands(s, ls, dm, style.bands)) {
            const size_t g = split == LayerSplit::kind ? 0 : distance_group(p.depth, dm.max_depth);
            out.groups[g].paths.push_back(p);
        }
    }
    for (const Label& l : layer.labels)
        if (!l.text.empty() && l.size_px > 0.0f) out.labels.push_back({l.at, l.text, l.size_px, l.anchor, ls.color, l.kind});
    return out;
}

}  // namespace

bool variable_width(const LayerStyle& s) { return s.dash.empty() && (s.taper > 0.0 || s.weight_min != s.weight_max); }

LayerSplit parse_layer_split(const std::string& text) {
    if (text == "kind") return LayerSplit::kind;
    if (text == "kind+distance") return LayerSplit::kind_distance;
    throw Error("export", "", "unknown --layers value \"" + text + "\" (use kind or kind+distance)");
}

double max_depth(const Drawing& drawing) {
    double m = 0.0;
    for (const Layer& l : drawing.layers)
        for (const Stroke& s : l.strokes)
            for (float d : s.depth) m = std::max(m, double(d));
    return m;
}

StyledDrawing style_drawing(const Drawing& drawing, const Style& style, LayerSplit split) {
    StyledDrawing out;
    out.width = drawing.width;
    out.height = drawing.height;
    out.background = style.background;
    out.split = split;
    out.metadata = drawing.metadata;
    out.georeference = drawing.georeference;
    out.widths_mm = style.widths_mm;
    out.furniture = drawing.furniture;
    const DistanceMap dm{max_depth(drawing), style.near, style.far};
    for (size_t i = 0; i < drawing.layers.size(); ++i)
        out.layers[i] = style_layer(drawing.layers[i], style, dm, split);
    return out;
}

size_t path_count(const StyledDrawing& drawing) {
    size_t n = 0;
    for (const StyledLayer& l : drawing.layers)
        for (const StyledGroup& g : l.groups) n += g.paths.size();
    return n;
}

}  // namespace penink
