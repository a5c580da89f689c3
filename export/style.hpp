// Drawing styles: per-layer pen colour, width and opacity (near and far), distance thinning,
// dashes, sketchiness, overshoot and repeats, parsed from styles/*.toml (toml11) or built in.
// Widths, dashes, sketch and overshoot are in pixels of the drawing's image (SVG user units);
// near/far are fractions of the drawing's largest eye distance (see styles/README.md).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/drawing.hpp"

namespace penink {

struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb&) const = default;
};

// "#rrggbb" (also "#rgb") -> Rgb; throws std::invalid_argument with a short reason.
Rgb parse_rgb(const std::string& text);
// Rgb -> "#rrggbb" (lower case).
std::string rgb_hex(Rgb c);

// How one layer's strokes are drawn. Values at the near distance; *_far at the far distance,
// linearly interpolated in between (clamped outside).
// Dash patterns: each length 0 or at least min_dash_px, the pattern at least min_dash_pattern_px
// long in all, at most max_dash_entries numbers (a finer pattern costs time and memory in every
// writer and says nothing on paper).
constexpr double min_dash_px = 0.1, min_dash_pattern_px = 1.0;
constexpr std::size_t max_dash_entries = 16;

struct LayerStyle {
    Rgb color{0, 0, 0};
    double width = 1.0, width_far = 1.0;      // stroke width, image pixels
    double opacity = 1.0, opacity_far = 1.0;  // [0, 1]
    double keep_far = 1.0;                    // share of strokes kept at the far distance
    std::vector<double> dash;                 // on/off lengths in pixels; empty = solid
    double sketch = 0.0;                      // endpoint perturbation (lines stage), pixels
    double overshoot = 0.0;                   // extension of open stroke ends, pixels
    int repeat = 1;                           // times each stroke is drawn (plotter passes)
    double min_length = 2.0;                  // shorter strokes (pen-down length, pixels) are dropped
    bool visible = true;                      // false: the layer is written empty
    // Tapered ends (the pen's lift): an open stroke thins over its last `taper` px at each end
    // (half its length when shorter) to taper_min times its width; 0: no taper. Ignored on
    // dashed layers.
    double taper = 0.0;
    double taper_min = 0.0;  // [0, 1]
    // Width factor at stroke weight 0 and 1 (Stroke::weight: creases by flow, silhouettes by
    // the depth gap behind them), linear between; strokes without weights take weight_max.
    double weight_min = 1.0, weight_max = 1.0;
    // Map furniture layers: the size of their labels, points on the page (0: the layer draws no
    // text). Drawing layers carry no text.
    double font_size = 0.0;
    bool operator==(const LayerStyle&) const = default;
};

struct Style {
    std::string name = "technical";
    Rgb fill{255, 255, 255};        // surface mask fill
    bool no_fill = false;           // fill = "none": no surface mask (pen plotters draw fills as outlines)
    bool widths_mm = false;         // width_unit = "mm": widths in millimetres on the page, whatever its size
    Rgb background{255, 255, 255};  // page / image background
    double near = 0.0, far = 1.0;   // fractions of the drawing's largest depth
    int bands = 4;                  // width bands (quantisation levels) per layer
    std::array<LayerStyle, layer_count> layers;  // indexed by LayerKind
    LayerStyle& layer(LayerKind k) { return layers[static_cast<size_t>(k)]; }
    const LayerStyle& layer(LayerKind k) const { return layers[static_cast<size_t>(k)]; }
    bool operator==(const Style&) const = default;
};

// The default style: equal to styles/technical.toml.
Style default_style();
// Shipped styles by name ("technical", "field-sketch", "plotter"); throws Error("style", name,
// "unknown style \"NAME\" (use technical, field-sketch or plotter)").
Style builtin_style(const std::string& name);
std::vector<std::string> builtin_style_names();

// Parses a style file; starts from default_style() and applies the file's keys.
// Errors: Error("style", path, what), e.g. `unknown layer "foo"`, `width must be >= 0`.
Style load_style(const std::string& path);
// Either a built-in name or a path to a .toml file.
Style resolve_style(const std::string& name_or_path);

// Applies a style table given as TOML text (a style file's text, or a scene's [style] table
// written out: top-level keys and one sub-table per layer name or "all"; "all" sets the nine
// drawing layers, never the map furniture's). Throws Error("style", source, what) on bad input
// (nothing applied then), "invalid TOML: ..." among them.
void apply_style_overrides(Style& style, const std::string& toml_text, const std::string& source = "");

}  // namespace penink
