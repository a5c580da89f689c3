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
#include "surface/surface_mesh.hpp"
#include "surface/terrain_locator.hpp"

namespace penink {

inline constexpr double default_view_azimuth = 45.0;    // looking north-east: from the south-west
inline constexpr double default_view_altitude = -30.0;  // looking down

// The scene's DEM, read with its vertical exaggeration; a missing-CRS warning
// (missing_crs_warning, dem_reader.hpp) goes to stderr.
Terrain read_scene_dem(const Scene& scene);

Camera scene_camera(const Scene& scene, const Terrain& terrain);

// Points the automatic camera frames: every edge node and a subsample of the rest.
std::vector<glm::dvec3> frame_samples(const Terrain& terrain);

// Elevation (world z) of the terrain's flat triangles under plan points (x, y): the surface set up
// once for many queries (a flight path's cameras).
class TerrainGround {
public:
    explicit TerrainGround(const Terrain& terrain);
    TerrainGround(const TerrainGround&) = delete;  // the locator points at mesh_
    TerrainGround& operator=(const TerrainGround&) = delete;
    // False outside the DEM.
    bool height(double x, double y, double& z) const;

private:
    SurfaceMesh mesh_;
    TerrainLocator locator_;
};

// One query: TerrainGround(terrain).height(x, y, z).
bool ground_height(const Terrain& terrain, double x, double y, double& z);

// The terrain cropped to what the camera sees (logged: cells used of all); throws
// penink::Error(stage "scene") when the camera is below the ground or sees none of the DEM.
Terrain terrain_for_view(const Terrain& terrain, Camera& camera, const Scene& scene, const Log& log);

}  // namespace penink
