#include "scene/flight_frames.hpp"

#include <algorithm>
#include <sstream>

#include "core/error.hpp"
#include "input/scene_position.hpp"
#include "input/terrain_window.hpp"
#include "surface/grid_ground.hpp"

namespace penink {

namespace {

// The "what" of an error from another stage, re-reported against the CSV line.
std::string error_what(const Error& e) {
    const std::string prefix = format_error(e.stage(), e.file(), "");
    const std::string msg = e.what();
    return msg.rfind(prefix, 0) == 0 ? msg.substr(prefix.size()) : msg;
}

bool window_empty(const GridWindow& w) { return w.cols() < 2 || w.rows() < 2; }

GridWindow window_union(const std::vector<GridWindow>& windows) {
    GridWindow u;
    bool any = false;
    for (const GridWindow& w : windows) {
        if (window_empty(w)) continue;
        if (!any) u = w, any = true;
        u.c0 = std::min(u.c0, w.c0), u.r0 = std::min(u.r0, w.r0);
        u.c1 = std::max(u.c1, w.c1), u.r1 = std::max(u.r1, w.r1);
    }
    return u;
}
}  // namespace

Camera flight_camera(const Scene& scene, const Terrain& dem, const FlightRecord& r, const std::string& csv) {
    Camera cam;
    glm::dvec2 xy;
    try {
        xy = parse_scene_position(r.position, dem, csv);
    } catch (const Error& e) {
        throw Error("batch", csv, "line " + std::to_string(r.line) + ": " + error_what(e));
    }
    cam.eye = {xy.x, xy.y, r.elevation * scene.vertical_exaggeration};
    cam.azimuth = r.azimuth, cam.altitude = r.altitude, cam.fov = scene.camera.fov;
    cam.width = scene.camera.width, cam.height = scene.camera.height;
    double ground = 0.0;
    if (grid_ground_height(dem, xy.x, xy.y, ground) && cam.eye.z <= ground) {
        std::ostringstream m;
        m << "line " << r.line << ": camera is inside the terrain (elevation " << r.elevation << " m, ground "
          << ground / scene.vertical_exaggeration << " m)";
        throw Error("batch", csv, m.str());
    }
    return cam;
}

Scene frame_scene(const Scene& scene, const FlightRecord& r) {
    Scene s = scene;
    if (r.light_azimuth) s.light.azimuth = *r.light_azimuth;
    if (r.light_altitude) s.light.altitude = *r.light_altitude;
    if (r.min_score) s.creases.min_score = *r.min_score;
    return s;
}

GridWindow union_window(const Terrain& dem, const std::vector<Camera>& cameras) {
    std::vector<GridWindow> windows;
    for (const Camera& c : cameras) windows.push_back(visible_window(dem, view_projection(c), 1));
    return window_union(windows);
}

Flight plan_flight(const Scene& scene, const std::string& csv, bool whole_dem, const Log& log) {
    Flight f;
    f.records = read_flight_path(csv);
    f.dem = read_scene_dem(scene);
    std::vector<GridWindow> windows;
    for (const FlightRecord& r : f.records) {
        f.cameras.push_back(flight_camera(scene, f.dem, r, csv));
        windows.push_back(visible_window(f.dem, view_projection(f.cameras.back()), 1));
        if (window_empty(windows.back()))
            throw Error("batch", csv, "line " + std::to_string(r.line) + ": the camera sees no part of the DEM");
    }
    const GridWindow w = whole_dem ? GridWindow{0, 0, f.dem.cols, f.dem.rows} : window_union(windows);
    f.model = crop_terrain(f.dem, w);
    glm::dvec3 lo, hi;
    terrain_bounds(f.model, lo, hi);
    for (Camera& c : f.cameras) fit_depth_range(c, lo, hi);
    log.info("modelled " + std::to_string(std::size_t(w.cols() - 1) * (w.rows() - 1)) + " of " +
             std::to_string(std::size_t(f.dem.cols - 1) * (f.dem.rows - 1)) + " DEM cells for " +
             std::to_string(f.records.size()) + " frames");
    return f;
}

}  // namespace penink
