// Places the camera of a scene over a DEM: the scene's UTM / lon,lat / x y position and
// elevation (metres above datum, scaled with the vertical exaggeration) or, with none, the whole
// DEM framed from the south-west, looking down at 30 degrees (conventions.md). Then crops the
// DEM to the nodes the view needs and fits near/far planes to what is left.
#pragma once
#include <vector>

#include "core/log.hpp"
#include "scene/scene.hpp"
#include "core/camera.hpp"
#include "input/terrain.hpp"

namespace penink {

inline constexpr double default_view_azimuth = 45.0;    // looking north-east: from the south-west
inline constexpr double default_view_altitude = -30.0;  // looking down

// The scene's DEM, read with its vertical exaggeration; a missing-CRS warning
// (missing_crs_warning, dem_reader.hpp) goes to stderr.
Terrain read_scene_dem(const Scene& scene);

Camera scene_camera(const Scene& scene, const Terrain& terrain);

// Points the automatic camera frames: every edge node and a subsample of the rest.
std::vector<glm::dvec3> frame_samples(const Terrain& terrain);

// The terrain cropped to what the camera sees (logged: cells used of all); throws
// penink::Error(stage "scene") when the camera is below the ground or sees none of the DEM.
// The whole terrain is moved, not copied, when the view sees all of it.
Terrain terrain_for_view(Terrain terrain, Camera& camera, const Scene& scene, const Log& log);

}  // namespace penink
