#include "scene/orbit.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace penink {

std::vector<Camera> orbit_cameras(const Camera& start, const glm::dvec3& lo, const glm::dvec3& hi, int frames) {
    std::vector<Camera> out;
    // The axis passes through the point of the view ray nearest the box's centre: the point the
    // camera looks at stays where the first frame has it.
    const glm::dvec3 d = direction_from_angles(start.azimuth, start.altitude);
    const glm::dvec3 centre = start.eye + glm::dot(0.5 * (lo + hi) - start.eye, d) * d;
    const double dx = start.eye.x - centre.x, dy = start.eye.y - centre.y;
    for (int k = 0; k < frames; ++k) {
        const double turn = 360.0 * k / frames;
        const double a = turn * std::acos(-1.0) / 180.0, c = std::cos(a), s = std::sin(a);
        Camera cam = start;
        cam.eye.x = centre.x + dx * c + dy * s;  // clockwise: bearing of (dx, dy) grows by `turn`
        cam.eye.y = centre.y - dx * s + dy * c;
        cam.azimuth = std::fmod(start.azimuth + turn, 360.0);
        fit_depth_range(cam, lo, hi);
        out.push_back(cam);
    }
    return out;
}

}  // namespace penink
