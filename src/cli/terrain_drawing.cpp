#include "cli/terrain_drawing.hpp"

#include <chrono>
#include <cstdio>
#include <unistd.h>
#include <sstream>

#include "cli/terrain_view.hpp"
#include "drainage/drainage_build.hpp"
#include "lines/simplify.hpp"
#include "lines/trace_mask_outline.hpp"
#include "lines/frustum_clip.hpp"
#include "lines/mesh_visibility.hpp"
#include "lines/trace_pixel_lines.hpp"
#include "surface/boundary_curves.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

namespace {

std::string format_camera(const Camera& c, const Terrain& t) {
    std::ostringstream s;
    s.precision(10);
    s << "eye " << c.eye.x + t.origin.x << " " << c.eye.y + t.origin.y << " " << c.eye.z
      << (t.utm_zone ? " (UTM " + std::to_string(t.utm_zone) + (t.north ? "N" : "S") + ")" : "")
      << ", azimuth " << c.azimuth << ", altitude " << c.altitude << ", fov " << c.fov << ", "
      << c.width << "x" << c.height;
    return s.str();
}

void fill_metadata(const Scene& scene, const Camera& cam, const Terrain& t, Drawing& d) {
    std::ostringstream light, params;
    light << "azimuth " << scene.light.azimuth << ", altitude " << scene.light.altitude;
    params << "vertical_exaggeration " << scene.vertical_exaggeration << ", tessellation max_level "
           << scene.tess_max_level << " target_edge_px " << scene.tess_target_edge_px << ", seed "
           << scene.seed << ", style " << scene.style;
    d.metadata["source"] = scene.dem;
    d.metadata["camera"] = format_camera(cam, t);
    d.metadata["light"] = light.str();
    d.metadata["parameters"] = params.str();
    d.metadata["generator"] = "penink";
}

}  // namespace

void add_frame_lines(const FrameImages& images, const SurfaceMesh& mesh, const Camera& camera,
                     Drawing& drawing) {
    TraceParams sil;
    sil.min_pixels = 3, sil.max_spur = 2, sil.kind = "silhouette";
    std::vector<Stroke> strokes = simplify_strokes(trace_pixel_lines(images.silhouettes, images.toward, sil), 0.5f);
    const PixelMask cover = coverage_mask(images);
    Layer& surface = drawing.layer(LayerKind::surface);
    surface.fill = trace_mask_outline(cover, 0.5f);
    std::vector<ObjectPolyline> boundary;
    for (auto& line : clip_polylines_to_frustum(boundary_polylines(mesh), view_projection(camera)))
        boundary.push_back({std::move(line), 1.0f, "outline", ""});
    VisibilityOptions visibility;
    visibility.rel_tolerance = 0.002f;  // terrain: the boundary lies on the rendered surface
    for (Stroke& s : visible_strokes(boundary, images.toward, camera, visibility)) strokes.push_back(std::move(s));
    drawing.layer(LayerKind::silhouettes).strokes = std::move(strokes);
}

namespace {
FrameOptions frame_options(const Scene& scene) {
    FrameOptions options;
    options.tessellation.max_level = scene.tess_max_level;
    options.tessellation.target_edge_px = scene.tess_target_edge_px;
    options.separate_passes = scene.separate_passes;
    options.silhouette_min_gap = scene.silhouette_min_gap;
    options.silhouette_method = scene.silhouette_method == "adjacency"      ? SilhouetteMethod::adjacency
                                : scene.silhouette_method == "object-space" ? SilhouetteMethod::object_space
                                                                            : SilhouetteMethod::toward_away;
    return options;
}
}  // namespace

TerrainFrames::TerrainFrames(GlContext& context, const Scene& scene, const Terrain& dem, Terrain terrain,
                             int width, int height, const Log& log)
    : context_(&context), terrain_(std::move(terrain)), mesh_(mesh_from_terrain(terrain_)),
      renderer_(context.gl(), mesh_, width, height) {
    if (!scene.creases.enabled && !scene.ridges.enabled) return;
    const bool tty = isatty(2);
    DrainageOptions options;
    options.routing = *drainage_routing_named(scene.drainage_routing);  // validate_scene checked it
    DrainageDb db = load_or_build_drainage(
        scene.dem, dem, options, [&](const std::string& m) { log.info(m); },
        [tty](const std::string& stage, double fraction) {  // long builds show progress on a terminal
            if (tty) std::fprintf(stderr, "\rpenink: building drainage database: %-12s %3d%%%s", stage.c_str(),
                                  int(fraction * 100.0 + 0.5), fraction >= 1.0 ? "\n" : "");
        });
    pending_lines_ = std::async(std::launch::async, [this, db = std::move(db)] {
        return prepare_drainage_lines(db, mesh_);
    });
}

TerrainFrames::~TerrainFrames() {
    if (pending_lines_.valid()) pending_lines_.wait();
}

SceneDrawing TerrainFrames::draw(const Camera& camera, const Scene& frame) {
    SceneDrawing out;
    out.camera = camera;
    out.cells = std::size_t(terrain_.cols - 1) * (terrain_.rows - 1);
    out.triangles = mesh_.tri.size();
    const FrameImages images = renderer_.render(camera, frame_options(frame));
    out.times = images.times;
    out.drawing.width = camera.width, out.drawing.height = camera.height;
    if (pending_lines_.valid())
        lines_ = std::make_unique<DrainageLines>(context_->gl(), pending_lines_.get());
    if (lines_)
        lines_->draw(camera, frame, renderer_.surface_pass().toward_texture(),
                     max_visible_distance(images.toward), out.drawing, out.times);
    const auto t0 = std::chrono::steady_clock::now();
    add_frame_lines(images, mesh_, camera, out.drawing);
    out.trace_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    fill_metadata(frame, camera, terrain_, out.drawing);
    return out;
}

SceneDrawing draw_terrain(const Scene& scene, GlContext& context, const Log& log) {
    const Terrain dem = read_scene_dem(scene);
    log.info("read " + scene.dem + ": " + std::to_string(dem.cols) + "x" + std::to_string(dem.rows) + " nodes");
    Camera camera = scene_camera(scene, dem);
    Terrain view = terrain_for_view(dem, camera, scene, log);
    TerrainFrames frames(context, scene, dem, std::move(view), camera.width, camera.height, log);
    return frames.draw(camera, scene);
}

}  // namespace penink
