// The drawing handed from the lines stage to export: strokes (polylines in image pixels,
// origin top-left, y down, with per-point eye distance in metres / world units) grouped in
// the eight named layers of conventions.md, bottom to top, plus the surface mask polygons.
#pragma once
#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "core/georeference.hpp"

namespace penink {

enum class LayerKind { surface, coastline, ridges, creases, pels, textures, feature_edges, silhouettes };

inline constexpr std::size_t layer_count = 8;
inline constexpr std::array<LayerKind, layer_count> all_layers = {
    LayerKind::surface, LayerKind::coastline, LayerKind::ridges, LayerKind::creases, LayerKind::pels,
    LayerKind::textures, LayerKind::feature_edges, LayerKind::silhouettes};

// Exact layer name used in SVG ids/labels, PS/EPS comments and PDF OCG names.
std::string_view layer_name(LayerKind kind);

// One pen stroke: an open polyline (closed when the first point is repeated at the end).
struct Stroke {
    std::vector<glm::vec2> points;  // image pixels
    std::vector<float> depth;       // eye distance per point (same size as points), metres
    float strength = 1.0f;          // score that selected the line (rs for creases), >= 0
    std::string kind;               // data-kind: "silhouette", "outline", "crease", ...
    // Weight per point in [0, 1] (same size as points), or empty: none. The stroke's place in its
    // layer's hierarchy of weight (creases by flow, silhouettes by the depth gap behind them:
    // lines/stroke_weight.hpp); the style maps it to a width between its weight_min and 1 times
    // the layer's width (styles/README.md). Any layer's strokes may carry it.
    std::vector<float> weight;
};

// True when the stroke has >= 3 points and its first and last points are equal.
inline bool is_closed(const Stroke& s) { return s.points.size() >= 3 && s.points.front() == s.points.back(); }

// Point i's weight; 1 when the stroke carries none.
inline float weight_at(const Stroke& s, std::size_t i) { return i < s.weight.size() ? s.weight[i] : 1.0f; }

// A closed ring of the surface mask (even-odd fill), image pixels.
using Ring = std::vector<glm::vec2>;

struct Layer {
    LayerKind kind = LayerKind::surface;
    std::vector<Stroke> strokes;
    std::vector<Ring> fill;  // only the surface layer fills: the white mask hiding what is behind
};

struct Drawing {
    int width = 0, height = 0;  // image size in pixels
    std::array<Layer, layer_count> layers;  // indexed by LayerKind, bottom to top
    std::map<std::string, std::string> metadata;  // source, camera, light, parameters
    std::optional<Georeference> georeference;     // plan views only: pixel -> map transform

    Drawing();
    Layer& layer(LayerKind k) { return layers[static_cast<size_t>(k)]; }
    const Layer& layer(LayerKind k) const { return layers[static_cast<size_t>(k)]; }
};

}  // namespace penink
