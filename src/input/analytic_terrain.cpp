#include "input/analytic_terrain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/parallel_chunks.hpp"

namespace penink {

namespace {

constexpr double pi = 3.14159265358979323846;

double gauss(double h, double s, double dx, double dy) { return h * std::exp(-(dx * dx + dy * dy) / (2.0 * s * s)); }

// The Gaussian bumps a shape is the sum of (x, y, height, sigma); empty for the other shapes.
struct Bump {
    double x, y, h, s;
};
std::vector<Bump> bumps(const AnalyticTerrain& s) {
    switch (s.shape) {
        case AnalyticShape::gaussian_hill: return {{0.0, 0.0, s.height, s.width}};
        case AnalyticShape::two_hills:
            return {{0.0, 0.0, s.height, s.width}, {0.8 * s.width, 4.0 * s.width, 1.6 * s.height, 1.5 * s.width}};
        case AnalyticShape::saddle:
            return {{-1.5 * s.width, 0.0, s.height, s.width}, {1.5 * s.width, 0.0, s.height, s.width}};
        default: return {};
    }
}

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

// n . (eye - p) up to the positive factor |(-f_x, -f_y, 1)|.
double facing(const AnalyticTerrain& s, const HeightFunction& f, const glm::dvec3& eye, double x, double y) {
    const glm::dvec2 g = analytic_gradient(s, x, y);
    return -g.x * (eye.x - x) - g.y * (eye.y - y) + (eye.z - f(x, y));
}

std::vector<std::vector<glm::dvec3>> hill_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    // Every crossing along each ray from the axis; the k-th crossings of neighbouring rays form
    // branch k (convex silhouette first, then concave ones behind it at grazing views).
    const HeightFunction f = analytic_height(s);
    std::vector<std::vector<glm::dvec3>> branches(4);
    const int n = 7200;
    for (int i = 0; i <= n; ++i) {
        const double th = 2 * pi * (i % n) / n, c = std::cos(th), sn = std::sin(th);
        const auto g = [&](double r) { return facing(s, f, eye, r * c, r * sn); };
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
    const double e = s.half_extent;
    const auto g = [&](double x) { return facing(s, f, eye, x, 0.0); };
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

// Zero set of g on a square grid by marching squares: crossings on cell edges refined by
// bisection, segments chained through shared crossings into curves.
std::vector<std::vector<glm::dvec3>> zero_set_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    const HeightFunction f = analytic_height(s);
    const double e = s.half_extent;
    const double step = std::max(std::min(2.0, s.width / 16.0), 2.0 * e / 4000.0);
    const int n = int(std::ceil(2.0 * e / step)) + 1;
    const auto node_x = [&](int i) { return -e + i * step; };
    std::vector<double> g(std::size_t(n) * n);
    parallel_chunks(std::size_t(n), 64, [&](std::size_t j0, std::size_t j1) {
        for (std::size_t j = j0; j < j1; ++j)
            for (int i = 0; i < n; ++i) g[j * n + i] = facing(s, f, eye, node_x(i), node_x(int(j)));
    });
    const auto val = [&](int i, int j) { return g[std::size_t(j) * n + i]; };
    // Crossing on edge id: 2 * node + 0 (towards +x) or + 1 (towards +y).
    std::unordered_map<std::uint64_t, int> crossing_of;
    std::vector<glm::dvec3> crossing;
    std::vector<std::array<int, 2>> links;  // per crossing: up to two neighbouring crossings
    const auto crossing_on = [&](int i, int j, int dir) {
        const std::uint64_t id = 2 * (std::uint64_t(j) * n + i) + dir;
        const auto [it, fresh] = crossing_of.try_emplace(id, int(crossing.size()));
        if (fresh) {
            const double x0 = node_x(i), y0 = node_x(j);
            const double t = bisect([&](double u) { return facing(s, f, eye, x0 + (dir ? 0.0 : u), y0 + (dir ? u : 0.0)); },
                                    0.0, step);
            const double x = x0 + (dir ? 0.0 : t), y = y0 + (dir ? t : 0.0);
            crossing.push_back({x, y, f(x, y)});
            links.push_back({-1, -1});
        }
        return it->second;
    };
    const auto link = [&](int a, int b) {
        for (int k : {a, b}) {
            const int other = k == a ? b : a;
            (links[k][0] < 0 ? links[k][0] : links[k][1]) = other;
        }
    };
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const bool s00 = val(i, j) > 0, s10 = val(i + 1, j) > 0, s01 = val(i, j + 1) > 0, s11 = val(i + 1, j + 1) > 0;
            if (s00 == s10 && s00 == s01 && s00 == s11) continue;
            std::vector<int> c;  // crossings in the order bottom, right, top, left
            if (s00 != s10) c.push_back(crossing_on(i, j, 0));
            if (s10 != s11) c.push_back(crossing_on(i + 1, j, 1));
            if (s01 != s11) c.push_back(crossing_on(i, j + 1, 0));
            if (s00 != s01) c.push_back(crossing_on(i, j, 1));
            if (c.size() == 2) {
                link(c[0], c[1]);
            } else {  // both diagonals' signs differ: pair by the sign at the cell centre
                const bool centre = facing(s, f, eye, node_x(i) + 0.5 * step, node_x(j) + 0.5 * step) > 0;
                if (centre == s00) link(c[0], c[1]), link(c[2], c[3]);
                else link(c[0], c[3]), link(c[1], c[2]);
            }
        }
    // Walk the chains: open ones from their ends first, then the closed loops.
    std::vector<std::vector<glm::dvec3>> out;
    std::vector<std::uint8_t> used(crossing.size(), 0);
    const auto walk = [&](int start) {
        std::vector<glm::dvec3> curve;
        for (int prev = -1, cur = start; cur >= 0 && !used[cur];) {
            used[cur] = 1;
            curve.push_back(crossing[cur]);
            const int next = links[cur][0] != prev ? links[cur][0] : links[cur][1];
            prev = cur, cur = next;
        }
        if (curve.size() >= 2) out.push_back(std::move(curve));
    };
    for (std::size_t k = 0; k < crossing.size(); ++k)
        if (!used[k] && (links[k][0] < 0 || links[k][1] < 0)) walk(int(k));
    for (std::size_t k = 0; k < crossing.size(); ++k)
        if (!used[k]) {
            const std::size_t first = out.size();
            walk(int(k));
            if (out.size() > first) out.back().push_back(out.back().front());  // close the loop
        }
    return out;
}

bool inside(const AnalyticTerrain& s, const glm::dvec3& q) {
    return std::abs(q.x) <= s.half_extent && std::abs(q.y) <= s.half_extent;
}

bool smooth(AnalyticShape shape) { return shape != AnalyticShape::cliff && shape != AnalyticShape::hemisphere; }

// Eye -> p stays above the surface (stopping 0.5 % short of p, where the ray grazes it) and, on a
// smooth surface, the surface is not concave along the ray at p (then it lies above the grazing
// ray right before p).
bool visible(const HeightFunction& f, const AnalyticTerrain& s, const glm::dvec3& eye, const glm::dvec3& p) {
    const glm::dvec3 d = glm::normalize(p - eye);
    if (smooth(s.shape)) {
        const double h = std::min(0.5, s.width / 100.0);
        const glm::dvec3 a = p - d * h, b = p + d * h;
        if ((f(a.x, a.y) - a.z) + (f(b.x, b.y) - b.z) > 0.0) return false;
    }
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

HeightFunction analytic_height(const AnalyticTerrain& s) {
    const double h = s.height, w = s.width;
    switch (s.shape) {
        case AnalyticShape::plain: return [](double, double) { return 0.0; };
        case AnalyticShape::hemisphere:
            return [=](double x, double y) { return std::sqrt(std::max(0.0, w * w - x * x - y * y)); };
        case AnalyticShape::cliff: return [=](double, double y) { return y <= 0.0 ? h : 0.0; };
        case AnalyticShape::ridge: return [=](double x, double) { return gauss(h, w, x, 0.0); };
        case AnalyticShape::smooth_cliff: return [=](double, double y) { return 0.5 * h * (1.0 - std::tanh(y / w)); };
        case AnalyticShape::gaussian_hill:
        case AnalyticShape::two_hills:
        case AnalyticShape::saddle:
            return [b = bumps(s)](double x, double y) {
                double z = 0.0;
                for (const Bump& k : b) z += gauss(k.h, k.s, x - k.x, y - k.y);
                return z;
            };
    }
    return [](double, double) { return 0.0; };
}

glm::dvec2 analytic_gradient(const AnalyticTerrain& s, double x, double y) {
    const double h = s.height, w = s.width;
    switch (s.shape) {
        case AnalyticShape::plain:
        case AnalyticShape::cliff: return {0.0, 0.0};
        case AnalyticShape::hemisphere: {
            const double z2 = w * w - x * x - y * y;
            return z2 > 0.0 ? glm::dvec2(-x, -y) / std::sqrt(z2) : glm::dvec2(0.0);
        }
        case AnalyticShape::ridge: return {-x / (w * w) * gauss(h, w, x, 0.0), 0.0};
        case AnalyticShape::smooth_cliff: {
            const double c = std::cosh(y / w);
            return {0.0, -0.5 * h / (w * c * c)};
        }
        case AnalyticShape::gaussian_hill:
        case AnalyticShape::two_hills:
        case AnalyticShape::saddle: {
            glm::dvec2 g(0.0);
            for (const Bump& k : bumps(s)) g -= gauss(k.h, k.s, x - k.x, y - k.y) / (k.s * k.s) * glm::dvec2(x - k.x, y - k.y);
            return g;
        }
    }
    return {0.0, 0.0};
}

Terrain terrain_from_function(int cols, int rows, double spacing, const HeightFunction& f) {
    Terrain t;
    t.cols = cols, t.rows = rows;
    t.source = "synthetic";
    t.pos.resize(t.size());
    t.valid.assign(t.size(), 1);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            const double x = (c - (cols - 1) * 0.5) * spacing, y = ((rows - 1) * 0.5 - r) * spacing;
            t.pos[t.index(c, r)] = glm::vec3(float(x), float(y), float(f(x, y)));
        }
    }
    return t;
}

Terrain analytic_grid(const AnalyticTerrain& shape, double spacing) {
    const int n = 2 * int(std::lround(shape.half_extent / spacing)) + 1;
    Terrain t = terrain_from_function(n, n, spacing, analytic_height(shape));
    for (const glm::vec3& p : t.pos) {
        t.elevation_min = std::min(t.elevation_min, double(p.z));
        t.elevation_max = std::max(t.elevation_max, double(p.z));
    }
    return t;
}

std::vector<std::vector<glm::dvec3>> analytic_contour_generator(const AnalyticTerrain& s, const glm::dvec3& eye) {
    switch (s.shape) {
        case AnalyticShape::plain: return {};
        case AnalyticShape::gaussian_hill: return hill_generator(s, eye);
        case AnalyticShape::hemisphere: return sphere_generator(s, eye);
        case AnalyticShape::cliff: return cliff_generator(s, eye);
        case AnalyticShape::ridge: return ridge_generator(s, eye);
        case AnalyticShape::two_hills:
        case AnalyticShape::smooth_cliff:
        case AnalyticShape::saddle: return zero_set_generator(s, eye);
    }
    return {};
}

std::vector<std::vector<glm::vec2>> analytic_silhouettes(const AnalyticTerrain& s, const Camera& cam,
                                                         bool only_surface_behind) {
    const HeightFunction f = analytic_height(s);
    std::vector<std::vector<glm::vec2>> out;
    for (const std::vector<glm::dvec3>& curve : analytic_contour_generator(s, cam.eye)) {
        // Per point: its pixel, or none where it is not a visible silhouette point.
        std::vector<glm::dvec2> px(curve.size());
        std::vector<std::uint8_t> ok(curve.size(), 0);
        parallel_chunks(curve.size(), 256, [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) {
                const glm::dvec3& p = curve[i];
                double depth = 0;
                ok[i] = inside(s, p) && project_to_pixel(cam, p, px[i], depth) && px[i].x >= 0 && px[i].y >= 0 &&
                        px[i].x <= cam.width && px[i].y <= cam.height && visible(f, s, cam.eye, p) &&
                        (!only_surface_behind || surface_behind(f, s, cam.eye, p));
            }
        });
        std::vector<glm::vec2> run;
        const auto flush = [&] {
            if (run.size() >= 2) out.push_back(run);
            run.clear();
        };
        for (std::size_t i = 0; i < curve.size(); ++i) {
            if (!ok[i] || (!run.empty() && glm::length(glm::dvec2(run.back()) - px[i]) > 5.0)) flush();
            if (ok[i]) run.push_back(glm::vec2(px[i]));
        }
        flush();
    }
    return out;
}

std::optional<AnalyticCase> analytic_case(const std::string& name, int width, int height) {
    AnalyticCase c;
    c.name = name;
    AnalyticTerrain& s = c.shape;
    glm::dvec3 eye(0.0);
    double azimuth = 0.0, altitude = 0.0, top = 0.0;
    if (name == "hill") {
        eye = {0.0, -1300.0, 450.0}, altitude = -10.0, top = s.height;
    } else if (name == "two-hills") {
        s.shape = AnalyticShape::two_hills, s.half_extent = 3000.0;
        eye = {0.0, -1300.0, 700.0}, altitude = -14.0, top = 1.6 * s.height;
    } else if (name == "smooth-cliff") {
        s.shape = AnalyticShape::smooth_cliff, s.height = 100.0, s.width = 15.0, s.half_extent = 1000.0;
        c.spacing = 5.0;
        eye = {-150.0, -600.0, 260.0}, azimuth = 15.0, altitude = -15.0, top = s.height;
    } else if (name == "saddle") {
        s.shape = AnalyticShape::saddle, s.half_extent = 3000.0;
        eye = {0.0, -1300.0, 520.0}, altitude = -12.0, top = s.height;
    } else {
        return std::nullopt;
    }
    Camera& cam = c.camera;
    cam.eye = eye, cam.azimuth = azimuth, cam.altitude = altitude, cam.fov = 40.0;
    cam.width = width, cam.height = height;
    fit_depth_range(cam, {-s.half_extent, -s.half_extent, 0.0}, {s.half_extent, s.half_extent, top});
    return c;
}

std::string analytic_case_names() { return "hill, two-hills, smooth-cliff, saddle"; }

}  // namespace penink
