#include "scene/mesh_frames.hpp"

#include "core/version.hpp"
#include "core/stopwatch.hpp"

#include "input/mesh_subdivision.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "lines/indication_textures.hpp"
#include "lines/mesh_visibility.hpp"
#include "lines/trace_mask_outline.hpp"
#include "scene/orbit.hpp"
#include "surface/mesh_normals.hpp"

namespace penink {

namespace {

PelOptions pel_options(const MeshSettings& ms) {
    PelOptions o;
    o.threshold = ms.pel_threshold;
    if (ms.light) {
        o.light_at_eye = false;
        o.light_dir = glm::vec3(glm::normalize(mesh_to_world(ms, *ms.light)));
    }
    return o;
}

float mesh_diagonal(const TriangleMesh& mesh) {
    glm::vec3 lo, hi;
    return mesh_bounds(mesh, lo, hi) ? glm::length(hi - lo) : 1.0f;
}

// Texture styles: the scene's material.NAME entries, else by material-name keywords.
TextureOptions texture_options(const TriangleMesh& mesh, const MeshSettings& ms, const Scene& scene) {
    TextureOptions o;
    const float scale = ms.texture_scale.value_or(mesh_diagonal(mesh) / 24.0f);
    o.threshold = ms.texture_threshold;
    o.noise_scale = 4.0f * scale;
    o.edge_band = 1.5f * scale;
    o.features.crease_angle = ms.crease_angle;
    o.seed = scene.style.seed;
    for (const std::string& name : mesh.material_names) {
        auto it = ms.materials.find(name);
        const std::string tex = it != ms.materials.end() ? it->second : default_texture_for_material(name);
        if (!tex.empty()) o.materials[name] = {tex, scale, ms.texture_confidence};
    }
    return o;
}

std::vector<ObjectPolyline> mesh_textures(const TriangleMesh& mesh, const MeshSettings& ms, const Scene& scene,
                                          const Log& log) {
    const TextureOptions o = texture_options(mesh, ms, scene);
    if (o.materials.empty()) return {};
    const std::string dir = find_texture_library(scene);
    if (dir.empty()) {
        if (!ms.materials.empty())
            throw Error("scene", scene.source.file.empty() ? mesh_file(scene) : scene.source.file,
                        "no texture library found (set [textures] library or PENINK_TEXTURES)");
        std::cerr << "penink: warning: no texture library found, textures left out "
                     "(set [textures] library or PENINK_TEXTURES)\n";
        return {};
    }
    const TextureLibrary lib = load_texture_library(dir);
    for (const auto& [material, style] : o.materials)
        if (!lib.textures.count(style.texture))
            throw Error("scene", scene.source.file.empty() ? mesh_file(scene) : scene.source.file,
                        "[textures] material." + material + ": unknown texture \"" + style.texture + "\" (not in " + dir + ")");
    log.info("texture library " + dir);
    return indication_textures(mesh, lib, o);
}

}  // namespace

MeshLines mesh_lines(const TriangleMesh& mesh, const MeshSettings& ms, const Scene& scene, const glm::vec3& eye,
                     const Log& log) {
    MeshLines out;
    auto t0 = Clock::now();
    FeatureOptions fo;
    fo.crease_angle = ms.crease_angle;
    const std::vector<MeshEdge> edges = classify_edges(mesh, fo);
    const FeatureSplit split = split_feature_edges(mesh, edges, eye);
    if (ms.features) out.feature_edges = feature_polylines(mesh, split.features);
    out.times.features = lap_ms(t0);
    const TriangleMesh smooth = split_at_creases(mesh, edges);
    const auto normals = smooth_vertex_normals(smooth, mesh_vertex_normals(smooth, NormalWeighting::angle), ms.smoothing);
    const float edge = mean_edge_length(smooth);
    out.times.normals = lap_ms(t0);
    if (ms.pels) {
        const PelGeometry geom = pel_geometry(smooth);
        out.times.pel_geometry = lap_ms(t0);
        // Xie et al., "Photic Extremum Lines": PELs of the filtered normal field, kept by line strength.
        const auto filtered = gaussian_filter_normals(smooth, normals, ms.normal_filter * edge);
        const PelResult pel = photic_extremum_lines(smooth, geom, filtered, eye, pel_options(ms));
        out.pels = chain_segments(strong_pel_lines(curved_only(pel.segments, filtered), ms.line_strength * edge), "pel");
        out.times.pel = lap_ms(t0);
    }
    out.silhouettes = chain_segments(mesh_silhouettes(smooth, normals, eye), "silhouette");
    for (ObjectPolyline& p : feature_polylines(mesh, split.contours)) {
        p.kind = "silhouette";
        out.silhouettes.push_back(std::move(p));
    }
    out.times.silhouettes = lap_ms(t0);
    if (ms.textures) out.textures = mesh_textures(mesh, ms, scene, log);
    out.times.textures = lap_ms(t0);
    return out;
}

namespace {

// Depth of the nearest surface of either facing: open meshes hide lines with their backs too.
DepthImage nearest_depth(const FrameImages& images) {
    DepthImage d = images.toward;
    for (std::size_t i = 0; i < d.depth.size() && i < images.away.depth.size(); ++i)
        d.depth[i] = std::min(d.depth[i], images.away.depth[i]);
    return d;
}

void add_visible(const std::vector<ObjectPolyline>& lines, const DepthImage& depth, const Camera& cam,
                 Layer& layer) {
    for (Stroke& s : visible_strokes(lines, depth, cam))
        if (s.points.size() >= 2) layer.strokes.push_back(std::move(s));
}

std::string format_vec(const glm::dvec3& v) {
    std::ostringstream s;
    s.precision(8);
    s << v.x << " " << v.y << " " << v.z;
    return s.str();
}

void fill_metadata(const Scene& scene, const MeshSettings& ms, const Camera& c, Drawing& d) {
    std::ostringstream cam, params;
    cam.precision(8);
    cam << "eye " << format_vec(c.eye) << " (z-up world), azimuth " << c.azimuth << ", altitude " << c.altitude
        << ", fov " << c.fov << ", " << c.width << "x" << c.height;
    params << "up " << (ms.y_up ? "y" : "z") << ", pels " << (ms.pels ? "on" : "off") << " threshold "
           << ms.pel_threshold << " smoothing " << ms.smoothing << " normal_filter " << ms.normal_filter
           << " line_strength " << ms.line_strength << ", crease_angle " << ms.crease_angle
           << ", textures " << (ms.textures ? "on" : "off") << " threshold " << ms.texture_threshold
           << ", seed " << scene.style.seed << ", style " << scene.style.name;
    d.metadata["source"] = mesh_file(scene);
    d.metadata["camera"] = cam.str();
    d.metadata["light"] = ms.light ? "direction " + format_vec(*ms.light) + " (mesh frame)" : "at the camera";
    d.metadata["parameters"] = params.str();
    d.metadata["generator"] = std::string("penink ") + penink_version;
    const std::string name = std::filesystem::path(mesh_file(scene)).filename().string();
    d.metadata["title"] = name + ": pen-and-ink drawing";
    d.metadata["description"] = "Pen-and-ink drawing of the mesh " + name + " by penink " + penink_version +
                                "; camera " + d.metadata["camera"] + "; light " + d.metadata["light"];
}

void log_mesh_timings(const MeshLines& l, std::size_t triangles, const Log& log) {
    std::ostringstream s;
    s.precision(3);
    s << "CPU ms: normals " << l.times.normals << ", PEL geometry " << l.times.pel_geometry << ", PEL "
      << l.times.pel << " (" << triangles << " triangles), silhouettes " << l.times.silhouettes
      << ", feature edges " << l.times.features << ", textures " << l.times.textures << ", visibility "
      << l.times.visibility << "; lines: " << l.pels.size() << " PEL, " << l.silhouettes.size()
      << " silhouette, " << l.feature_edges.size() << " feature-edge, " << l.textures.size() << " texture";
    log.info(s.str());
}

}  // namespace

MeshFrames::MeshFrames(const Scene& scene, GlContext& context, const Log& log)
    : log_(&log), ms_(scene.mesh), mesh_(read_mesh(mesh_file(scene))) {
    loop_subdivide(mesh_, ms_.subdivide);
    if (ms_.y_up) mesh_y_up_to_z_up(mesh_);
    log.info("read " + mesh_file(scene) + ": " + std::to_string(mesh_.positions.size()) + " vertices, " +
             std::to_string(mesh_.triangles.size()) + " triangles, " + std::to_string(mesh_.material_names.size()) +
             " materials");
    surface_ = surface_mesh_from(mesh_, mesh_vertex_normals(mesh_));
    renderer_ = std::make_unique<TerrainRenderer>(context.gl(), surface_, scene.view.camera.width, scene.view.camera.height);
}

Camera MeshFrames::scene_camera(const Scene& scene) const {
    glm::vec3 lo, hi;
    mesh_bounds(mesh_, lo, hi);
    return mesh_camera(scene, mesh_.positions, lo, hi);
}

std::vector<Camera> MeshFrames::orbit(const Scene& scene, int frames) const {
    glm::vec3 lo, hi;
    mesh_bounds(mesh_, lo, hi);
    return orbit_cameras(scene_camera(scene), lo, hi, frames);
}

SceneDrawing MeshFrames::draw(const Camera& camera, const Scene& frame) {
    SceneDrawing out;
    out.triangles = mesh_.triangles.size();
    out.camera = camera;
    FrameOptions options;
    options.tessellation.max_level = 1;  // the lines lie on the flat triangles
    // The silhouettes are object-space lines (mesh_lines): the frame needs the depth images only,
    // not the image-space SIL pass.
    options.silhouette_method = SilhouetteMethod::object_space;
    const FrameImages images = renderer_->render(out.camera, options);
    out.times = images.times;
    const auto t0 = Clock::now();
    MeshLines lines = mesh_lines(mesh_, ms_, frame, glm::vec3(out.camera.eye), *log_);
    auto t1 = Clock::now();
    Drawing& d = out.drawing;
    d.width = out.camera.width, d.height = out.camera.height;
    d.layer(LayerKind::surface).fill = trace_mask_outline(coverage_mask(images), 0.5f);
    const DepthImage depth = nearest_depth(images);
    add_visible(lines.pels, depth, out.camera, d.layer(LayerKind::pels));
    add_visible(lines.silhouettes, depth, out.camera, d.layer(LayerKind::silhouettes));
    add_visible(lines.feature_edges, depth, out.camera, d.layer(LayerKind::feature_edges));
    add_visible(lines.textures, depth, out.camera, d.layer(LayerKind::textures));
    lines.times.visibility = lap_ms(t1);
    out.times.pel = lines.times.pel;
    out.lines = lines.times;
    out.trace_ms = ms_since(t0);
    log_mesh_timings(lines, mesh_.triangles.size(), *log_);
    fill_metadata(frame, ms_, out.camera, d);
    d.georeference = plan_view_georeference(out.camera, {0.0, 0.0}, "");  // mesh coordinates, no CRS
    d.metadata.merge(georeference_metadata(out.camera, d.georeference));
    return out;
}

SceneView open_mesh_view(const Scene& scene, GlContext& context, const Log& log) {
    auto frames = std::make_unique<MeshFrames>(scene, context, log);
    SceneView view;
    view.camera = frames->scene_camera(scene);
    view.frames = std::move(frames);
    return view;
}

}  // namespace penink
