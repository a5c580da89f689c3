// The speed/accuracy sweep of `penink bench` (Mower, "Fast Image-Space Silhouette Extraction",
// Tables 1-4 in spirit): level-of-detail tolerance x image size x silhouette method (each of
// `methods`: Toward/Away, Adjacency, edge walk, object-space) x tessellation max_level; for each, time per frame =
// median wall ms of k frames after warm-up, with the fastest and slowest (TFT/AFT + SIL +
// read-back + tracing; creases cost the same in every row, so they are off) and accuracy of the
// SIL mask against a reference none of the methods computes: on an analytic terrain
// (input/analytic_terrain.hpp) its closed-form silhouettes; on a DEM the ray-cast silhouettes of
// the full-resolution PN surface (scene/raycast_reference.hpp: rays at ref_supersample x the
// largest image size, surface tessellated to ref_edge_px there), scaled to the smaller sizes;
// precision / recall at 1 and 2 px and mean distances in pixels (lines/line_accuracy.hpp). Then
// "model no more than a scene needs" rows: projected-size tessellation vs a fixed level, frustum
// culling, DEM window cropping, each on/off, for the scene's camera and a 4x zoom (fov / 4) where
// most of the DEM is out of view.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include <optional>

#include "core/log.hpp"
#include "export/speed_accuracy_chart.hpp"
#include "input/analytic_terrain.hpp"
#include "input/terrain.hpp"
#include "render/gl_context.hpp"
#include "scene/scene.hpp"

namespace penink {

struct SpeedAccuracyConfig {
    std::vector<int> levels{1, 2, 4, 8};
    std::vector<std::pair<int, int>> sizes{{500, 375}, {1000, 750}, {2000, 1500}};
    std::vector<SilhouetteMethod> methods{SilhouetteMethod::toward_away, SilhouetteMethod::adjacency,
                                          SilhouetteMethod::edge_walk, SilhouetteMethod::object_space};
    // [surface] tolerance_px values swept (level of detail; 0 = full resolution); empty = the scene's.
    std::vector<float> tolerances;
    int frames = 5, warmup = 1;
    double ref_edge_px = 1.0;  // ray-cast reference: tessellated edges at the largest size, pixels
    int ref_supersample = 4;   // ray-cast reference: rays per pixel along x and y
    // The terrain is this analytic case's grid (dem = analytic_grid(shape, spacing)): views use
    // its camera and the closed-form reference. None: a DEM, the scene's camera, ray-cast reference.
    std::optional<AnalyticCase> analytic;
    bool needs = true;         // the "model no more than a scene needs" rows
    std::pair<int, int> needs_size{0, 0};  // their image size; 0 = the scene's
};

struct BenchRow {
    std::string group;     // "sweep" or "needs"
    std::string view;      // "scene" or "zoom4"
    int width = 0, height = 0;
    std::string method;    // toward-away | adjacency | edge-walk | object-space
    int level = 0;         // tessellation max_level
    double tolerance_px = 0;  // [surface] tolerance_px of the frame's level-of-detail mesh (0: full resolution)
    bool adaptive = true, culling = true, cropping = true;
    std::size_t cells = 0;
    double ms = 0;         // median wall ms per frame
    double ms_min = 0, ms_max = 0;  // fastest and slowest of the timed frames
    double tft = 0, aft = 0, sil = 0;  // GPU ms of that frame's passes (median frame)
    double p1 = 0, r1 = 0, p2 = 0, r2 = 0, drawn_to_ref = 0, ref_to_drawn = 0;
    double ref_ms = 0;     // time to compute the reference for this view (once per view)
    std::string reference; // "closed-form" or "ray-cast"
};

// CSV header and rows (fixed precision).
std::string bench_csv(const std::vector<BenchRow>& rows);
// Human-readable table (fixed-width columns).
std::string bench_table(const std::vector<BenchRow>& rows);
// Chart series from the sweep rows: one colour per method (in order of appearance), one dash per
// image size and tolerance, points in level order labelled "L<level>" with min-max time bars;
// y = F1 score at 1 px.
std::vector<ChartSeries> bench_chart_series(const std::vector<BenchRow>& rows);

// Every row of the sweep (and the needs rows) for the scene's DEM, with a progress bar on stderr.
std::vector<BenchRow> speed_accuracy_rows(const Scene& scene, const Terrain& dem, GlContext& context,
                                          const SpeedAccuracyConfig& config, const Log& log);

}  // namespace penink
