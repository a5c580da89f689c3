// A finished Drawing with its style applied (thinning by distance, overshoot, repeats and
// sketchiness happen before, in the lines stage: lines/finish_drawing.hpp): every stroke split into width bands
// (runs of segments whose distance-interpolated width/opacity falls in the same quantised
// level), coloured and dashed. Coordinates stay in image pixels (origin top-left, y down);
// depth is eye distance in metres. All writers (SVG, PS/EPS, PDF, PNG) consume this one
// structure, so every format carries identical geometry, layers and order.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/drawing.hpp"
#include "core/stroke_taper.hpp"
#include "export/style.hpp"

namespace penink {

// kind: one group per layer; kind_distance: sublayers near / middle / far (depth thirds).
enum class LayerSplit { kind, kind_distance };

// "kind" or "kind+distance" (the CLI's --layers); throws Error("export", "", "unknown --layers
// value \"X\" (use kind or kind+distance)").
LayerSplit parse_layer_split(const std::string& text);

struct StyledPath {
    std::vector<glm::vec2> points;  // image pixels, >= 1 point (1 point = a dot)
    double width = 1.0;             // pixels
    double opacity = 1.0;
    Rgb color;
    std::vector<double> dash;  // pixels, empty = solid
    std::string kind;          // data-kind
    double depth = 0.0;        // mean eye distance of the band's points, metres
    double strength = 0.0;     // the stroke's score
    // Variable width (a tapered or weighted stroke, styles/README.md): one width per point, px;
    // `width` is then their largest. Empty: one width. Writers draw such a path as its filled
    // outline (stroke_outline.hpp); the points stay its centre line.
    std::vector<double> widths;
};

// A label in the layer's colour (core/drawing.hpp's Label): Helvetica, size_px the em.
struct StyledLabel {
    glm::vec2 at{0.0f, 0.0f};  // baseline point, image pixels
    std::string text;          // UTF-8
    double size_px = 10.0;
    TextAnchor anchor = TextAnchor::start;
    Rgb color;
    std::string kind;  // data-kind
};

// A drawable group: the whole layer, or one of its near/middle/far sublayers.
struct StyledGroup {
    std::string name;  // "ridges" or "ridges-near", ...
    std::vector<StyledPath> paths;
};

struct StyledLayer {
    LayerKind kind = LayerKind::surface;
    std::string name;             // layer_name(kind)
    std::vector<Ring> fill;       // surface mask rings (even-odd), drawn below the strokes
    Rgb fill_color{255, 255, 255};
    LayerStyle style;             // the style the paths were made with (common attributes)
    std::vector<StyledGroup> groups;  // 1 (LayerSplit::kind) or 3 (kind_distance)
    std::vector<StyledLabel> labels;  // furniture layers: text above the paths
};

struct StyledDrawing {
    int width = 0, height = 0;  // image pixels
    Rgb background{255, 255, 255};
    LayerSplit split = LayerSplit::kind;
    std::array<StyledLayer, layer_count> layers;  // bottom to top, conventions.md order
    std::map<std::string, std::string> metadata;
    std::optional<Georeference> georeference;  // plan views: image pixel -> map (Drawing's)
    // Path widths (and dashes) in millimetres on the page instead of image pixels (Style::widths_mm):
    // export_document turns them into pixels at the page's scale.
    bool widths_mm = false;
    bool furniture = false;  // Drawing::furniture: the map furniture layers are written
};

// Whether a writer writes `layer`: the nine drawing layers always, the furniture layers on maps.
inline bool layer_written(const StyledDrawing& drawing, const StyledLayer& layer) {
    return drawing.furniture || !is_furniture(layer.kind);
}

// Whether a layer's strokes get variable widths: taper or weight_min != weight_max, undashed.
bool variable_width(const LayerStyle& style);

// taper_factor (the width factor towards a stroke's ends): core/stroke_taper.hpp.

// Applies `style`'s colours, widths (by distance, in bands; or per point, with taper and weight,
// on variable_width layers), opacity and dashes to `drawing`.
StyledDrawing style_drawing(const Drawing& drawing, const Style& style, LayerSplit split = LayerSplit::kind);

// The largest eye distance of any stroke point in the drawing (0 if none).
double max_depth(const Drawing& drawing);

// Total number of paths across layers and groups.
size_t path_count(const StyledDrawing& drawing);

}  // namespace penink
