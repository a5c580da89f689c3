// The hachures layer of a terrain frame (hachure_lines.hpp).
#include "scene/hachure_lines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "scene/drainage_lines.hpp"

namespace penink {

namespace {

void check(const std::string& file, const char* key, double v, double lo, double hi) {
    if (v >= lo && v <= hi) return;
    throw Error("scene", file, std::string("[hachures] ") + key + " must be between " + message_number(lo) + " and " +
                                   message_number(hi) + " (got " + message_number(v) + ")");
}

}  // namespace

const std::vector<std::string>& hachure_keys() {
    static const std::vector<std::string> keys = {
        "enabled", "tone", "blend", "contrast", "gamma", "min_slope_deg", "spacing_min_px", "spacing_max_px",
        "width_px", "d_test", "yield_px", "max_turn_deg", "aerial", "min_length_px"};
    return keys;
}

double* hachure_number(HachureParams& p, const std::string& key) {
    const std::pair<const char*, double*> numbers[] = {
        {"blend", &p.blend},        {"contrast", &p.contrast},         {"gamma", &p.gamma},
        {"min_slope_deg", &p.min_slope_deg}, {"spacing_min_px", &p.spacing_min_px}, {"spacing_max_px", &p.spacing_max_px},
        {"width_px", &p.width_px},  {"d_test", &p.d_test},             {"yield_px", &p.yield_px},
        {"max_turn_deg", &p.max_turn_deg},   {"aerial", &p.aerial},    {"min_length_px", &p.min_length_px}};
    for (const auto& [name, value] : numbers)
        if (key == name) return value;
    return nullptr;
}

HachureParams hachure_pen(HachureParams params, const Style& style) {
    // the hachures' spacing is computed for the pen that draws them (millimetres at 96 dpi)
    const double px = style.widths_mm ? 96.0 / 25.4 : 1.0;
    const LayerStyle& pen = style.layer(LayerKind::hachures);
    if (params.width_px <= 0.0) params.width_px = pen.width * px;
    // and the range its width takes with the tone (the layer's weight factors)
    params.weight_min = pen.weight_min, params.weight_max = pen.weight_max;
    // its taper and the ink of the lines it yields to, which the coverage feedback counts
    params.taper_px = pen.taper * px, params.taper_min = pen.taper_min;
    for (std::size_t i = 0; i < hachure_obstacle_layers.size(); ++i) {
        const LayerStyle& ls = style.layer(hachure_obstacle_layers[i]);
        params.obstacle_pens[i] = HachurePen{ls.width * px, ls.weight_min, ls.weight_max, ls.taper * px, ls.taper_min};
    }
    return params;
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

int hachure_node_step(const GridNodes& nodes, GridWindow w, const Camera& camera) {
    w = w.clamped(nodes.cols, nodes.rows);
    if (w.cols() < 2 || w.rows() < 2) return 1;
    const PixelProjector project(camera);
    double largest = 0.0;  // pixels a cell spans, the largest over the lattice
    bool seen = false;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
            const int c = w.c0 + (w.cols() - 2) * i / 15, r = w.r0 + (w.rows() - 2) * j / 15;
            if (!nodes.has_data(nodes.index(c, r)) || !nodes.has_data(nodes.index(c + 1, r)) ||
                !nodes.has_data(nodes.index(c, r + 1)))
                continue;
            glm::dvec2 a, b, e;
            double da, db, de;
            if (!project(glm::dvec3(nodes.at(c, r)), a, da) || !project(glm::dvec3(nodes.at(c + 1, r)), b, db) ||
                !project(glm::dvec3(nodes.at(c, r + 1)), e, de))
                return 1;  // a node behind the eye: keep every node
            if (a.x < 0 || a.y < 0 || a.x >= camera.width || a.y >= camera.height) continue;
            largest = std::max({largest, glm::length(b - a), glm::length(e - a)});
            seen = true;
        }
    if (!seen || !(largest > 0.0)) return 1;
    int step = 1;
    while (step < hachure_max_node_step && 2.0 * step * largest <= hachure_node_px) step *= 2;
    return step;
}

HachureNodes hachure_nodes(const FrameTerrain& terrain, const Camera& camera) {
    HachureNodes out;
    const int step = hachure_node_step(terrain.nodes, terrain.window, camera);
    GridWindow w = terrain.window;
    w.c0 -= w.c0 % step, w.r0 -= w.r0 % step;  // the grid's every step-th node, whatever the window
    out.sampled = sampled_window(terrain.nodes, w, step);
    if (out.sampled.step == 1) terrain.nodes.need(terrain.window);  // read directly by the hachures
    return out;
}

void add_hachures(const FrameTerrain& terrain, const Camera& camera, const DepthImage& toward,
                  const glm::dvec3& light, const HachureParams& params, Drawing& drawing) {
    if (!params.enabled) return;
    add_hachures(terrain, hachure_nodes(terrain, camera), camera, toward, light, params, drawing);
}

void add_hachures(const FrameTerrain& terrain, const HachureNodes& nodes, const Camera& camera,
                  const DepthImage& toward, const glm::dvec3& light, const HachureParams& params, Drawing& drawing,
                  NodeTileCounts* tiles) {
    if (!params.enabled) return;
    const GridNodes& n = terrain.nodes;
    HachureGrid grid;
    grid.z_scale = n.z_scale;
    if (n.has_sea()) grid.floor_z = n.sea_z();
    const SampledWindow& sampled = nodes.sampled;
    if (sampled.step == 1) {
        grid.cols = n.cols, grid.rows = n.rows, grid.pos = n.pos, grid.valid = n.valid;
        grid.c0 = terrain.window.c0, grid.r0 = terrain.window.r0, grid.c1 = terrain.window.c1, grid.r1 = terrain.window.r1;
    } else {
        grid.cols = sampled.cols, grid.rows = sampled.rows;
        grid.read = [&n, &sampled](GridWindow part, glm::vec3* pos, std::uint8_t* valid) {
            read_sampled(n, sampled, part, pos, valid);
        };
        grid.c1 = sampled.cols, grid.r1 = sampled.rows;
        grid.counts = tiles;
    }
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

std::string hachure_tiles_line(const SampledWindow& sampled, const NodeTileCounts& tiles) {
    char line[256];
    std::snprintf(line, sizeof line, "hachures: every %d nodes (%d x %d sampled), %zu reads of %zu tiles of %d x %d, %.3g MiB held at most",
                  sampled.step, sampled.cols, sampled.rows, tiles.reads, tiles.distinct, NodeTiles::default_tile_cols,
                  NodeTiles::default_tile_rows, double(tiles.most_bytes) / double(1 << 20));
    return line;
}

}  // namespace penink
