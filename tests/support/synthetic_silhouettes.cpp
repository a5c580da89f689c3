#include "support/synthetic_silhouettes.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace penink {

namespace {

constexpr double pi = 3.14159265358979323846;

// Root of g in [a, b] (g(a), g(b) of opposite signs) by 60 bisections.
template <typename G>
double bisect(G&& g, double a, double b) {
    const bool ga = g(a) > 0;
    for (int k = 0; k < 60; ++k) {
        const double m = 0.5 * (a + b);
        ((g(m) > 0) == ga ? a : b) = m;
    }
    return 0.5 * (a + b);
}

std::vector<std::vector<glm::dvec3>> hill_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    // Every crossing along each ray from the axis; the k-th crossings of neighbouring rays form
    // branch k (convex silhouette first, then concave ones behind it at grazing views).
    const HeightFunction f = analytic_height(s);
    const double sig2 = s.width * s.width;
    std::vector<std::vector<glm::dvec3>> branches(4);
    const int n = 7200;
    for (int i = 0; i <= n; ++i) {
        const double th = 2 * pi * (i % n) / n, c = std::cos(th), sn = std::sin(th);
        const auto g = [&](double r) {
            const double x = r * c, y = r * sn, z = f(x, y), k = z / sig2;  // grad f = -k (x, y)
            return k * x * (eye.x - x) + k * y * (eye.y - y) + (eye.z - z);
        };
        std::size_t k = 0;
        for (double r = 0.5; r < 6 * s.width && k < branches.size(); r += 0.5)
            if ((g(r) > 0) != (g(r + 0.5) > 0)) {
                const double root = bisect(g, r, r + 0.5);
                branches[k++].push_back({root * c, root * sn, f(root * c, root * sn)});
            }
    }
    return branches;
}

std::vector<std::vector<glm::dvec3>> sphere_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    const double r = s.width, d = glm::length(eye);
    if (d <= r) return {};
    const glm::dvec3 u = eye / d;
    const glm::dvec3 m = u * (r * r / d);
    const double rho = r * std::sqrt(1.0 - r * r / (d * d));
    const glm::dvec3 a = glm::normalize(std::abs(u.z) < 0.9 ? glm::cross(u, glm::dvec3(0, 0, 1)) : glm::cross(u, glm::dvec3(1, 0, 0)));
    const glm::dvec3 b = glm::cross(u, a);
    std::vector<std::vector<glm::dvec3>> out(1);
    for (int i = 0; i <= 7200; ++i) {
        const double th = 2 * pi * (i % 7200) / 7200;
        const glm::dvec3 p = m + rho * (std::cos(th) * a + std::sin(th) * b);
        if (p.z > 0.0) out.back().push_back(p);
        else if (!out.back().empty()) out.emplace_back();
    }
    return out;
}

std::vector<std::vector<glm::dvec3>> ridge_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    const HeightFunction f = analytic_height(s);
    const double w2 = s.width * s.width, e = s.half_extent;
    const auto g = [&](double x) {  // n . (eye - p) with n ~ (-f'(x), 0, 1), f' = -x f / w^2
        const double z = f(x, 0.0);
        return (x * z / w2) * (eye.x - x) + (eye.z - z);
    };
    std::vector<std::vector<glm::dvec3>> out;
    for (double x = -e; x < e; x += 0.5) {
        if ((g(x) > 0) == (g(x + 0.5) > 0)) continue;
        const double root = bisect(g, x, x + 0.5);
        std::vector<glm::dvec3> line;
        for (double y = -e; y <= e; y += 2.0) line.push_back({root, y, f(root, 0.0)});
        out.push_back(std::move(line));
    }
    return out;
}

std::vector<std::vector<glm::dvec3>> cliff_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    // Top edge: plateau (normal up) and cliff face (normal +y) face opposite ways when the eye
    // is above the plateau on the high side or below it on the low side. Foot: face and plain.
    std::vector<std::vector<glm::dvec3>> out;
    const auto edge = [&](double z) {
        std::vector<glm::dvec3> line;
        for (double x = -s.half_extent; x <= s.half_extent; x += 2.0) line.push_back({x, 0.0, z});
        out.push_back(std::move(line));
    };
    if ((eye.z > s.height) != (eye.y > 0.0)) edge(s.height);
    if (eye.y < 0.0 && eye.z > 0.0) edge(0.0);
    return out;
}

bool inside(const AnalyticTerrain& s, const glm::dvec3& q) {
    return std::abs(q.x) <= s.half_extent && std::abs(q.y) <= s.half_extent;
}

// Eye -> p stays above the surface (stopping 0.5 % short of p, where the ray grazes it).
bool visible(const HeightFunction& f, const AnalyticTerrain& s, const glm::dvec3& eye, const glm::dvec3& p) {
    const int n = std::max(100, int(glm::length(p - eye)));
    for (int i = 1; i < n; ++i) {
        const glm::dvec3 q = eye + (p - eye) * (double(i) / n * 0.995);
        if (inside(s, q) && q.z < f(q.x, q.y) - 0.01) return false;
    }
    return true;
}

// The ray from the eye through p meets the surface beyond p inside the extent.
bool surface_behind(const HeightFunction& f, const AnalyticTerrain& s, const glm::dvec3& eye, const glm::dvec3& p) {
    const glm::dvec3 d = glm::normalize(p - eye);
    for (double t = 2.0; t < 4.0 * s.half_extent; t += 1.0) {
        const glm::dvec3 q = p + d * t;
        if (!inside(s, q)) return false;
        if (q.z < f(q.x, q.y)) return true;
    }
    return false;
}

}  // namespace

std::vector<std::vector<glm::dvec3>> analytic_contour_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    switch (s.shape) {
        case AnalyticShape::plain: return {};
        case AnalyticShape::gaussian_hill: return hill_generator(s, eye);
        case AnalyticShape::hemisphere: return sphere_generator(s, eye);
        case AnalyticShape::cliff: return cliff_generator(s, eye);
        case AnalyticShape::ridge: return ridge_generator(s, eye);
    }
    return {};
}

std::vector<std::vector<glm::vec2>> analytic_silhouettes(const AnalyticTerrain& s, const Camera& cam,
                                                         bool only_surface_behind) {
    const HeightFunction f = analytic_height(s);
    std::vector<std::vector<glm::vec2>> out;
    for (const std::vector<glm::dvec3>& curve : analytic_contour_generator(s, cam.eye)) {
        std::vector<glm::vec2> run;
        const auto flush = [&] {
            if (run.size() >= 2) out.push_back(run);
            run.clear();
        };
        for (const glm::dvec3& p : curve) {
            glm::dvec2 px;
            double depth = 0;
            const bool ok = inside(s, p) && project_to_pixel(cam, p, px, depth) && px.x >= 0 && px.y >= 0 &&
                            px.x <= cam.width && px.y <= cam.height && visible(f, s, cam.eye, p) &&
                            (!only_surface_behind || surface_behind(f, s, cam.eye, p));
            if (!ok || (!run.empty() && glm::length(glm::dvec2(run.back()) - px) > 5.0)) flush();
            if (ok) run.push_back(glm::vec2(px));
        }
        flush();
    }
    return out;
}

}  // namespace penink
