// The hachures layer of a terrain frame (hachure_lines.hpp).
#include "scene/hachure_lines.hpp"

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "scene/drainage_lines.hpp"

namespace penink {

namespace {

std::string number_text(double v) {
    char s[32];
    std::snprintf(s, sizeof s, "%g", v);
    return s;
}

void read_value(const toml::value& t, const char* key, double& out, const std::string& file) {
    if (!t.contains(key)) return;
    const toml::value& v = t.at(key);
    if (v.is_integer()) out = double(v.as_integer());
    else if (v.is_floating()) out = v.as_floating();
    else throw Error("scene", file, std::string("[hachures] ") + key + ": expected a number");
    if (!std::isfinite(out)) throw Error("scene", file, std::string("[hachures] ") + key + ": expected a finite number");
}

void check(const std::string& file, const char* key, double v, double lo, double hi) {
    if (v >= lo && v <= hi) return;
    throw Error("scene", file, std::string("[hachures] ") + key + " must be between " + number_text(lo) + " and " +
                                   number_text(hi) + " (got " + number_text(v) + ")");
}

}  // namespace

const std::vector<std::string>& hachure_keys() {
    static const std::vector<std::string> keys = {
        "enabled", "tone", "blend", "contrast", "gamma", "min_slope_deg", "spacing_min_px", "spacing_max_px",
        "width_px", "d_test", "yield_px", "max_turn_deg", "aerial", "min_length_px"};
    return keys;
}

void read_hachures(const toml::value& root, HachureParams& p, const std::string& file) {
    if (!root.is_table() || !root.contains("hachures")) return;
    const toml::value& t = root.at("hachures");
    if (t.contains("enabled")) {
        if (!t.at("enabled").is_boolean()) throw Error("scene", file, "[hachures] enabled: must be true or false");
        p.enabled = t.at("enabled").as_boolean();
    }
    if (t.contains("tone")) {
        const toml::value& v = t.at("tone");
        if (!v.is_string() || !hachure_tone_named(v.as_string().str, p.tone))
            throw Error("scene", file, "[hachures] tone must be \"light\", \"slope\" or \"blend\"" +
                                           (v.is_string() ? " (got \"" + v.as_string().str + "\")" : std::string()));
    }
    read_value(t, "blend", p.blend, file);
    read_value(t, "contrast", p.contrast, file);
    read_value(t, "gamma", p.gamma, file);
    read_value(t, "min_slope_deg", p.min_slope_deg, file);
    read_value(t, "spacing_min_px", p.spacing_min_px, file);
    read_value(t, "spacing_max_px", p.spacing_max_px, file);
    read_value(t, "width_px", p.width_px, file);
    read_value(t, "d_test", p.d_test, file);
    read_value(t, "yield_px", p.yield_px, file);
    read_value(t, "max_turn_deg", p.max_turn_deg, file);
    read_value(t, "aerial", p.aerial, file);
    read_value(t, "min_length_px", p.min_length_px, file);
}

void validate_hachures(const HachureParams& p, const std::string& file) {
    check(file, "blend", p.blend, 0.0, 1.0);
    check(file, "contrast", p.contrast, 0.01, 10.0);
    check(file, "gamma", p.gamma, 0.1, 10.0);
    check(file, "min_slope_deg", p.min_slope_deg, 0.0, 89.0);
    check(file, "spacing_min_px", p.spacing_min_px, 0.5, 1000.0);
    check(file, "spacing_max_px", p.spacing_max_px, p.spacing_min_px, 1000.0);
    check(file, "width_px", p.width_px, 0.0, 100.0);
    check(file, "d_test", p.d_test, 0.05, 1.0);
    check(file, "yield_px", p.yield_px, 0.0, 100.0);
    check(file, "max_turn_deg", p.max_turn_deg, 1.0, 180.0);
    check(file, "aerial", p.aerial, 0.0, 1.0);
    check(file, "min_length_px", p.min_length_px, 0.0, 1000.0);
}

void add_hachures(const FrameTerrain& terrain, const Camera& camera, const DepthImage& toward,
                  const glm::dvec3& light, const HachureParams& params, Drawing& drawing) {
    if (!params.enabled) return;
    const GridNodes& n = terrain.nodes;
    n.need(terrain.window);  // read directly below
    HachureGrid grid;
    grid.cols = n.cols, grid.rows = n.rows, grid.pos = n.pos, grid.valid = n.valid, grid.z_scale = n.z_scale;
    if (n.has_sea()) grid.floor_z = n.sea_z();
    grid.c0 = terrain.window.c0, grid.r0 = terrain.window.r0, grid.c1 = terrain.window.c1, grid.r1 = terrain.window.r1;
    HachureFrame frame;
    frame.camera = &camera;
    frame.toward = &toward;
    frame.light = light;
    frame.max_distance = max_visible_distance(toward);
    frame.width_px = params.width_px > 0.0 ? params.width_px : default_hachure_width_px;
    for (std::size_t i = 0; i < hachure_obstacle_layers.size(); ++i) {
        frame.obstacles.push_back(&drawing.layer(hachure_obstacle_layers[i]).strokes);
        frame.obstacle_pens.push_back(params.obstacle_pens[i]);
    }
    drawing.layer(LayerKind::hachures).strokes = trace_hachures(grid, frame, params);
}

}  // namespace penink
