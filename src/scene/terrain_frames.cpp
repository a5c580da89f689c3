#include "scene/terrain_frames.hpp"

#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/memory_budget.hpp"
#include "core/version.hpp"
#include "core/progress_bar.hpp"
#include "core/stopwatch.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/drainage_memory.hpp"
#include "input/crs_util.hpp"
#include "lines/object_silhouettes.hpp"
#include "lines/simplify.hpp"
#include "lines/stroke_weight.hpp"
#include "lines/depth_edge_placement.hpp"
#include "lines/trace_mask_outline.hpp"
#include "lines/frustum_clip.hpp"
#include "lines/mesh_visibility.hpp"
#include "lines/trace_pixel_lines.hpp"
#include "scene/cache_build_estimate.hpp"
#include "scene/hachure_lines.hpp"
#include "scene/map_scale.hpp"
#include "scene/scene_memory.hpp"
#include "scene/terrain_keep.hpp"
#include "scene/terrain_view.hpp"
#include "surface/boundary_curves.hpp"
#include "surface/pn_tessellation.hpp"

namespace penink {

namespace {

std::string format_camera(const Camera& c, const Terrain& t) {  // t: georeference only
    std::ostringstream s;
    s.precision(10);
    s << "eye " << c.eye.x + t.origin.x << " " << c.eye.y + t.origin.y << " " << c.eye.z
      << (t.utm_zone ? " (UTM " + std::to_string(t.utm_zone) + (t.north ? "N" : "S") + ")" : "")
      << ", azimuth " << c.azimuth << ", altitude " << c.altitude;
    if (is_orthographic(c)) s << ", orthographic, " << c.view_width << " m across";
    else s << ", fov " << c.fov;
    s << ", " << c.width << "x" << c.height;
    return s.str();
}

void fill_metadata(const Scene& scene, const Camera& cam, const Terrain& t, Drawing& d) {
    std::ostringstream light, params;
    light << "azimuth " << scene.view.light.azimuth << ", altitude " << scene.view.light.altitude;
    params << "vertical_exaggeration " << scene.terrain.vertical_exaggeration << (scene.terrain.exaggeration_was_auto ? " (auto)" : "");
    if (scene.view.map_scale > 0.0) params << ", map scale 1:" << map_scale_text(scene.view.map_scale);
    params << ", tessellation max_level "
           << scene.terrain.tess_max_level << " target_edge_px " << scene.terrain.tess_target_edge_px << ", surface tolerance_px "
           << scene.terrain.surface_tolerance_px << " min_radius_px " << scene.terrain.surface_min_radius_px << ", seed "
           << scene.style.seed << ", style " << scene.style.name;
    if (scene.terrain.sea_level) params << ", sea_level " << *scene.terrain.sea_level;
    d.metadata["source"] = scene.source.dem;
    d.metadata["camera"] = format_camera(cam, t);
    d.metadata["light"] = light.str();
    d.metadata["parameters"] = params.str();
    d.metadata["generator"] = std::string("penink ") + penink_version;
    const std::string name = std::filesystem::path(scene.source.file.empty() ? scene.source.dem : scene.source.file).filename().string();
    d.metadata["title"] = name + ": pen-and-ink drawing";
    std::ostringstream desc;
    desc << "Pen-and-ink drawing of the DEM " << std::filesystem::path(scene.source.dem).filename().string() << " by penink "
         << penink_version << ", vertical exaggeration " << scene.terrain.vertical_exaggeration << "; camera "
         << d.metadata["camera"] << "; light " << d.metadata["light"];
    d.metadata["description"] = desc.str();
}

}  // namespace

PixelMask object_space_silhouette_mask(const SurfaceMesh& mesh, const Camera& camera,
                                       const TessellationOptions& tessellation) {
    const PnTessellation tess = tessellate_pn_surface(mesh, view_projection(camera), glm::vec2(camera.width, camera.height),
                                                      tessellation.target_edge_px, tessellation.max_level);
    const ObjectSilhouettes sil = object_space_silhouettes(tess.pos, tess.tri, camera);
    return rasterize_polylines(silhouette_polylines(sil, true), camera.width, camera.height);
}

std::vector<Stroke> traced_silhouettes(const FrameImages& images) {
    TraceParams sil;
    sil.min_pixels = 3, sil.max_spur = 2, sil.kind = "silhouette";
    sil.depth_radius = 1;  // the occluding surface's depth (occlusion-aware joins)
    std::vector<Stroke> strokes = trace_pixel_lines(images.silhouettes, images.toward, sil);
    place_on_depth_edges(strokes, images.toward, images.away);
    return simplify_strokes(std::move(strokes), 0.5f);
}

void add_frame_lines(const FrameImages& images, const SurfaceMesh& mesh, const Camera& camera,
                     Drawing& drawing) {
    std::vector<Stroke> strokes = traced_silhouettes(images);
    const PixelMask cover = coverage_mask(images);
    Layer& surface = drawing.layer(LayerKind::surface);
    surface.fill = trace_mask_outline(cover, 0.5f);
    std::vector<ObjectPolyline> boundary;
    for (auto& line : clip_polylines_to_frustum(boundary_polylines(mesh), view_projection(camera)))
        boundary.push_back({std::move(line), 1.0f, "outline", ""});
    VisibilityOptions visibility;
    visibility.rel_tolerance = 0.002f;  // terrain: the boundary lies on the rendered surface
    for (Stroke& s : visible_strokes(boundary, images.toward, camera, visibility)) strokes.push_back(std::move(s));
    weigh_by_depth_gap(strokes, images.toward);  // profile lines heaviest (lines/stroke_weight.hpp)
    equalise_weights(strokes);
    drawing.layer(LayerKind::silhouettes).strokes = std::move(strokes);
}

namespace {
FrameOptions frame_options(const Scene& scene) {
    FrameOptions options;
    options.tessellation.max_level = scene.terrain.tess_max_level;
    options.tessellation.target_edge_px = scene.terrain.tess_target_edge_px;
    options.separate_passes = scene.lines.separate_passes;
    options.silhouette_min_gap = scene.lines.silhouette_min_gap;
    options.tessellation.cull_patches = scene.terrain.cull_patches;
    options.silhouette_method = scene.lines.silhouette_method;
    return options;
}
}  // namespace

namespace {
// The drainage build's options of a scene (the DEM's identity from `key` where given).
DrainageOptions scene_drainage_options(const Scene& scene, const TerrainCacheKey* key) {
    DrainageOptions options;
    options.routing = *drainage_routing_named(scene.terrain.drainage_routing);  // validate_scene checked it
    options.cache_dir = scene.terrain.cache_dir;
    if (key && key->content_hash) options.dem = DrainageFingerprint{key->file_size, key->mtime_ns, key->content_hash};
    return options;
}
}  // namespace

bool scene_drainage_cached(const Scene& scene, const TerrainCacheKey& key, int cols, int rows) {
    const DrainageOptions options = scene_drainage_options(scene, &key);
    Terrain size_only;  // drainage_fingerprint reads its size alone, the DEM's identity being given
    size_only.cols = cols, size_only.rows = rows;
    const DrainageFingerprint fp = drainage_fingerprint(scene.source.dem, size_only, options);
    for (const std::string& p : {scene.source.dem + ".dv", drainage_cache_path(scene.source.dem, options.cache_dir, false)})
        if (const std::optional<DrainageFingerprint> f = peek_drainage_fingerprint(p); f && *f == fp) return true;
    return false;
}

std::optional<DrainageLineSource> scene_drainage(const Scene& scene, const Terrain& dem, const Log& log,
                                                 const TerrainCacheKey* key) {
    if (!scene.lines.creases.enabled && !scene.lines.ridges.enabled) return std::nullopt;
    StageProgress progress(std::cerr, log.progress, "building drainage database");
    const DrainageOptions options = scene_drainage_options(scene, key);
    DrainageLineSource source;
    const auto t0 = Clock::now();
    bool building = false;  // the progress callback is called by a build alone
    std::string file;
    source.db = load_or_build_drainage(
        scene.source.dem, dem, options, [&](const std::string& m) { log.info(m); },
        [&](const std::string& stage, double fraction) {
            if (!building) announce_cache_build(std::cerr, CacheKind::drainage, dem.cols, dem.rows);
            building = true;
            progress.update(stage, fraction);
        },
        &source.vertices, &file);
    // creases built per tile as frames need them, kept where the caches are written (beside the
    // database, or in the user's cache folder for one read beside a DEM in a read-only folder)
    if (source.db.has_crease_source())
        source.creases = StoredCreases::take(
            source.db, file.empty() ? std::string() : crease_tile_folder(drainage_cache_path(scene.source.dem, options.cache_dir)));
    if (source.creases) {  // a frame's first tiles can take minutes on a large DEM: shown as they are built
        auto shown = std::make_shared<StageProgress>(std::cerr, log.progress, "crease tiles");
        source.creases->on_build_progress([shown](double f) { shown->update("building", f); });
    }
    log.info("drainage database ready (" + std::to_string(int(ms_since(t0))) + " ms)");
    return source;
}

std::function<void(int cols, int rows)> crease_tiles_memory_check(const Scene& scene, int dem_cols, int dem_rows) {
    const std::uint64_t max_memory = scene.terrain.max_memory;
    const double frame = max_memory > 0 ? scene_frame_bytes(scene, dem_cols, dem_rows) : 0.0;
    return [dem = scene.source.dem, max_memory, frame](int cols, int rows) {
        check_memory("drainage", dem,
                     "building the crease tiles of a view not drawn before (the drainage grid's " + std::to_string(cols) +
                         "x" + std::to_string(rows) + " points)",
                     frame + crease_tiles_build_bytes(double(cols) * double(rows)), memory_budget(max_memory));
    };
}

NodeHeights terrain_node_heights(const StoredTerrain& t) {
    NodeHeights h;
    h.cols = t.nodes.cols, h.rows = t.nodes.rows;
    h.span = [nodes = t.nodes, keep = t.storage](int r, int c0, int c1, float* z) {
        thread_local std::vector<glm::vec3> scratch;  // (blocks are filled on several threads at once)
        nodes.read_heights(nodes.index(c0, r), nodes.index(c1, r), z, scratch);
    };
    return h;
}

void read_whole_when_damaged(DrainageLineSource& source, const Scene& scene, const StoredTerrain& dem, const Log& log) {
    if (!source.vertices.file) return;
    const DrainageOptions options = scene_drainage_options(scene, &dem.key);
    source.read_whole = [dem_path = scene.source.dem, meta = dem.meta, options, log] {
        log.info("drainage: " + dem_path + ": damaged drainage cache; reading it whole");
        return load_or_build_drainage(dem_path, meta, options, [&log](const std::string& m) { log.info(m); });
    };
}

std::optional<DrainageLineSource> scene_drainage(const Scene& scene, const SceneTerrain& dem, const Log& log) {
    const TerrainCacheKey* key = &dem.stored.key;
    std::optional<DrainageLineSource> source = dem.stored.in_memory ? scene_drainage(scene, *dem.stored.in_memory, log, key)
                                                                    : scene_drainage(scene, dem.stored.meta, log, key);
    if (source) read_whole_when_damaged(*source, scene, dem.stored, log);
    if (source && source->creases && !dem.stored.in_memory && dem.stored.nodes.blocks)
        source->creases->use_node_heights(terrain_node_heights(dem.stored));
    if (source && source->creases)
        source->creases->before_first_decode(crease_tiles_memory_check(scene, dem.stored.meta.cols, dem.stored.meta.rows));
    return source;
}

TerrainFrames::TerrainFrames(GlContext& context, std::optional<DrainageLineSource> drainage, FrameTerrain terrain,
                             int width, int height, const Log& log, LineCulling culling)
    : TerrainFrames(context,
                    drainage ? std::make_shared<const DrainageLineSource>(std::move(*drainage)) : nullptr,
                    std::move(terrain), width, height, std::move(culling), nullptr, log) {}

TerrainFrames::TerrainFrames(GlContext& context, std::shared_ptr<const DrainageLineSource> drainage,
                             FrameTerrain terrain, int width, int height, LineCulling culling,
                             TerrainGpuKeep* gpu, const Log& log)
    : context_(&context), terrain_(std::move(terrain)), width_(width), height_(height), gpu_(gpu), log_(log) {
    if (!drainage) return;
    const LineBox box = frame_line_box(terrain_);
    drainage_ = drainage;
    pending_lines_ = std::async(std::launch::async, [this, db = std::move(drainage), box, culling = std::move(culling)] {
        const auto t0 = Clock::now();
        DrainageLineData data = prepare_drainage_lines(*db, box, culling);
        lines_ms_ = ms_since(t0);
        return data;
    });
}

namespace {
FrameTerrain logged_frame_terrain(Terrain terrain, const Log& log) {
    const auto t0 = Clock::now();
    const int cols = terrain.cols, rows = terrain.rows;
    FrameTerrain f = frame_terrain(std::move(terrain));
    log.info("level-of-detail pyramid: " + std::to_string(f.lod.side()) + "^2 nodes (" + std::to_string(cols) + "x" +
             std::to_string(rows) + " modelled, " + std::to_string(int(ms_since(t0))) + " ms)");
    return f;
}
}  // namespace

TerrainFrames::TerrainFrames(GlContext& context, std::optional<DrainageLineSource> drainage, Terrain terrain, int width,
                             int height, const Log& log, LineCulling culling)
    : TerrainFrames(context, std::move(drainage), logged_frame_terrain(std::move(terrain), log), width, height, log,
                    std::move(culling)) {}

TerrainFrames::~TerrainFrames() {
    if (pending_lines_.valid()) pending_lines_.wait();
}

SurfaceMesh TerrainFrames::frame_mesh(const Camera& camera, const Scene& frame) const {
    if (frame.terrain.surface_tolerance_px <= 0.0f) return mesh_from_terrain(window_terrain(terrain_));
    LodOptions lod;
    lod.tolerance_px = frame.terrain.surface_tolerance_px;
    lod.min_radius_px = frame.terrain.surface_min_radius_px;
    return select_lod_mesh(terrain_.lod, terrain_.nodes, terrain_.meta.vertical_exaggeration, camera, lod);
}

SceneDrawing TerrainFrames::draw(const Camera& camera, const Scene& frame) {
    SceneDrawing out;
    out.camera = camera;
    out.cells = terrain_.cells();
    const auto t_select = Clock::now();
    const bool full = frame.terrain.surface_tolerance_px <= 0.0f;
    if (!(full && mesh_is_full_)) {  // the full-resolution mesh, once made and uploaded, serves every frame
        mesh_ = frame_mesh(camera, frame);
        mesh_is_full_ = full;
        if (renderer_) renderer_->set_surface(mesh_);
        else if (gpu_) renderer_ = gpu_->renderers.get(context_->gl(), mesh_, width_, height_);
        else renderer_ = std::make_shared<TerrainRenderer>(context_->gl(), mesh_, width_, height_);
    }
    out.times.select = ms_since(t_select);
    out.triangles = mesh_.tri.size();
    const FrameOptions options = frame_options(frame);
    FrameImages images = renderer_->render(camera, options);
    images.times.select = out.times.select;
    out.times = images.times;
    if (options.silhouette_method == SilhouetteMethod::object_space) {
        const auto t0 = Clock::now();
        images.silhouettes = object_space_silhouette_mask(mesh_, camera, options.tessellation);
        out.times.sil = ms_since(t0);
    }
    out.drawing.width = camera.width, out.drawing.height = camera.height;
    // the hachures' nodes (their step; at step 1 the window read into place), found while the
    // drainage lines may still be prepared on another core
    const auto t_nodes = Clock::now();
    std::optional<HachureNodes> hachure_grid;
    if (frame.lines.hachures.enabled) hachure_grid = hachure_nodes(terrain_, camera);
    const double nodes_ms = ms_since(t_nodes);
    // the silhouettes and the surface's outline (their layers alone) while the drainage lines
    // may still be prepared
    const auto t0 = Clock::now();
    add_frame_lines(images, mesh_, camera, out.drawing);
    out.trace_ms = ms_since(t0);
    if (pending_lines_.valid()) {
        std::unique_ptr<DrainageLines>& made = gpu_ ? gpu_->lines : own_lines_;
        if (made) made->set_lines(pending_lines_.get());
        else made = std::make_unique<DrainageLines>(context_->gl(), pending_lines_.get());
        lines_ = made.get();
        std::string built;
        if (const StoredCreases* c = drainage_ ? drainage_->creases.get() : nullptr)
            built = "; creases kept for " + std::to_string(c->stems_built()) + " of " + std::to_string(c->stem_count()) +
                    " stems (" + std::to_string(c->vertices_built()) + " vertices), " + std::to_string(c->tiles_read()) +
                    " tile files read, " + std::to_string(c->tiles_written()) + " written";
        log_.info("drainage lines prepared (" + std::to_string(int(lines_ms_)) + " ms" + built + ")");
    }
    if (lines_)
        lines_->draw(camera, frame, renderer_->surface_pass().toward_texture(),
                     max_visible_distance(images.toward), out.drawing, out.times);
    if (terrain_.nodes.has_sea()) {  // the shore of the modelled window, found with the first frame
        if (!coast_) coast_ = std::make_unique<CoastlineLines>(context_->gl(), terrain_.nodes, terrain_.window);
        coast_->draw(camera, renderer_->surface_pass().toward_texture(), out.drawing);
    }
    const auto t_hachures = Clock::now();  // after the lines they yield to
    if (hachure_grid) {
        NodeTileCounts tiles;
        add_hachures(terrain_, *hachure_grid, camera, images.toward,
                     light_vector(Light{frame.view.light.azimuth, frame.view.light.altitude}),
                     hachure_pen(frame.lines.hachures, frame.style.resolved), out.drawing, &tiles);
        if (hachure_grid->sampled.step > 1) log_.info(hachure_tiles_line(hachure_grid->sampled, tiles));
    }
    out.hachure_ms = nodes_ms + ms_since(t_hachures);
    out.silhouette_mask = std::move(images.silhouettes);
    out.toward = std::move(images.toward);
    if (const CheckedBlocks* blocks = terrain_.nodes.blocks)
        out.cache_bytes_read = blocks->bytes_read(), out.cache_bytes = blocks->bytes();
    fill_metadata(frame, camera, terrain_.meta, out.drawing);
    out.drawing.georeference = plan_view_georeference(camera, terrain_.meta.origin, terrain_.meta.crs_wkt);
    if (out.drawing.georeference) add_geographic_corners(*out.drawing.georeference, camera.width, camera.height);
    out.drawing.metadata.merge(georeference_metadata(camera, out.drawing.georeference));
    return out;
}

LineBox frame_line_box(const FrameTerrain& terrain) {
    LineBox box;
    box.lo = glm::vec2(terrain.lo), box.hi = glm::vec2(terrain.hi), box.exaggeration = terrain.meta.vertical_exaggeration;
    box.sea_level = terrain.nodes.sea_level;
    return box;
}

namespace {

// What a view of the scene's DEM is drawn from, read or made through `keep`: the DEM's caches
// read, its camera placed, its drainage lines' source, and the DEM cropped to the view.
struct ViewParts {
    Camera camera;
    std::shared_ptr<const DrainageLineSource> drainage;
    FrameTerrain model;
};
ViewParts view_parts(Scene& scene, const Log& log, TerrainKeep& keep) {
    const SceneTerrain dem = keep.terrain(scene, log);
    ViewParts v;
    v.camera = scene_camera(scene, dem);
    v.drainage = keep.drainage(scene, dem, log);
    const auto t0 = Clock::now();
    v.model = terrain_for_view(dem, v.camera, scene, log);
    log.info("view window found (" + std::to_string(int(ms_since(t0))) + " ms)");
    return v;
}

}  // namespace

std::size_t write_view_crease_tiles(Scene& scene, const Log& log, BuiltNetworkHandle built) {
    TerrainKeep keep;  // (the caches read as open_terrain_view reads them)
    const ViewParts v = view_parts(scene, log, keep);
    if (!v.drainage || !v.drainage->creases) return 0;
    if (built) v.drainage->creases->use_built_network(std::move(built));
    prepare_drainage_lines(*v.drainage, frame_line_box(v.model), LineCulling{{v.camera}, line_culling_px(scene)});
    return v.drainage->creases->tiles_written();
}

SceneView open_terrain_view(Scene& scene, GlContext& context, const Log& log, TerrainKeep* keep) {
    TerrainKeep once;  // without a keep: what this view reads and builds, for it alone
    TerrainKeep& k = keep ? *keep : once;
    k.build_side_by_side(scene, log);  // a large DEM's first drawing: both caches at once
    ViewParts v = view_parts(scene, log, k);
    SceneView view;
    view.camera = v.camera;
    view.frames = std::make_unique<TerrainFrames>(context, std::move(v.drainage), std::move(v.model), view.camera.width,
                                                  view.camera.height, LineCulling{{view.camera}, line_culling_px(scene)},
                                                  keep ? &keep->gpu() : nullptr, log);
    return view;
}

}  // namespace penink
