#include "preview/preview_session.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <glm/glm.hpp>

#include "core/error.hpp"
#include "core/stopwatch.hpp"
#include "core/input_files.hpp"
#include "export/atomic_file.hpp"
#include "export/export_drawing.hpp"
#include "input/crs_util.hpp"
#include "scene/frame_output.hpp"
#include "scene/map_scale.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

namespace fs = std::filesystem;

namespace {

FrameOutput svg_in_memory(bool measure) {
    FrameOutput out;
    out.document_format = "svg";
    out.line_measures = measure;  // only -v prints them
    return out;
}

}  // namespace

std::optional<glm::dvec3> unproject_pixel(const Camera& cam, const DepthImage& depth, double px, double py) {
    if (is_empty(depth) || !(px >= 0.0 && py >= 0.0 && px < depth.width && py < depth.height)) return std::nullopt;
    const int x = int(px), y = int(py);
    const float d = sample_depth(depth, x, y);
    if (!std::isfinite(d)) return std::nullopt;
    const glm::dmat4 inverse = glm::inverse(view_projection(cam));
    const double nx = (x + 0.5) / depth.width * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / depth.height * 2.0;
    const glm::dvec4 a = inverse * glm::dvec4(nx, ny, -1.0, 1.0), b = inverse * glm::dvec4(nx, ny, 1.0, 1.0);
    const glm::dvec3 near = glm::dvec3(a) / a.w, far = glm::dvec3(b) / b.w;
    // eye_depth grows one for one along the ray from its near point (perspective: a ray from the
    // eye; orthographic: a ray along the view direction)
    return near + glm::normalize(far - near) * (double(d) - eye_depth(cam, near));
}

PreviewSession::PreviewSession(const Scene& scene, std::string save_path, GlBackend gl, const Log& log)
    : log_(log) {
    const std::string& name = scene.source.file.empty() ? scene.source.dem : scene.source.file;
    if (scene.source.dem.empty()) throw Error("input", name, "no DEM given");
    if (is_mesh_scene(scene)) throw Error("cli", name, "penink preview draws terrains (a DEM or a terrain scene), not meshes");
    dem_ = fs::absolute(scene.source.dem).lexically_normal().string();
    if (!scene.source.file.empty())
        base_ = read_input_text("scene", scene.source.file, max_text_input_bytes, "scene file");
    if (!scene.terrain.cache_dir.empty())  // [cache] dir or --cache-dir, for the frames and the file saved
        base_ = with_cache_dir(base_, fs::absolute(scene.terrain.cache_dir).lexically_normal().string());
    save_path_ = fs::absolute(save_path).lexically_normal().string();
    std::string pattern = (fs::temp_directory_path() / "penink-preview-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw Error("cli", pattern, "cannot make the preview's private folder");
    folder_ = pattern;
    scene_file_ = (fs::path(folder_) / fs::path(save_path_).filename()).string();
    context_ = make_gl_context(gl);
    log_.info(context_->description());

    Scene first = scene;  // the scene's own view, drawn once
    first.source.dem = dem_;
    apply_map_scale(first, PageOptions{});
    const SceneDrawing drawn = draw_scene(first, *context_, log_, &keep_);  // its camera and depths alone
    meta_ = keep_.stored(first, log_).meta;
    const Camera& cam = drawn.camera;
    PreviewView& v = initial_;
    v.orthographic = is_orthographic(cam);
    v.azimuth = cam.azimuth, v.altitude = cam.altitude, v.fov = scene.view.camera.fov;
    v.width = scene.view.camera.width, v.height = scene.view.camera.height;
    const glm::dvec3 dir = direction_from_angles(cam.azimuth, cam.altitude);
    const glm::dvec3 centre = unproject_pixel(cam, drawn.toward, cam.width / 2.0, cam.height / 2.0)
                                  .value_or(cam.eye + dir * (0.5 * (cam.near_plane + cam.far_plane)));
    const double unit = linear_unit_of(meta_.crs_wkt);
    v.target_x = (centre.x + meta_.origin.x) / unit, v.target_y = (centre.y + meta_.origin.y) / unit;
    v.distance = std::max(glm::length(centre - cam.eye), 1.0);
    v.light_azimuth = first.view.light.azimuth, v.light_altitude = first.view.light.altitude;
    v.vertical_exaggeration = first.terrain.vertical_exaggeration;
    v.crease_min_score = first.lines.creases.min_score, v.ridge_min_score = first.lines.ridges.min_score;
    v.hachure_spacing_min = first.lines.hachures.spacing_min_px, v.hachure_spacing_max = first.lines.hachures.spacing_max_px;
    v.style = first.style.name;
    if (fs::is_regular_file(v.style)) v.style = fs::absolute(v.style).lexically_normal().string();
    v.visible = scene_visibility(base_);
    v.seed = first.style.seed;
    v.sea_level = first.terrain.sea_level;
    v.map_scale = first.view.map_scale;
}

PreviewSession::~PreviewSession() {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
}

Scene PreviewSession::load_view(const PreviewView& view) {
    {
        std::ofstream f(scene_file_, std::ios::binary | std::ios::trunc);
        f << scene_text(base_, dem_, view);
        if (!f.flush()) throw Error("cli", scene_file_, "cannot write the preview's scene file");
    }
    Scene scene = load_scene(scene_file_);
    validate_scene(scene);
    apply_map_scale(scene, PageOptions{});
    return scene;
}

PreviewFrame PreviewSession::draw(const PreviewView& view, double scale) {
    const auto t0 = Clock::now();
    PreviewView v = view;
    scale = std::clamp(scale, 0.05, 1.0);
    if (scale < 1.0) {
        v.width = std::max(16, int(std::lround(view.width * scale)));
        v.height = std::max(16, int(std::lround(view.height * scale)));
        if (v.map_scale > 0.0) v.map_scale *= double(view.width) / v.width;  // the same ground across
    }
    Scene scene = load_view(v);
    const double load_ms = ms_since(t0);
    RenderedFrame frame = render_scene_frame(scene, *context_, svg_in_memory(log_.verbose), log_, &keep_);
    log_.info("frame " + std::to_string(v.width) + "x" + std::to_string(v.height) + ": scene " +
              std::to_string(int(load_ms)) + " ms, hachures " + std::to_string(int(frame.drawn.hachure_ms)) +
              " ms, finish " + std::to_string(int(frame.written.finish_ms)) + " ms, SVG " +
              std::to_string(int(frame.written.write_ms)) + " ms, all " + std::to_string(int(ms_since(t0))) + " ms");
    if (scale >= 1.0) {
        camera_ = frame.drawn.camera;
        depth_ = std::move(frame.drawn.toward);
        exaggeration_ = scene.terrain.vertical_exaggeration;
    }
    PreviewFrame out;
    out.svg = std::move(frame.written.document);
    out.width = v.width, out.height = v.height;
    out.draw_ms = ms_since(t0);
    return out;
}

std::optional<PreviewPoint> PreviewSession::locate(double px, double py) const {
    const std::optional<glm::dvec3> p = unproject_pixel(camera_, depth_, px, py);
    if (!p) return std::nullopt;
    const double unit = linear_unit_of(meta_.crs_wkt);
    PreviewPoint out;
    out.x = (p->x + meta_.origin.x) / unit, out.y = (p->y + meta_.origin.y) / unit;
    out.elevation = p->z / exaggeration_;
    if (const auto ll = map_to_lon_lat(meta_.crs_wkt, {{out.x, out.y}}); !ll.empty()) out.lon = ll[0].x, out.lat = ll[0].y;
    return out;
}

std::string PreviewSession::save(const PreviewView& view) {
    write_file_atomically(save_path_, scene_text(base_, dem_, view));
    return save_path_;
}

std::vector<std::string> PreviewSession::export_files(const PreviewView& view, const std::vector<std::string>& extensions) {
    std::vector<std::string> paths;
    for (const std::string& ext : extensions) paths.push_back(fs::path(save_path_).replace_extension(ext).string());
    Scene scene = load_view(view);
    check_output_targets(paths, PageOptions{}, scene.view.camera.width, scene.view.camera.height);
    FrameOutput out;
    out.files = paths;
    render_scene_frame(scene, *context_, out, log_, &keep_);
    return paths;
}

}  // namespace penink
