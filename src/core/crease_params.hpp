// Parameters of the crease and ridge scores (Mower, "Concurrent Drainage Network Rendering",
// eq. 1-6; conventions.md) and the score itself, for the CPU (tests, docs) and the DM pass
// (render/dm.hpp, shaders/dm.comp.glsl), which both use crease_score_divisor. Terms sc, ic, fc are
// each in [0, 1]; three readings of eq. 6's normalisation:
//   thirds (default): rs = (sw sc + iw ic + fw fc) / 3              - rs_min(d)
//   paper:            rs = (sw sc + iw ic + fw fc) / (sw + iw + fw) - rs_min(d)
//   rank:             as paper, each term replaced by its percentile among the frame's visible
//                     vertices (lines/rank_scores.hpp; the DM pass gives the terms)
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

// What the weighted sum of the terms is divided by: 3, or the sum of the weights ("paper" and
// "rank"; 1 when every weight is 0, so the score is then -rs_min rather than undefined).
inline double crease_score_divisor(const CreaseParams& p) {
    if (p.normalisation == ScoreNormalisation::thirds) return 3.0;
    const double sum = p.slope_weight + p.illumination_weight + p.flow_weight;
    return sum > 0.0 ? sum : 1.0;
}

// rs of eq. 6 for terms sc, ic, fc and the threshold rs_min (= min_score + attenuation d / D).
inline double crease_score(const CreaseParams& p, double sc, double ic, double fc, double rs_min) {
    return (p.slope_weight * sc + p.illumination_weight * ic + p.flow_weight * fc) / crease_score_divisor(p) - rs_min;
}

// The scene's names of the normalisations ("thirds", "paper", "rank"); nullopt for any other.
inline std::optional<ScoreNormalisation> score_normalisation_named(const std::string& name) {
    if (name == "thirds") return ScoreNormalisation::thirds;
    if (name == "paper") return ScoreNormalisation::paper;
    if (name == "rank") return ScoreNormalisation::rank;
    return std::nullopt;
}

inline const char* score_normalisation_name(ScoreNormalisation n) {
    switch (n) {
    case ScoreNormalisation::paper: return "paper";
    case ScoreNormalisation::rank: return "rank";
    default: return "thirds";
    }
}

}  // namespace penink
