// The drawing handed from the lines stage to export: strokes (polylines in image pixels,
// origin top-left, y down, with per-point eye distance in metres / world units) grouped in
// the nine named drawing layers of conventions.md, bottom to top, plus the surface mask polygons;
// above them the five map furniture layers (neatline, grid, scale bar, north arrow, title:
// lines/map_furniture.hpp), written only for maps (Drawing::furniture), which also hold text
// labels and white panels (fill rings) under their lines.
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

enum class LayerKind {
    surface, coastline, hachures, ridges, creases, pels, textures, feature_edges, silhouettes,
    neatline, grid, scale_bar, north_arrow, title  // map furniture
};

inline constexpr std::size_t layer_count = 14;
inline constexpr std::size_t drawing_layer_count = 9;  // the layers every drawing writes
inline constexpr std::array<LayerKind, layer_count> all_layers = {
    LayerKind::surface, LayerKind::coastline, LayerKind::hachures, LayerKind::ridges, LayerKind::creases, LayerKind::pels,
    LayerKind::textures, LayerKind::feature_edges, LayerKind::silhouettes, LayerKind::neatline, LayerKind::grid,
    LayerKind::scale_bar, LayerKind::north_arrow, LayerKind::title};

// The map furniture layers: neatline, grid, scale-bar, north-arrow, title.
inline constexpr bool is_furniture(LayerKind kind) { return static_cast<std::size_t>(kind) >= drawing_layer_count; }

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
    std::vector<float> weight{};
};

// True when the stroke has >= 3 points and its first and last points are equal.
inline bool is_closed(const Stroke& s) { return s.points.size() >= 3 && s.points.front() == s.points.back(); }

// Point i's weight; 1 when the stroke carries none.
inline float weight_at(const Stroke& s, std::size_t i) { return i < s.weight.size() ? s.weight[i] : 1.0f; }

// A closed ring of the surface mask (even-odd fill), image pixels.
using Ring = std::vector<glm::vec2>;

// Where a label's baseline point lies along its text: its start, middle or end.
enum class TextAnchor { start, middle, end };

// One line of text (map furniture): Helvetica at size_px (the em, image pixels), its baseline
// through `at` (image pixels), horizontal; UTF-8 (writers keep what Latin-1 can say).
struct Label {
    glm::vec2 at{0.0f, 0.0f};
    std::string text;
    float size_px = 10.0f;
    TextAnchor anchor = TextAnchor::start;
    std::string kind;  // data-kind: "title", "scale-label", ...
};

struct Layer {
    LayerKind kind = LayerKind::surface;
    std::vector<Stroke> strokes;
    // The surface's white mask hiding what is behind; on a furniture layer, the paper-coloured
    // panels under its lines and labels.
    std::vector<Ring> fill;
    std::vector<Label> labels;  // furniture layers only
};

struct Drawing {
    int width = 0, height = 0;  // image size in pixels
    std::array<Layer, layer_count> layers;  // indexed by LayerKind, bottom to top
    std::map<std::string, std::string> metadata;  // source, camera, light, parameters
    std::optional<Georeference> georeference;     // plan views only: pixel -> map transform
    // The furniture layers are written (plan views: empty when the map has no furniture);
    // otherwise only the nine drawing layers are.
    bool furniture = false;

    Drawing();
    Layer& layer(LayerKind k) { return layers[static_cast<size_t>(k)]; }
    const Layer& layer(LayerKind k) const { return layers[static_cast<size_t>(k)]; }
};

}  // namespace penink
