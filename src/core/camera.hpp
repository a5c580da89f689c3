// Camera (pinhole or orthographic) and sun in the world frame of conventions.md (x east, y north,
// z up; for a terrain the local frame is metres relative to Terrain::origin). Angles in degrees:
// azimuth clockwise from grid north, altitude above the horizontal; fov is the horizontal field of
// view of a perspective camera, view_width the ground width (metres) an orthographic image spans.
// Depth is the eye distance for a perspective camera and the distance along the view direction
// for an orthographic one (eye_depth): every pass that compares or attenuates by depth uses it.
#pragma once
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace penink {

enum class Projection { perspective, orthographic };

struct Camera {
    Projection projection = Projection::perspective;
    glm::dvec3 eye{0.0};          // world position (orthographic: centre of the view plane)
    double azimuth = 0.0;         // view direction, degrees clockwise from north
    double altitude = -30.0;      // degrees above horizontal, negative looks down
    double fov = 40.0;            // horizontal field of view, degrees (perspective)
    double view_width = 1.0;      // world units across the image width (orthographic)
    int width = 1000, height = 750;  // image, pixels
    double near_plane = 1.0, far_plane = 1e5;  // eye distances bounding the scene
};

struct Light {
    double azimuth = 315.0;   // degrees clockwise from north (NW sun, cartographic default)
    double altitude = 45.0;   // degrees above horizon
};

// Unit view direction for azimuth/altitude (degrees).
glm::dvec3 direction_from_angles(double azimuth_deg, double altitude_deg);
// Its inverse: the azimuth in [0, 360) and altitude in [-90, 90] (degrees) of a unit direction.
glm::dvec2 angles_from_direction(const glm::dvec3& unit);
// Unit vector from the surface towards the light.
glm::dvec3 light_vector(const Light& light);

glm::dmat4 view_matrix(const Camera& cam);        // world -> eye (right-handed, -z forward)
glm::dmat4 projection_matrix(const Camera& cam);  // eye -> clip (OpenGL, depth -1..1)
glm::dmat4 view_projection(const Camera& cam);

// World point -> image pixel (origin top-left, y down) and depth (eye_depth); false when behind.
bool project_to_pixel(const Camera& cam, const glm::dvec3& world, glm::dvec2& pixel, double& depth);

// project_to_pixel and world_per_pixel for many points of one camera: its matrices and its
// field of view's tangent made once, the arithmetic per point the same (the same results, bit
// for bit).
class PixelProjector {
public:
    explicit PixelProjector(const Camera& cam);
    bool operator()(const glm::dvec3& world, glm::dvec2& pixel, double& depth) const;
    double world_per_pixel(double depth) const;

private:
    glm::dmat4 view_, projection_;
    double width_, height_, view_width_, tan_half_fov_;
    bool orthographic_;
};

bool is_orthographic(const Camera& cam);
// Depth of a world point: eye distance (perspective) or distance along the view direction
// (orthographic), world units.
double eye_depth(const Camera& cam, const glm::dvec3& world);
// Unit vector from a world point towards the viewer: towards the eye (perspective) or against
// the view direction (orthographic). A surface faces the viewer where its normal has a positive
// dot product with it.
glm::dvec3 toward_viewer(const Camera& cam, const glm::dvec3& world);
// World units per image pixel at depth d: d * 2 tan(fov/2) / width (perspective), view_width /
// width at any depth (orthographic).
double world_per_pixel(const Camera& cam, double depth);

// What a framer is asked for: the view direction and the image as Camera has them (azimuth,
// altitude and fov in degrees, width and height in pixels; fov for perspective only), and how
// large the framed points appear: an orthographic image `view_width` world units across when it
// is > 0 (a map scale fixes it), else the points spanning `fill` of the image width, or of its
// height when that is the tighter fit.
struct Framing {
    double azimuth = 0.0, altitude = -30.0;
    double fov = 40.0;
    int width = 1000, height = 750;
    double view_width = 0.0;  // orthographic only
    double fill = 0.9;
};

// Perspective camera looking at the box [lo, hi] from f's azimuth/altitude, placed so the box is
// centred and spans f.fill of the image (conventions.md default: from the south-west, looking
// down).
Camera frame_box(const glm::dvec3& lo, const glm::dvec3& hi, const Framing& f);

// The same for a set of points (e.g. a model's vertices): the points themselves (not their box's
// empty corners) are centred in the image and span f.fill of its width or height.
Camera frame_points(const std::vector<glm::dvec3>& points, const Framing& f);

// Orthographic camera looking along f's azimuth/altitude with the points centred in the image,
// f.view_width across or fitted by f.fill (Framing). The eye lies on the plane touching the
// front of the points' box (a thousandth of its depth in front), so depths count from there and
// are positive.
Camera frame_points_orthographic(const std::vector<glm::dvec3>& points, const Framing& f);

// Moves an orthographic camera's eye along its view direction (the image unchanged) so its plane
// touches the front of the box [lo, hi], a thousandth of the box's depth in front, and fits the
// depth range to the box.
void place_orthographic_eye(Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi);

// Sets near/far from the box so everything in it lies inside the depth range (orthographic: the
// near plane may be as close as the eye plane).
void fit_depth_range(Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi);

}  // namespace penink
