// Scene keys of a mesh drawing (conventions.md: meshes in their own units, y up unless the scene
// says otherwise): [mesh] file, up; [camera] eye, target, up (vectors in the mesh's own frame,
// before the y-up -> z-up conversion; roll is not supported: `up` must be roughly the mesh's up
// axis), fov, width, height, azimuth/altitude for the auto-framed view; [light] direction
// (towards the light, mesh frame; default: light at the camera); [pels] enabled, threshold,
// smoothing, normal_filter, line_strength; [features] enabled, crease_angle (degrees); [textures] enabled, threshold, library,
// scale, confidence, material.NAME = "bricks". Also the Camera and light of the z-up world.
#pragma once
#include <map>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "scene/scene.hpp"
#include "core/camera.hpp"

namespace penink {

struct MeshScene {
    std::string path;             // mesh file (resolved relative to the scene file)
    bool y_up = true;             // [mesh] up = "y" (default) or "z"
    int subdivide = 0;            // [mesh] subdivide: Loop subdivision iterations (0..4)
    std::optional<glm::dvec3> eye, target;  // [camera], mesh frame
    glm::dvec3 up{0, 1, 0};                 // [camera] up, mesh frame (default: the mesh's up)
    std::optional<glm::dvec3> light;        // [light] direction, mesh frame, towards the light
    bool pels = true;
    float pel_threshold = 0.1f;   // tau on the normalised |grad phi| (0..1)
    int smoothing = 0;            // Laplacian normal smoothing iterations
    // Xie et al., "Photic Extremum Lines" post-processing (docs/reproduction.md, PELs), both in
    // mean edge lengths of the mesh drawn (after subdivision), so they follow its resolution:
    float normal_filter = 0.0f;   // sigma of the Gaussian normal filter; 0 = none
    float line_strength = 0.0f;   // least integral of g along a PEL line; 0 = keep every line
    bool features = true;
    float crease_angle = 40.0f;   // degrees
    bool textures = true;
    float texture_threshold = 0.65f;
    float texture_confidence = 0.6f;       // 1 = exact strokes, 0 = very sketchy
    std::optional<float> texture_scale;    // cluster cell, mesh units (default: from the size)
    std::string texture_library;           // folder of *.txt clusters ("" = search, see below)
    std::map<std::string, std::string> materials;  // material name -> texture name
};

// The mesh keys of a scene (defaults for a bare mesh path). Throws penink::Error("scene", file,
// ...) on a bad key, e.g. "[camera] eye: expected 3 numbers", "[mesh] up: use \"y\" or \"z\"".
MeshScene load_mesh_scene(const Scene& scene);

// Mesh-frame vector -> z-up world frame: (x, y, z) -> (x, -z, y) when y_up, else unchanged.
glm::dvec3 mesh_to_world(const MeshScene& ms, const glm::dvec3& v);

// The camera: eye/target converted to eye, azimuth, altitude (fov, size from [camera]), or
// the box [lo, hi] (world frame) framed from [camera] azimuth/altitude (default from the
// south-west, 30 degrees down) filling 90 % of the width. Near/far fitted to the box.
// Throws Error("scene", ...) when only one of eye/target is given, they coincide, or `up` is
// not roughly the mesh's up axis.
Camera mesh_camera(const Scene& scene, const MeshScene& ms, const std::vector<glm::vec3>& points,
                   const glm::dvec3& lo, const glm::dvec3& hi);

// Folder of the texture library: [textures] library, else $PENINK_TEXTURES, else the first of
// <scene dir>/textures, <mesh dir>/../textures, <exe dir>/../examples/textures,
// <exe dir>/../share/penink/textures that exists; "" when none.
std::string find_texture_library(const Scene& scene, const MeshScene& ms);

}  // namespace penink
