#include "scene/frame_output.hpp"

#include <cmath>
#include <sstream>

#include "core/stopwatch.hpp"
#include "scene/plan_directions.hpp"
#include "scene/scene_style.hpp"

namespace penink {

FrameOutputResult write_frame(Drawing& drawing, const Style& style, std::uint64_t seed, bool terrain,
                              const FrameOutput& output) {
    FrameOutputResult out;
    auto t0 = Clock::now();
    FinishOptions finish = finish_options(style, seed, terrain);
    finish.measure = output.line_measures;
    out.finish = finish_drawing(drawing, finish);
    out.finish_ms = lap_ms(t0);
    if (terrain) {
        const std::string page_path = output.files.empty() ? "stdout." + output.document_format : output.files.front();
        add_scene_furniture(drawing, output.furniture, output.map_scale, style, output.page, page_path);
    }
    const StyledDrawing styled = style_drawing(drawing, style, output.split);
    if (!output.document_format.empty())
        out.document = export_document(styled, output.page, "stdout." + output.document_format);
    if (!output.files.empty()) export_drawings(styled, output.page, output.files);
    out.write_ms = lap_ms(t0);
    out.plot = plot_stats(styled);
    if (output.width_report) out.widths = width_report(styled);
    return out;
}

RenderedFrame render_scene_frame(Scene& scene, GlContext& context, const FrameOutput& output, const Log& log,
                                 TerrainKeep* keep) {
    RenderedFrame frame;
    const Style& style = scene.style.resolved;
    frame.terrain = !is_mesh_scene(scene);
    frame.drawn = draw_scene(scene, context, log, keep);
    log_frame_timings(frame.drawn, log);
    FrameOutput with_furniture = output;  // a plan view's furniture comes from the scene
    with_furniture.furniture = scene.view.furniture, with_furniture.map_scale = scene.view.map_scale;
    frame.written = write_frame(frame.drawn.drawing, style, scene.style.seed, frame.terrain, with_furniture);
    return frame;
}

void log_finish(const FinishStats& stats, const Log& log) {
    for (LayerKind k : all_layers) {
        const LayerFinishStats& l = stats.layers[static_cast<size_t>(k)];
        if (l.strokes_in == 0) continue;
        std::ostringstream s;
        s << std::fixed;
        s.precision(0);
        s << layer_name(k) << ": " << l.strokes_in << " strokes -> " << l.joined << " joined -> "
          << l.strokes << " lines, " << l.length << " px drawn, pen-up " << l.travel_before
          << " px -> " << l.travel_after << " px ordered; " << l.small_loops << " loops under 25 px, ";
        s.precision(1);
        s << 100.0 * l.doubled_share << " % doubled (within 1.5 px for 4 px or more)";
        log.info(s.str());
    }
}

void log_directions(const Drawing& drawing, const std::string& dem_path, const Log& log) {
    for (const LayerDirections& l : plan_view_directions(drawing, dem_path)) {
        std::ostringstream s;
        s << std::fixed;
        s.precision(3);
        s << layer_name(l.kind) << ": " << l.directions.grid_share() << " of the length within 1 deg of a grid direction; ";
        s.precision(1);
        s << "to the fall line (slopes > 5 deg) median " << l.directions.fall_median_deg << " deg, p90 "
          << l.directions.fall_p90_deg << " deg";
        log.info(s.str());
    }
}

void log_frame_timings(const SceneDrawing& r, const Log& log) {
    std::ostringstream s;
    s.precision(3);
    s << "GPU ms: TFT " << r.times.tft << ", AFT " << r.times.aft << ", SIL " << r.times.sil << ", DM " << r.times.dm << ", RIDGES " << r.times.ridges
      << ", read-back " << r.times.readback << "; trace " << r.trace_ms << " ms; "
      << r.triangles << " triangles selected in " << std::lround(r.times.select) << " ms; hachures "
      << std::lround(r.hachure_ms) << " ms";
    log.info(s.str());
    if (r.cache_bytes > 0) {
        std::ostringstream c;
        c.precision(3);
        c << "terrain cache: " << double(r.cache_bytes_read) / 1048576.0 << " of " << double(r.cache_bytes) / 1048576.0
          << " MiB of nodes and pyramid read";
        log.info(c.str());
    }
}

}  // namespace penink
