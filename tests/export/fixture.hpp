// Shared test data for the export tests: a small fixed Drawing (200 x 160 pixels, strokes in
// several layers, a surface ring with a hole), a style with visible pens, and temp folders
// (support/temp_dir.hpp).
#pragma once
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <toml.hpp>

#include "core/drawing.hpp"
#include "core/error.hpp"
#include "export/style.hpp"
#include "support/temp_dir.hpp"

namespace penink::test {

inline Stroke make_stroke(std::vector<glm::vec2> pts, std::vector<float> depth, float strength,
                          std::string kind) {
    Stroke s;
    s.points = std::move(pts);
    s.depth = std::move(depth);
    s.strength = strength;
    s.kind = std::move(kind);
    return s;
}

inline Drawing small_drawing() {
    Drawing d;
    d.width = 200;
    d.height = 160;
    d.metadata = {{"source", "synthetic"}, {"camera", "eye <0 0 10> & \"test\""}};
    d.layer(LayerKind::surface).fill = {{{10, 60}, {190, 60}, {190, 150}, {10, 150}},
                                        {{80, 90}, {120, 90}, {120, 130}, {80, 130}}};
    d.layer(LayerKind::ridges).strokes.push_back(make_stroke(
        {{20, 70}, {60, 65}, {100, 72}, {140, 66}, {180, 70}}, {100, 300, 500, 800, 1000}, 0.5f, "ridge"));
    d.layer(LayerKind::creases).strokes.push_back(
        make_stroke({{30, 120}, {70, 110}, {110, 140}}, {200, 300, 400}, 0.25f, "crease"));
    d.layer(LayerKind::textures).strokes.push_back(
        make_stroke({{140, 100}, {180, 140}}, {600, 600}, 1.0f, "texture"));
    d.layer(LayerKind::feature_edges).strokes.push_back(make_stroke({{40, 30}}, {50}, 2.0f, "peak"));
    d.layer(LayerKind::silhouettes).strokes.push_back(make_stroke(
        {{10, 60}, {100, 20}, {190, 60}, {10, 60}}, {1000, 900, 1000, 1000}, 1.0f, "silhouette"));
    return d;
}

inline toml::value parse_toml(const std::string& text) {
    std::istringstream in(text);
    return toml::parse(in, "test.toml");
}

// Wide pens so rasterisations can be compared; widths and opacity fall with distance.
inline Style visible_style() {
    Style s = default_style();
    apply_style_overrides(s, R"(
        fill = "#d8d8d8"
        [all]
        width = 3.0
        width_far = 1.5
        taper = 0.0
        weight_min = 1.0
        weight_max = 1.0
        [creases]
        color = "#b03020"
        opacity = 0.5
        [textures]
        dash = [8.0, 6.0]
        [feature-edges]
        width = 8.0
        [silhouettes]
        width = 4.0
        color = "#203080"
    )");
    return s;
}

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// The message of the penink::Error `f` throws, or "no error".
inline std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace penink::test
