// The parameters of the hachures layer (lines/hachures.hpp), apart so that the scene can hold
// them without the tracing's interface.
#pragma once
#include <array>
#include <string>

#include "core/drawing.hpp"

namespace penink {

enum class HachureTone { light, slope, blend };

// "light", "slope", "blend"; false for another name.
bool hachure_tone_named(const std::string& name, HachureTone& out);
const char* hachure_tone_name(HachureTone tone);

// A pen as the style draws a layer, in image pixels: width times lerp(weight_min, weight_max,
// the stroke's weight), thinning to taper_min over taper_px at each end.
struct HachurePen {
    double width_px = 1.0, weight_min = 1.0, weight_max = 1.0, taper_px = 0.0, taper_min = 1.0;
};

// The layers the hachures yield to (drawn before them), in this order.
inline constexpr std::array<LayerKind, 4> hachure_obstacle_layers = {LayerKind::creases, LayerKind::ridges,
                                                                     LayerKind::coastline, LayerKind::silhouettes};

// The [hachures] table of a scene (conventions.md, styles/README.md); the defaults are
// hachure_defaults()'s.
struct HachureParams {
    bool enabled = true;
    HachureTone tone = HachureTone::light;
    double blend = 0.0;            // weight of the slope tone in "blend", [0, 1]
    double contrast = 0.0;         // gain on the tone about 0.5, [0.01, 10]
    double gamma = 0.0;            // exponent on the tone after the gain, [0.1, 10]
    double min_slope_deg = 0.0;    // flatter ground (drawn exaggeration) gets no line
    double spacing_min_px = 0.0;   // closest separation, image pixels (darkest tone)
    double spacing_max_px = 0.0;   // widest separation; lighter tones get no line
    double width_px = 0.0;         // pen width the spacing is computed for; 0: the style's hachures width
    double d_test = 0.0;           // a line stops nearer than d_test x separation to another
    double yield_px = 0.0;         // and nearer than this to a crease, ridge or silhouette
    double max_turn_deg = 0.0;     // largest turn of the image direction per pixel
    double aerial = 0.0;           // perspective: tone falls to (1 - aerial) at the farthest depth
    double min_length_px = 0.0;    // shorter lines are dropped
    // The pen's range, from the style (hachure_pen, scene/hachure_lines.hpp; not [hachures] keys): the widths of
    // the lightest and the heaviest stroke as factors of width_px (the style's weight_min and
    // weight_max of the hachures layer). Equal: one width, tone by spacing alone.
    double weight_min = 1.0, weight_max = 1.0;
    // The pen's taper (the style's taper px and taper_min of the hachures layer) and the pens of
    // hachure_obstacle_layers: the ink they lay, which the coverage feedback counts
    // (lines/hachures.hpp).
    double taper_px = 0.0, taper_min = 1.0;
    std::array<HachurePen, hachure_obstacle_layers.size()> obstacle_pens{};
};

// The defaults (lines/hachures.cpp), the one set of them.
HachureParams hachure_defaults();

}  // namespace penink
