#include "scene/terrain_view.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "core/error.hpp"
#include "input/dem_reader.hpp"
#include "input/scene_position.hpp"
#include "input/terrain_window.hpp"
#include "surface/grid_ground.hpp"

namespace penink {

namespace {
const std::string& scene_file(const Scene& s) { return s.file.empty() ? s.dem : s.file; }
}

std::vector<glm::dvec3> frame_samples(const Terrain& t) {
    std::vector<glm::dvec3> pts;
    const std::size_t step = std::max<std::size_t>(1, t.size() / 20000);  // enough to frame by
    for (std::size_t i = 0; i < t.size(); i += step)
        if (t.valid[i]) pts.emplace_back(t.pos[i]);
    for (int c = 0; c < t.cols; ++c)  // the edges decide the frame: keep all of them
        for (int r : {0, t.rows - 1})
            if (t.valid[t.index(c, r)]) pts.emplace_back(t.pos[t.index(c, r)]);
    for (int r = 0; r < t.rows; ++r)
        for (int c : {0, t.cols - 1})
            if (t.valid[t.index(c, r)]) pts.emplace_back(t.pos[t.index(c, r)]);
    return pts;
}

Terrain read_scene_dem(const Scene& scene) {
    DemOptions options;
    options.vertical_exaggeration = scene.vertical_exaggeration;
    Terrain dem = read_dem(scene.dem, options);
    if (const std::string w = missing_crs_warning(dem); !w.empty()) std::cerr << w << "\n";
    return dem;
}

Camera scene_camera(const Scene& scene, const Terrain& terrain) {
    const SceneCamera& sc = scene.camera;
    const double az = sc.azimuth.value_or(default_view_azimuth);
    const double alt = sc.altitude.value_or(default_view_altitude);
    if (!sc.position) return frame_points(frame_samples(terrain), az, alt, sc.fov, sc.width, sc.height, 0.9);
    glm::dvec3 lo, hi;
    terrain_bounds(terrain, lo, hi);
    Camera cam;
    const glm::dvec2 xy = parse_scene_position(*sc.position, terrain, scene_file(scene));
    cam.eye = {xy.x, xy.y, *sc.elevation * scene.vertical_exaggeration};
    cam.azimuth = az, cam.altitude = alt, cam.fov = sc.fov;
    cam.width = sc.width, cam.height = sc.height;
    fit_depth_range(cam, lo, hi);
    return cam;
}

Terrain terrain_for_view(Terrain terrain, Camera& cam, const Scene& scene, const Log& log) {
    double ground = 0.0;
    if (scene.camera.position && grid_ground_height(terrain, cam.eye.x, cam.eye.y, ground) && cam.eye.z <= ground) {
        std::ostringstream msg;
        msg << "camera is inside the terrain (elevation " << cam.eye.z / scene.vertical_exaggeration
            << " m, ground " << ground / scene.vertical_exaggeration << " m)";
        throw Error("scene", scene_file(scene), msg.str());
    }
    const GridWindow w = visible_window(terrain, view_projection(cam), 1);
    if (w.cols() < 2 || w.rows() < 2)
        throw Error("scene", scene_file(scene), "the camera sees no part of the DEM");
    const std::size_t cells = std::size_t(w.cols() - 1) * (w.rows() - 1);
    const std::size_t all = std::size_t(terrain.cols - 1) * (terrain.rows - 1);
    const bool whole = w.c0 == 0 && w.r0 == 0 && w.c1 == terrain.cols && w.r1 == terrain.rows;
    Terrain view = whole ? std::move(terrain) : crop_terrain(terrain, w);
    log.info("modelled " + std::to_string(cells) + " of " + std::to_string(all) + " DEM cells (window " +
             std::to_string(w.c0) + ".." + std::to_string(w.c1 - 1) + " x " + std::to_string(w.r0) + ".." +
             std::to_string(w.r1 - 1) + ")");
    glm::dvec3 lo, hi;
    terrain_bounds(view, lo, hi);
    fit_depth_range(cam, lo, hi);
    return view;
}

}  // namespace penink
