// Pinhole camera and sun in the world frame of conventions.md (x east, y north, z up; for a
// terrain the local frame is metres relative to Terrain::origin). Angles in degrees: azimuth
// clockwise from grid north, altitude above the horizontal; fov is the horizontal field of view.
#pragma once
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace penink {

struct Camera {
    glm::dvec3 eye{0.0};          // world position
    double azimuth = 0.0;         // view direction, degrees clockwise from north
    double altitude = -30.0;      // degrees above horizontal, negative looks down
    double fov = 40.0;            // horizontal field of view, degrees
    int width = 1000, height = 750;  // image, pixels
    double near_plane = 1.0, far_plane = 1e5;  // eye distances bounding the scene
};

struct Light {
    double azimuth = 315.0;   // degrees clockwise from north (NW sun, cartographic default)
    double altitude = 45.0;   // degrees above horizon
};

// Unit view direction for azimuth/altitude (degrees).
glm::dvec3 direction_from_angles(double azimuth_deg, double altitude_deg);
// Unit vector from the surface towards the light.
glm::dvec3 light_vector(const Light& light);

glm::dmat4 view_matrix(const Camera& cam);        // world -> eye (right-handed, -z forward)
glm::dmat4 projection_matrix(const Camera& cam);  // eye -> clip (OpenGL, depth -1..1)
glm::dmat4 view_projection(const Camera& cam);

// World point -> image pixel (origin top-left, y down) and eye distance; false when behind.
bool project_to_pixel(const Camera& cam, const glm::dvec3& world, glm::dvec2& pixel, double& depth);

// Camera looking at the box [lo, hi] from azimuth/altitude, placed so the box is centred and
// spans `fill` of the image width, or of its height when that is the tighter fit
// (conventions.md default: from the south-west, looking down).
Camera frame_box(const glm::dvec3& lo, const glm::dvec3& hi, double azimuth, double altitude,
                 double fov, int width, int height, double fill = 0.9);

// The same for a set of points (e.g. a model's vertices): the points themselves (not their box's
// empty corners) are centred in the image and span `fill` of its width or height.
Camera frame_points(const std::vector<glm::dvec3>& points, double azimuth, double altitude, double fov,
                    int width, int height, double fill = 0.9);

// Sets near/far from the box so everything in it lies inside the depth range.
void fit_depth_range(Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi);

}  // namespace penink
