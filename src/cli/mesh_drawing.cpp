#include "cli/mesh_drawing.hpp"

#include "input/mesh_subdivision.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "lines/indication_textures.hpp"
#include "lines/mesh_visibility.hpp"
#include "lines/trace_mask_outline.hpp"
#include "surface/mesh_normals.hpp"

namespace penink {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point& t0) {
    const auto t1 = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    t0 = t1;
    return ms;
}

bool is_sharp(EdgeKind k) { return k == EdgeKind::crease || k == EdgeKind::nonmanifold; }

bool faces_eye(const TriangleMesh& m, int f, const glm::vec3& eye) {
    const glm::uvec3& t = m.triangles[f];
    const glm::vec3 &a = m.positions[t.x], &b = m.positions[t.y], &c = m.positions[t.z];
    return glm::dot(glm::cross(b - a, c - a), eye - a) > 0.0f;
}

unsigned find_root(std::vector<unsigned>& parent, unsigned i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// Corner (3 * face + k) of face f at vertex v.
unsigned corner_of(const TriangleMesh& m, int f, unsigned v) {
    const glm::uvec3& t = m.triangles[f];
    return 3u * unsigned(f) + (t.x == v ? 0u : t.y == v ? 1u : 2u);
}

// Drops PEL segments inside flat-shaded triangles (all three vertex normals equal: a planar
// fan, where phi only varies with the light direction and its extrema mean nothing).
std::vector<ObjectSegment> curved_only(std::vector<ObjectSegment> segs, const std::vector<glm::vec3>& n) {
    std::erase_if(segs, [&](const ObjectSegment& s) {
        if (s.edge_a == ~std::uint64_t(0) || s.edge_b == ~std::uint64_t(0)) return false;
        const unsigned v[4] = {unsigned(s.edge_a >> 32), unsigned(s.edge_a), unsigned(s.edge_b >> 32), unsigned(s.edge_b)};
        float spread = 0.0f;
        for (int i = 1; i < 4; ++i) spread = std::max(spread, glm::length(n[v[i]] - n[v[0]]));
        return spread < 1e-3f;
    });
    return segs;
}

PelOptions pel_options(const MeshScene& ms) {
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
TextureOptions texture_options(const TriangleMesh& mesh, const MeshScene& ms, const Scene& scene) {
    TextureOptions o;
    const float scale = ms.texture_scale.value_or(mesh_diagonal(mesh) / 24.0f);
    o.threshold = ms.texture_threshold;
    o.noise_scale = 4.0f * scale;
    o.edge_band = 1.5f * scale;
    o.features.crease_angle = ms.crease_angle;
    o.seed = scene.seed;
    for (const std::string& name : mesh.material_names) {
        auto it = ms.materials.find(name);
        const std::string tex = it != ms.materials.end() ? it->second : default_texture_for_material(name);
        if (!tex.empty()) o.materials[name] = {tex, scale, ms.texture_confidence};
    }
    return o;
}

std::vector<ObjectPolyline> mesh_textures(const TriangleMesh& mesh, const MeshScene& ms, const Scene& scene,
                                          const Log& log) {
    const TextureOptions o = texture_options(mesh, ms, scene);
    if (o.materials.empty()) return {};
    const std::string dir = find_texture_library(scene, ms);
    if (dir.empty()) {
        if (!ms.materials.empty())
            throw Error("scene", scene.file.empty() ? ms.path : scene.file,
                        "no texture library found (set [textures] library or PENINK_TEXTURES)");
        std::cerr << "penink: warning: no texture library found, textures left out "
                     "(set [textures] library or PENINK_TEXTURES)\n";
        return {};
    }
    const TextureLibrary lib = load_texture_library(dir);
    for (const auto& [material, style] : o.materials)
        if (!lib.textures.count(style.texture))
            throw Error("scene", scene.file.empty() ? ms.path : scene.file,
                        "[textures] material." + material + ": unknown texture \"" + style.texture + "\" (not in " + dir + ")");
    log.info("texture library " + dir);
    return indication_textures(mesh, lib, o);
}

}  // namespace

FeatureSplit split_feature_edges(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges,
                                 const glm::vec3& eye) {
    FeatureSplit out;
    out.sharp.assign(mesh.positions.size(), 0);
    for (const MeshEdge& e : edges) {
        if (e.kind == EdgeKind::none) continue;
        if (is_sharp(e.kind)) out.sharp[e.a] = out.sharp[e.b] = 1;
        if (e.face_count == 2 && !faces_eye(mesh, e.face0, eye) && !faces_eye(mesh, e.face1, eye))
            continue;  // between two faces turned away: hidden on a closed surface
        const bool contour = is_sharp(e.kind) && e.face0 >= 0 && e.face1 >= 0 &&
                             faces_eye(mesh, e.face0, eye) != faces_eye(mesh, e.face1, eye);
        (contour ? out.contours : out.features).push_back(e);
    }
    return out;
}

TriangleMesh split_at_creases(const TriangleMesh& mesh, const std::vector<MeshEdge>& edges) {
    std::vector<unsigned> parent(mesh.triangles.size() * 3);
    for (unsigned i = 0; i < parent.size(); ++i) parent[i] = i;
    for (const MeshEdge& e : edges) {  // join the corners of smooth manifold edges
        if (is_sharp(e.kind) || e.face_count != 2) continue;
        for (unsigned v : {e.a, e.b}) {
            const unsigned r0 = find_root(parent, corner_of(mesh, e.face0, v));
            const unsigned r1 = find_root(parent, corner_of(mesh, e.face1, v));
            parent[std::max(r0, r1)] = std::min(r0, r1);
        }
    }
    TriangleMesh out = mesh;
    out.positions.clear();
    std::vector<unsigned> index(parent.size(), ~0u);
    for (unsigned c = 0; c < parent.size(); ++c) {  // new vertices in corner order: deterministic
        const unsigned r = find_root(parent, c);
        if (index[r] == ~0u) {
            index[r] = unsigned(out.positions.size());
            out.positions.push_back(mesh.positions[mesh.triangles[c / 3][c % 3]]);
        }
        out.triangles[c / 3][c % 3] = index[r];
    }
    return out;
}

MeshLines mesh_lines(const TriangleMesh& mesh, const MeshScene& ms, const Scene& scene, const glm::vec3& eye,
                     const Log& log) {
    MeshLines out;
    auto t0 = Clock::now();
    FeatureOptions fo;
    fo.crease_angle = ms.crease_angle;
    const std::vector<MeshEdge> edges = classify_edges(mesh, fo);
    const FeatureSplit split = split_feature_edges(mesh, edges, eye);
    if (ms.features) out.feature_edges = feature_polylines(mesh, split.features);
    out.times.features = ms_since(t0);
    const TriangleMesh smooth = split_at_creases(mesh, edges);
    const auto normals = smooth_vertex_normals(smooth, mesh_vertex_normals(smooth, NormalWeighting::angle), ms.smoothing);
    out.times.normals = ms_since(t0);
    if (ms.pels) {
        const PelGeometry geom = pel_geometry(smooth);
        out.times.pel_geometry = ms_since(t0);
        const PelResult pel = photic_extremum_lines(smooth, geom, normals, eye, pel_options(ms));
        out.pels = chain_segments(curved_only(pel.segments, normals), "pel");
        out.times.pel = ms_since(t0);
    }
    out.silhouettes = chain_segments(mesh_silhouettes(smooth, normals, eye), "silhouette");
    for (ObjectPolyline& p : feature_polylines(mesh, split.contours)) {
        p.kind = "silhouette";
        out.silhouettes.push_back(std::move(p));
    }
    out.times.silhouettes = ms_since(t0);
    if (ms.textures) out.textures = mesh_textures(mesh, ms, scene, log);
    out.times.textures = ms_since(t0);
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

void fill_metadata(const Scene& scene, const MeshScene& ms, const Camera& c, Drawing& d) {
    std::ostringstream cam, params;
    cam.precision(8);
    cam << "eye " << format_vec(c.eye) << " (z-up world), azimuth " << c.azimuth << ", altitude " << c.altitude
        << ", fov " << c.fov << ", " << c.width << "x" << c.height;
    params << "up " << (ms.y_up ? "y" : "z") << ", pels " << (ms.pels ? "on" : "off") << " threshold "
           << ms.pel_threshold << " smoothing " << ms.smoothing << ", crease_angle " << ms.crease_angle
           << ", textures " << (ms.textures ? "on" : "off") << " threshold " << ms.texture_threshold
           << ", seed " << scene.seed << ", style " << scene.style;
    d.metadata["source"] = ms.path;
    d.metadata["camera"] = cam.str();
    d.metadata["light"] = ms.light ? "direction " + format_vec(*ms.light) + " (mesh frame)" : "at the camera";
    d.metadata["parameters"] = params.str();
    d.metadata["generator"] = "penink";
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

SceneDrawing draw_mesh(const Scene& scene, GlContext& context, const Log& log) {
    const MeshScene ms = load_mesh_scene(scene);
    TriangleMesh mesh = read_mesh(ms.path);
    loop_subdivide(mesh, ms.subdivide);
    if (ms.y_up) mesh_y_up_to_z_up(mesh);
    glm::vec3 lo, hi;
    mesh_bounds(mesh, lo, hi);
    log.info("read " + ms.path + ": " + std::to_string(mesh.positions.size()) + " vertices, " +
             std::to_string(mesh.triangles.size()) + " triangles, " + std::to_string(mesh.material_names.size()) +
             " materials");
    SceneDrawing out;
    out.triangles = mesh.triangles.size();
    out.camera = mesh_camera(scene, ms, mesh.positions, lo, hi);
    const SurfaceMesh surface = surface_mesh_from(mesh, mesh_vertex_normals(mesh));  // outlives the renderer
    TerrainRenderer renderer(context.gl(), surface, out.camera.width, out.camera.height);
    FrameOptions options;
    options.tessellation.max_level = 1;  // the lines lie on the flat triangles
    const FrameImages images = renderer.render(out.camera, options);
    out.times = images.times;
    const auto t0 = Clock::now();
    MeshLines lines = mesh_lines(mesh, ms, scene, glm::vec3(out.camera.eye), log);
    auto t1 = Clock::now();
    Drawing& d = out.drawing;
    d.width = out.camera.width, d.height = out.camera.height;
    d.layer(LayerKind::surface).fill = trace_mask_outline(coverage_mask(images), 0.5f);
    const DepthImage depth = nearest_depth(images);
    add_visible(lines.pels, depth, out.camera, d.layer(LayerKind::pels));
    add_visible(lines.silhouettes, depth, out.camera, d.layer(LayerKind::silhouettes));
    add_visible(lines.feature_edges, depth, out.camera, d.layer(LayerKind::feature_edges));
    add_visible(lines.textures, depth, out.camera, d.layer(LayerKind::textures));
    lines.times.visibility = ms_since(t1);
    out.times.pel = lines.times.pel;
    out.trace_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    log_mesh_timings(lines, mesh.triangles.size(), log);
    fill_metadata(scene, ms, out.camera, d);
    return out;
}

}  // namespace penink
