// What a drawn frame becomes, the same for `penink render` and each frame of `penink batch`: its
// drawing finished with the style's finishing options (scene_style.hpp's finish_options;
// lines/finish_drawing.hpp: image-space sketch, overshoot, repeats, thinning, plotter order),
// styled (export/styled_drawing.hpp: pens, layer split) and exported to every file at once
// (export/export_drawing.hpp: all of them or none), plus, when asked, one document in memory for
// the standard output (made before any file is written, so its page errors come first).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/drawing.hpp"
#include "core/log.hpp"
#include "export/export_drawing.hpp"
#include "export/style.hpp"
#include "export/styled_drawing.hpp"
#include "lines/finish_drawing.hpp"
#include "scene/frame_source.hpp"
#include "scene/map_furniture.hpp"

namespace penink {

struct FrameOutput {
    std::vector<std::string> files;  // format from each extension; written together or none
    PageOptions page;
    LayerSplit split = LayerSplit::kind;
    std::string document_format;     // "" or svg, ps, eps, pdf: the document returned in memory
    bool width_report = false;       // the styled layers' width measures (export_drawing.hpp's width_report)
    bool line_measures = true;       // FinishStats' small loops and doubled share (FinishOptions::measure)
    // A terrain's plan view gets its map furniture (scene/map_furniture.hpp), after finishing.
    MapFurnitureOptions furniture{};
    double map_scale = 0.0;  // the scene's 1:N, 0: none
};

struct FrameOutputResult {
    FinishStats finish;
    PlotStats plot;
    std::string document;  // in document_format; empty when none was asked for
    std::vector<std::string> widths;  // width_report's lines, when asked for
    double finish_ms = 0;  // finishing, wall ms
    double write_ms = 0;   // styling and export, wall ms
};

// `terrain`: creases and ridges were sketched in object space by the terrain path (and a plan
// view is a map, with furniture).
FrameOutputResult write_frame(Drawing& drawing, const Style& style, std::uint64_t seed, bool terrain,
                              const FrameOutput& output);

// --verbose lines: per layer, what finishing did (strokes in, joined, lines, length, pen-up
// travel before and after ordering, small loops, doubled share); the frame's GPU pass times,
// tracing time and triangles.
// What `penink render` and `penink preview` make of a scene: the scene's own view drawn
// (draw_scene) and written (write_frame) with the style load_scene resolved.
struct RenderedFrame {
    SceneDrawing drawn;
    FrameOutputResult written;
    bool terrain = false;
};
// `keep`: kept between the frames of a process that draws one scene after another (frame_source.hpp).
RenderedFrame render_scene_frame(Scene& scene, GlContext& context, const FrameOutput& output, const Log& log,
                                 TerrainKeep* keep = nullptr);

void log_finish(const FinishStats& stats, const Log& log);
void log_frame_timings(const SceneDrawing& drawing, const Log& log);
// For a plan view of a terrain: each crease and ridge layer's grid-direction share and angle to
// the fall line (scene/plan_directions.hpp); nothing for other views.
void log_directions(const Drawing& drawing, const std::string& dem_path, const Log& log);

}  // namespace penink
