// The tone measure (tone_measure.hpp).
#include "lines/tone_measure.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <glm/gtc/matrix_inverse.hpp>

namespace penink {

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

// Separable Gaussian of a field weighted by w (0 where the field has no value).
std::vector<double> blur(const std::vector<double>& f, int w, int h, double sigma) {
    const int rad = std::max(1, int(std::ceil(3.0 * sigma)));
    std::vector<double> k(2 * rad + 1);
    for (int i = -rad; i <= rad; ++i) k[i + rad] = std::exp(-0.5 * i * i / (sigma * sigma));
    std::vector<double> tmp(f.size(), 0.0), out(f.size(), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0.0;
            for (int i = std::max(-rad, -x); i <= std::min(rad, w - 1 - x); ++i) s += k[i + rad] * f[std::size_t(y) * w + x + i];
            tmp[std::size_t(y) * w + x] = s;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0.0;
            for (int i = std::max(-rad, -y); i <= std::min(rad, h - 1 - y); ++i) s += k[i + rad] * tmp[std::size_t(y + i) * w + x];
            out[std::size_t(y) * w + x] = s;
        }
    return out;
}

}  // namespace

ToneImage ink_from_rgb(int width, int height, const std::vector<std::uint8_t>& rgb) {
    ToneImage out{width, height, std::vector<float>(std::size_t(width) * height, kNaN)};
    for (std::size_t i = 0; i < out.v.size() && 3 * i + 2 < rgb.size(); ++i)
        out.v[i] = float(1.0 - (0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2]) / 255.0);
    return out;
}

ToneImage target_tone(const ToneGrid& grid, const Camera& camera, const DepthImage& depth, const glm::dvec3& light) {
    ToneImage out{depth.width, depth.height, std::vector<float>(std::size_t(depth.width) * depth.height, kNaN)};
    if (grid.cols < 2 || grid.rows < 2 || !grid.pos) return out;
    // The affine grid: world xy = o + c a + r b.
    const glm::dvec2 o(grid.pos[0]), a = glm::dvec2(grid.pos[1]) - o, b = glm::dvec2(grid.pos[grid.cols]) - o;
    const double det = a.x * b.y - a.y * b.x;
    if (std::abs(det) < 1e-12) return out;
    const glm::dmat4 inv = glm::inverse(view_projection(camera));
    const bool ortho = is_orthographic(camera);
    const glm::dvec3 view = direction_from_angles(camera.azimuth, camera.altitude);
    const auto unproject = [&](double nx, double ny, double nz) {
        const glm::dvec4 p = inv * glm::dvec4(nx, ny, nz, 1.0);
        return glm::dvec3(p) / p.w;
    };
    const auto z_at = [&](int c, int r) { return double(grid.pos[std::size_t(r) * grid.cols + c].z) * grid.z_scale; };
    for (int y = 0; y < depth.height; ++y)
        for (int x = 0; x < depth.width; ++x) {
            const float d = depth.depth[std::size_t(y) * depth.width + x];
            if (!std::isfinite(d)) continue;
            const double nx = 2.0 * (x + 0.5) / camera.width - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / camera.height;
            const glm::dvec3 p0 = unproject(nx, ny, -1.0), p1 = unproject(nx, ny, 1.0);
            glm::dvec3 world;
            if (ortho) {  // depth along the view direction from the eye plane
                const glm::dvec3 on_plane = p0 - view * glm::dot(p0 - camera.eye, view);
                world = on_plane + view * double(d);
            } else {
                world = camera.eye + glm::normalize(p1 - camera.eye) * double(d);
            }
            const glm::dvec2 q = glm::dvec2(world) - o;
            double c = (q.x * b.y - q.y * b.x) / det, r = (a.x * q.y - a.y * q.x) / det;
            // a curvilinear grid (a geographic DEM in UTM): Newton steps on the cell's bilinear map
            for (int it = 0; it < 4; ++it) {
                const int cc = std::clamp(int(std::floor(c)), 0, grid.cols - 2), rr = std::clamp(int(std::floor(r)), 0, grid.rows - 2);
                const double u = c - cc, v = r - rr;
                const auto xy = [&](int i, int j) { return glm::dvec2(grid.pos[std::size_t(rr + j) * grid.cols + cc + i]); };
                const glm::dvec2 p00 = xy(0, 0), p10 = xy(1, 0), p01 = xy(0, 1), p11 = xy(1, 1);
                const glm::dvec2 at = (1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + (1 - u) * v * p01 + u * v * p11;
                const glm::dvec2 du = (1 - v) * (p10 - p00) + v * (p11 - p01), dv = (1 - u) * (p01 - p00) + u * (p11 - p10);
                const double dt = du.x * dv.y - du.y * dv.x;
                if (std::abs(dt) < 1e-12) break;
                const glm::dvec2 e = glm::dvec2(world) - at;
                c += (e.x * dv.y - e.y * dv.x) / dt, r += (du.x * e.y - du.y * e.x) / dt;
            }
            const int ci = int(std::floor(c)), ri = int(std::floor(r));
            if (ci < 0 || ri < 0 || ci + 1 >= grid.cols || ri + 1 >= grid.rows) continue;
            bool ok = true;
            for (int k = 0; k < 4; ++k) ok = ok && grid.valid[std::size_t(ri + k / 2) * grid.cols + ci + k % 2];
            if (!ok) continue;
            const double fc = c - ci, fr = r - ri;
            const double z00 = z_at(ci, ri), z10 = z_at(ci + 1, ri), z01 = z_at(ci, ri + 1), z11 = z_at(ci + 1, ri + 1);
            if ((1 - fr) * ((1 - fc) * z00 + fc * z10) + fr * ((1 - fc) * z01 + fc * z11) <= grid.sea_z) continue;
            const double zc = (1 - fr) * (z10 - z00) + fr * (z11 - z01), zr = (1 - fc) * (z01 - z00) + fc * (z11 - z10);
            // tangents along c and r: (a, zc), (b, zr); normal = their cross product, z up
            const auto xy = [&](int i, int j) { return glm::dvec2(grid.pos[std::size_t(ri + j) * grid.cols + ci + i]); };
            const glm::dvec2 tc = (1 - fr) * (xy(1, 0) - xy(0, 0)) + fr * (xy(1, 1) - xy(0, 1));
            const glm::dvec2 tr = (1 - fc) * (xy(0, 1) - xy(0, 0)) + fc * (xy(1, 1) - xy(1, 0));
            glm::dvec3 n = glm::cross(glm::dvec3(tc, zc), glm::dvec3(tr, zr));
            if (n.z < 0) n = -n;
            n = glm::normalize(n);
            out.v[std::size_t(y) * depth.width + x] = float(1.0 - std::max(0.0, glm::dot(n, light)));
        }
    return out;
}

ToneScore tone_score(const ToneImage& ink, const ToneImage& target, double sigma) {
    ToneScore s;
    s.sigma = sigma;
    const int w = target.width, h = target.height;
    const std::size_t n = std::size_t(w) * h;
    if (ink.width != w || ink.height != h || n == 0) return s;
    std::vector<double> m(n, 0.0), fi(n, 0.0), ft(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        if (std::isfinite(target.v[i]) && std::isfinite(ink.v[i])) m[i] = 1.0, fi[i] = ink.v[i], ft[i] = target.v[i];
    const std::vector<double> bm = blur(m, w, h, sigma), bi = blur(fi, w, h, sigma), bt = blur(ft, w, h, sigma);
    // inside: the square of half-side ceil(2 sigma) around the pixel is all terrain (integral image)
    const int rad = int(std::ceil(2.0 * sigma));
    // integral image of the mask for the box test
    std::vector<double> integ(std::size_t(w + 1) * (h + 1), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            integ[std::size_t(y + 1) * (w + 1) + x + 1] = m[std::size_t(y) * w + x] + integ[std::size_t(y) * (w + 1) + x + 1] +
                                                           integ[std::size_t(y + 1) * (w + 1) + x] - integ[std::size_t(y) * (w + 1) + x];
    double si = 0, st = 0, sii = 0, stt = 0, sit = 0;
    std::size_t count = 0;
    for (int y = rad; y < h - rad; ++y)
        for (int x = rad; x < w - rad; ++x) {
            const int x0 = x - rad, x1 = x + rad + 1, y0 = y - rad, y1 = y + rad + 1;
            const double box = integ[std::size_t(y1) * (w + 1) + x1] - integ[std::size_t(y0) * (w + 1) + x1] -
                               integ[std::size_t(y1) * (w + 1) + x0] + integ[std::size_t(y0) * (w + 1) + x0];
            if (box < double(x1 - x0) * (y1 - y0) - 0.5) continue;
            const std::size_t i = std::size_t(y) * w + x;
            const double I = bi[i] / bm[i], T = bt[i] / bm[i];
            si += I, st += T, sii += I * I, stt += T * T, sit += I * T;
            ++count;
        }
    s.pixels = count;
    if (count < 2) return s;
    const double N = double(count);
    const double mi = si / N, mt = st / N;
    const double vi = std::max(0.0, sii / N - mi * mi), vt = std::max(0.0, stt / N - mt * mt), cov = sit / N - mi * mt;
    s.mean_ink = mi, s.mean_target = mt;
    s.r = vi > 0 && vt > 0 ? cov / std::sqrt(vi * vt) : 0.0;
    const double C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
    s.ssim = std::abs((2 * mi * mt + C1) * (2 * cov + C2) / ((mi * mi + mt * mt + C1) * (vi + vt + C2)));
    return s;
}

std::array<double, 3> ink_by_depth_thirds(const ToneImage& ink, const ToneImage& target, const DepthImage& depth) {
    std::array<double, 3> sum{0, 0, 0}, count{0, 0, 0};
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    const std::size_t n = target.v.size();
    if (ink.v.size() != n || depth.depth.size() != n) return sum;
    for (std::size_t i = 0; i < n; ++i)
        if (std::isfinite(target.v[i])) lo = std::min(lo, depth.depth[i]), hi = std::max(hi, depth.depth[i]);
    if (!(hi > lo)) return sum;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(target.v[i]) || !std::isfinite(ink.v[i])) continue;
        const int k = std::min(2, int(3.0 * (depth.depth[i] - lo) / (hi - lo)));
        sum[k] += ink.v[i], count[k] += 1;
    }
    for (int k = 0; k < 3; ++k) sum[k] = count[k] > 0 ? sum[k] / count[k] : 0.0;
    return sum;
}

}  // namespace penink
