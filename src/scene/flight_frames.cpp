#include "scene/flight_frames.hpp"

#include <algorithm>
#include <sstream>

#include "core/error.hpp"
#include "input/scene_position.hpp"
#include "surface/grid_ground.hpp"

namespace penink {

namespace {

// The "what" of an error from another stage, re-reported against the CSV line.
std::string error_what(const Error& e) {
    const std::string prefix = format_error(e.stage(), e.file(), "");
    const std::string msg = e.what();
    return msg.rfind(prefix, 0) == 0 ? msg.substr(prefix.size()) : msg;
}

}  // namespace

Camera flight_camera(const Scene& scene, const SceneTerrain& dem, const FlightRecord& r, const std::string& csv) {
    Camera cam;
    glm::dvec2 xy;
    try {
        xy = parse_scene_position(r.position, dem.stored.meta, csv);
    } catch (const Error& e) {
        throw Error("batch", csv, "line " + std::to_string(r.line) + ": " + error_what(e));
    }
    cam.eye = {xy.x, xy.y, r.elevation * scene.terrain.vertical_exaggeration};
    cam.azimuth = r.azimuth, cam.altitude = r.altitude, cam.fov = scene.view.camera.fov;
    cam.width = scene.view.camera.width, cam.height = scene.view.camera.height;
    double ground = 0.0;
    if (grid_ground_height(dem.nodes(), xy.x, xy.y, ground) && cam.eye.z <= ground) {
        std::ostringstream m;
        m << "line " << r.line << ": camera is inside the terrain (elevation " << r.elevation << " m, ground "
          << ground / scene.terrain.vertical_exaggeration << " m)";
        throw Error("batch", csv, m.str());
    }
    return cam;
}

Scene frame_scene(const Scene& scene, const FlightRecord& r) {
    Scene s = scene;
    if (r.light_azimuth) s.view.light.azimuth = *r.light_azimuth;
    if (r.light_altitude) s.view.light.altitude = *r.light_altitude;
    if (r.min_score) s.lines.creases.min_score = *r.min_score;
    return s;
}

Flight plan_flight(Scene& scene, const std::string& csv, bool whole_dem, const Log& log) {
    Flight f;
    if (scene.view.camera.projection == Projection::orthographic)
        throw Error("batch", scene.source.file.empty() ? scene.source.dem : scene.source.file,
                    "a flight's cameras are perspective: [camera] projection = \"orthographic\" (or --map) is for one view");
    f.records = read_flight_path(csv);
    f.dem = open_scene_terrain(scene, log);
    std::vector<LodView> views;
    for (const FlightRecord& r : f.records) {
        f.cameras.push_back(flight_camera(scene, f.dem, r, csv));
        views.push_back(scene_view_window(f.dem, f.cameras.back()));
        if (views.back().window.cols() < 2)
            throw Error("batch", csv, "line " + std::to_string(r.line) + ": the camera sees no part of the DEM");
    }
    const LodView u = view_union(f.dem, views, whole_dem);
    f.model = frame_terrain(f.dem, u);
    for (Camera& c : f.cameras) fit_depth_range(c, u.lo, u.hi);
    const GridWindow& w = u.window;
    const Terrain& dem = f.dem.stored.meta;
    log.info("modelled " + std::to_string(std::size_t(w.cols() - 1) * (w.rows() - 1)) + " of " +
             std::to_string(std::size_t(dem.cols - 1) * (dem.rows - 1)) + " DEM cells for " +
             std::to_string(f.records.size()) + " frames");
    return f;
}

}  // namespace penink
