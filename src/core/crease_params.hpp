// Parameters of the crease and ridge scores (Mower, "Concurrent Drainage Network Rendering",
// eq. 1-6; conventions.md) and the per-vertex terms the DM pass (render/dm.hpp,
// shaders/dm.comp.glsl) writes for them; the score itself is lines/crease_scores.hpp's
// crease_scores, the one place eq. 6 is written. Terms sc, ic, fc are each in [0, 1]; three
// readings of eq. 6's normalisation:
//   thirds (default): rs = (sw sc + iw ic + fw fc) / 3              - rs_min(d)
//   paper:            rs = (sw sc + iw ic + fw fc) / (sw + iw + fw) - rs_min(d)
//   rank:             as paper, each term replaced by its percentile among the frame's visible
//                     vertices (lines/crease_scores.hpp)
// with rs_min(d) = min_score + distance_attenuation d / D; drawn where rs >= 0. "paper" is the
// weighted mean, in [0, 1] for any weights, and equal to /3 when every weight is 1 (eq. 6's /3 is
// the mean of three terms; Table 5's weights .1/.3/.6 already sum to 1). Under it the paper's
// Table 5 weights with Figure 15's min scores .10/.19/.25 draw less at each step; with /3 those
// weights score at most 1/3 and draw next to nothing from .19 on (docs/reproduction.md, measured).
// Table 5's min score .8 draws nothing under "paper" either (flow per basin is near 0 on most of
// the network); under "rank" it draws the top few per cent, the trunk streams in shade.
// One type for both layers; the scene ([creases], [ridges]), the DM pass and docs/conventions.md
// use these defaults.
#pragma once
#include <optional>
#include <string>

namespace penink {

enum class ScoreNormalisation { thirds, paper, rank };

struct CreaseParams {
    // Defaults chosen by eye on volcano and jacksboro (README): slope and flow lead, light shades.
    double slope_weight = 2.0, illumination_weight = 0.5, flow_weight = 4.0;
    double min_score = 0.12, distance_attenuation = 0.1;
    double spacing_px = 4.0;  // closest distance between drawn lines (even density), pixels
    ScoreNormalisation normalisation = ScoreNormalisation::thirds;
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

// Score (and terms' distance) of a vertex that is not visible: outside the frustum, behind the
// surface, or off the modelled surface.
inline constexpr float dm_hidden = -1.0e30f;

// One vertex's terms of eq. 6 as the DM pass writes them: sc = 1 - cos(slope), ic = 1 - cos of the
// light's incidence (clamped to [0, 1]), fc = flow normalised per basin, and d = its eye distance
// in metres (view depth for an orthographic camera); distance == dm_hidden when not visible.
struct CreaseTerms {
    float slope = 0.0f, illumination = 0.0f, flow = 0.0f, distance = dm_hidden;
};

// The scene's name of a normalisation ("thirds", "paper", "rank").
inline const char* score_normalisation_name(ScoreNormalisation n) {
    switch (n) {
    case ScoreNormalisation::paper: return "paper";
    case ScoreNormalisation::rank: return "rank";
    default: return "thirds";
    }
}

// The normalisation a scene names; nullopt for any other name.
inline std::optional<ScoreNormalisation> score_normalisation_named(const std::string& name) {
    for (const ScoreNormalisation n : {ScoreNormalisation::thirds, ScoreNormalisation::paper, ScoreNormalisation::rank})
        if (name == score_normalisation_name(n)) return n;
    return std::nullopt;
}

}  // namespace penink
