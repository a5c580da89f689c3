#include "core/camera.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/common.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace penink {

namespace {
constexpr double deg = 3.14159265358979323846 / 180.0;
}

glm::dvec3 direction_from_angles(double azimuth_deg, double altitude_deg) {
    const double a = azimuth_deg * deg, h = altitude_deg * deg;
    return {std::sin(a) * std::cos(h), std::cos(a) * std::cos(h), std::sin(h)};
}

glm::dvec2 angles_from_direction(const glm::dvec3& u) {
    double az = std::atan2(u.x, u.y) / deg;
    if (az < 0.0) az += 360.0;
    return {az, std::asin(std::clamp(u.z, -1.0, 1.0)) / deg};
}

glm::dvec3 light_vector(const Light& light) { return direction_from_angles(light.azimuth, light.altitude); }

glm::dmat4 view_matrix(const Camera& cam) {
    const glm::dvec3 d = direction_from_angles(cam.azimuth, cam.altitude);
    // Straight up/down views keep "up" as the azimuth direction on the ground.
    glm::dvec3 up(0, 0, 1);
    if (std::abs(d.z) > 0.999) up = direction_from_angles(cam.azimuth, 0.0) * (d.z < 0 ? 1.0 : -1.0);
    return glm::lookAt(cam.eye, cam.eye + d, up);
}

glm::dmat4 projection_matrix(const Camera& cam) {
    const double aspect = double(cam.width) / double(cam.height);
    if (is_orthographic(cam)) {
        const double hw = cam.view_width * 0.5, hh = hw / aspect;
        return glm::ortho(-hw, hw, -hh, hh, cam.near_plane, cam.far_plane);
    }
    const double fovy = 2.0 * std::atan(std::tan(cam.fov * deg / 2.0) / aspect);
    return glm::perspective(fovy, aspect, cam.near_plane, cam.far_plane);
}

glm::dmat4 view_projection(const Camera& cam) { return projection_matrix(cam) * view_matrix(cam); }

bool project_to_pixel(const Camera& cam, const glm::dvec3& world, glm::dvec2& pixel, double& depth) {
    return PixelProjector(cam)(world, pixel, depth);
}

PixelProjector::PixelProjector(const Camera& cam)
    : view_(view_matrix(cam)), projection_(projection_matrix(cam)), width_(cam.width), height_(cam.height),
      view_width_(cam.view_width), tan_half_fov_(std::tan(cam.fov * deg / 2.0)), orthographic_(is_orthographic(cam)) {}

bool PixelProjector::operator()(const glm::dvec3& world, glm::dvec2& pixel, double& depth) const {
    const glm::dvec4 e = view_ * glm::dvec4(world, 1.0);
    if (e.z >= 0.0) return false;
    const glm::dvec4 c = projection_ * e;
    pixel = {(c.x / c.w * 0.5 + 0.5) * width_, (0.5 - c.y / c.w * 0.5) * height_};
    depth = orthographic_ ? -e.z : glm::length(glm::dvec3(e));
    return true;
}

double PixelProjector::world_per_pixel(double depth) const {
    if (orthographic_) return view_width_ / width_;
    return depth * 2.0 * tan_half_fov_ / width_;
}

bool is_orthographic(const Camera& cam) { return cam.projection == Projection::orthographic; }

double eye_depth(const Camera& cam, const glm::dvec3& world) {
    if (is_orthographic(cam)) return glm::dot(world - cam.eye, direction_from_angles(cam.azimuth, cam.altitude));
    return glm::length(world - cam.eye);
}

glm::dvec3 toward_viewer(const Camera& cam, const glm::dvec3& world) {
    if (is_orthographic(cam)) return -direction_from_angles(cam.azimuth, cam.altitude);
    const glm::dvec3 v = cam.eye - world;
    const double l = glm::length(v);
    return l > 0.0 ? v / l : glm::dvec3(0.0);
}

double world_per_pixel(const Camera& cam, double depth) {
    if (is_orthographic(cam)) return cam.view_width / double(cam.width);
    return depth * 2.0 * std::tan(cam.fov * deg / 2.0) / double(cam.width);
}

Camera frame_box(const glm::dvec3& lo, const glm::dvec3& hi, const Framing& f) {
    std::vector<glm::dvec3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    return frame_points(corners, f);
}

Camera frame_points(const std::vector<glm::dvec3>& points, const Framing& f) {
    Camera cam;
    cam.azimuth = f.azimuth, cam.altitude = f.altitude, cam.fov = f.fov;
    cam.width = f.width, cam.height = f.height;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::dvec3 centre = (lo + hi) * 0.5, d = direction_from_angles(f.azimuth, f.altitude);
    // Start far enough to see the bounding sphere; then, step by step, slide the eye sideways so
    // the projected points are centred in the image, and scale the distance so they span f.fill
    // of the width, or of the height when that is the tighter fit.
    const double radius = glm::length(hi - lo) * 0.5;
    const double tan_x = std::tan(f.fov * deg / 2.0), tan_y = tan_x * double(f.height) / double(f.width);
    double dist = radius / std::sin(std::atan(std::min(tan_x, tan_y)));
    glm::dvec3 shift(0.0);
    for (int it = 0; it < 12; ++it) {  // converges geometrically; 12 steps reach ~1e-3
        cam.eye = centre + shift - d * dist;
        fit_depth_range(cam, lo, hi);
        const glm::dmat4 v = view_matrix(cam);
        double xl = 1e300, xr = -1e300, yl = 1e300, yr = -1e300;  // projected extent, tan units
        for (const glm::dvec3& p : points) {
            const glm::dvec4 e = v * glm::dvec4(p, 1.0);
            const double sx = e.x / std::max(-e.z, 1e-9), sy = e.y / std::max(-e.z, 1e-9);
            xl = std::min(xl, sx), xr = std::max(xr, sx), yl = std::min(yl, sy), yr = std::max(yr, sy);
        }
        const glm::dmat4 inv = glm::inverse(v);  // camera right and up in the world
        shift += (glm::dvec3(inv[0]) * (xl + xr) + glm::dvec3(inv[1]) * (yl + yr)) * (0.5 * dist);
        dist *= std::max((xr - xl) / (2.0 * tan_x * f.fill), (yr - yl) / (2.0 * tan_y * f.fill));
        dist = std::max(dist, radius * 1.05);
    }
    cam.eye = centre + shift - d * dist;
    fit_depth_range(cam, lo, hi);
    return cam;
}

Camera frame_points_orthographic(const std::vector<glm::dvec3>& points, const Framing& f) {
    Camera cam;
    cam.projection = Projection::orthographic;
    cam.azimuth = f.azimuth, cam.altitude = f.altitude;
    cam.width = f.width, cam.height = f.height;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    if (points.empty()) lo = hi = glm::dvec3(0.0);
    const glm::dvec3 centre = (lo + hi) * 0.5;
    cam.eye = centre;
    const glm::dmat4 v = view_matrix(cam);  // rotation about the centre: x right, y up, -z forward
    double xl = 1e300, xr = -1e300, yl = 1e300, yr = -1e300;
    for (const glm::dvec3& p : points) {
        const glm::dvec4 e = v * glm::dvec4(p, 1.0);
        xl = std::min(xl, e.x), xr = std::max(xr, e.x), yl = std::min(yl, e.y), yr = std::max(yr, e.y);
    }
    if (points.empty()) xl = xr = yl = yr = 0.0;
    const double aspect = double(f.width) / double(f.height);
    cam.view_width = f.view_width > 0.0 ? f.view_width : std::max({xr - xl, (yr - yl) * aspect, 1e-9}) / f.fill;
    const glm::dmat4 inv = glm::inverse(v);
    const glm::dvec3 shift = (glm::dvec3(inv[0]) * (xl + xr) + glm::dvec3(inv[1]) * (yl + yr)) * 0.5;
    cam.eye = centre + shift;
    place_orthographic_eye(cam, lo, hi);
    return cam;
}

void place_orthographic_eye(Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 d = direction_from_angles(cam.azimuth, cam.altitude);
    double smin = 1e300, smax = -1e300;  // the box's corners along d, from the eye
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        smin = std::min(smin, glm::dot(p - cam.eye, d)), smax = std::max(smax, glm::dot(p - cam.eye, d));
    }
    const double margin = 1e-3 * (smax - smin + cam.view_width) + 1e-3;  // the eye plane touches the box's front
    cam.eye += d * (smin - margin);
    fit_depth_range(cam, lo, hi);
}

void fit_depth_range(Camera& cam, const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dmat4 v = view_matrix(cam);
    double zmin = 1e300, zmax = 0.0;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        const double z = -(v * glm::dvec4(p, 1.0)).z;
        zmin = std::min(zmin, z), zmax = std::max(zmax, z);
    }
    if (is_orthographic(cam)) {  // depth is linear: a thin slab around the box
        const double pad = 0.01 * (zmax - zmin) + 1e-3;
        cam.near_plane = std::max(zmin - pad, 1e-6);
        cam.far_plane = std::max(zmax + pad, cam.near_plane + 1e-3);
        return;
    }
    cam.far_plane = std::max(zmax * 1.01, 1.0);
    cam.near_plane = std::max({zmin * 0.5, cam.far_plane * 1e-4, 1e-3});
}

}  // namespace penink
