// Parameters of the crease and ridge scores (Mower, "Concurrent Drainage Network Rendering",
// eq. 1-6; conventions.md): rs = (sw sc + iw ic + fw fc) / 3 - rs_min(d), drawn where rs >= 0,
// with rs_min(d) = min_score + distance_attenuation d / D. One type for both layers; the scene
// ([creases], [ridges]), the DM pass (render/dm.hpp) and docs/conventions.md use these defaults.
#pragma once

namespace penink {

struct CreaseParams {
    // Defaults chosen by eye on volcano and jacksboro (README): slope and flow lead, light shades.
    double slope_weight = 2.0, illumination_weight = 0.5, flow_weight = 4.0;
    double min_score = 0.12, distance_attenuation = 0.1;
    double spacing_px = 4.0;  // closest distance between drawn lines (even density), pixels
    bool enabled = true;
};

// The creases layer's defaults (drainage branches).
inline CreaseParams crease_defaults() { return {}; }

// The ridges layer's defaults: divides carry no flow, so ridges are scored by slope and light alone.
inline CreaseParams ridge_defaults() {
    CreaseParams p;
    p.illumination_weight = 1.0, p.flow_weight = 0.0, p.min_score = 0.05;
    return p;
}

}  // namespace penink
