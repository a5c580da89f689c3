// What a mesh drawing makes of its scene keys (conventions.md: meshes in their own units, y up
// unless the scene says otherwise), read at load into Scene::mesh (scene.hpp: MeshSettings):
// [mesh] file, up; [camera] eye, target, up (vectors in the mesh's own frame, before the y-up ->
// z-up conversion; roll is not supported: `up` must be roughly the mesh's up axis), fov, width,
// height, azimuth/altitude for the auto-framed view; [light] direction (towards the light, mesh
// frame; default: light at the camera); [pels] enabled, threshold, smoothing, normal_filter,
// line_strength; [features] enabled, crease_angle (degrees); [textures] enabled, threshold,
// library, scale, confidence, material.NAME = "bricks". Here: the Camera of the z-up world and the
// texture library's folder.
#pragma once
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/scene.hpp"
#include "core/camera.hpp"

namespace penink {

// The mesh file a scene draws: [mesh] file, or the bare mesh path given as the input.
const std::string& mesh_file(const Scene& scene);

// Mesh-frame vector -> z-up world frame: (x, y, z) -> (x, -z, y) when y_up, else unchanged.
glm::dvec3 mesh_to_world(const MeshSettings& ms, const glm::dvec3& v);

// The camera: eye/target converted to eye, azimuth, altitude (fov, size from [camera]), or
// the box [lo, hi] (world frame) framed from [camera] azimuth/altitude (default from the
// south-west, 30 degrees down) filling 90 % of the width. Near/far fitted to the box.
// Throws Error("scene", ...) when only one of eye/target is given, they coincide, or `up` is
// not roughly the mesh's up axis.
Camera mesh_camera(const Scene& scene, const std::vector<glm::vec3>& points,
                   const glm::dvec3& lo, const glm::dvec3& hi);

// Folder of the texture library: [textures] library, else $PENINK_TEXTURES, else the first of
// <scene dir>/textures, <mesh dir>/../textures, <exe dir>/../examples/textures,
// <exe dir>/../share/penink/textures that exists; "" when none.
std::string find_texture_library(const Scene& scene);

}  // namespace penink
