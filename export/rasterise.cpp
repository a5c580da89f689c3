// Capsule-coverage stroke rasteriser and even-odd polygon fill (rasterise.hpp).
#include "export/rasterise.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace penink {

namespace {

struct Canvas {
    int w = 0, h = 0;
    std::vector<float> rgb;          // composited colour, 0..1 per channel
    std::vector<float> cov;          // coverage of the shape being drawn
    std::vector<std::uint32_t> touched;  // pixels with cov > 0

    void cover(int x, int y, float c) {
        float& v = cov[size_t(y) * w + x];
        if (v == 0.0f && c > 0.0f) touched.push_back(std::uint32_t(y) * w + x);
        v = std::max(v, c);
    }
    void add(int x, int y, float c) {  // accumulates (fill sub-scanlines)
        float& v = cov[size_t(y) * w + x];
        if (v == 0.0f && c > 0.0f) touched.push_back(std::uint32_t(y) * w + x);
        v += c;
    }
    // Composites the current shape in `color` with `alpha`, then clears the coverage.
    void paint(Rgb color, double alpha) {
        const float c[3] = {color.r / 255.0f, color.g / 255.0f, color.b / 255.0f};
        for (std::uint32_t i : touched) {
            const float a = std::min(cov[i], 1.0f) * float(alpha);
            for (int k = 0; k < 3; ++k) rgb[3 * i + k] += (c[k] - rgb[3 * i + k]) * a;
            cov[i] = 0.0f;
        }
        touched.clear();
    }
};

// Box-filtered coverage of a pixel whose centre lies `d` from the centre line of a pen of
// half-width `r`: the overlap of [d - 0.5, d + 0.5] with [-r, r].
float pen_coverage(float d, float r) {
    return std::clamp(std::min(d + 0.5f, r) - std::max(d - 0.5f, -r), 0.0f, 1.0f);
}

// A capsule whose radius runs from ra at a to rb at b (the pen at the nearest point of the
// segment: within a hundredth of a pixel of the exact tapered hull for the slow width changes
// of tapered strokes).
void capsule(Canvas& cv, glm::vec2 a, glm::vec2 b, float ra, float rb) {
    const float r = std::max(ra, rb);
    const int x0 = std::max(0, int(std::floor(std::min(a.x, b.x) - r - 1)));
    const int x1 = std::min(cv.w - 1, int(std::ceil(std::max(a.x, b.x) + r + 1)));
    const int y0 = std::max(0, int(std::floor(std::min(a.y, b.y) - r - 1)));
    const int y1 = std::min(cv.h - 1, int(std::ceil(std::max(a.y, b.y) + r + 1)));
    const glm::vec2 ab = b - a;
    const float len2 = ab.x * ab.x + ab.y * ab.y;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const glm::vec2 p(x + 0.5f, y + 0.5f);
            const glm::vec2 ap = p - a;
            const float t = len2 > 0 ? std::clamp((ap.x * ab.x + ap.y * ab.y) / len2, 0.0f, 1.0f) : 0.0f;
            const glm::vec2 q = ap - ab * t;
            const float c = pen_coverage(std::sqrt(q.x * q.x + q.y * q.y), ra + (rb - ra) * t);
            if (c > 0.0f) cv.cover(x, y, c);
        }
}

void polyline(Canvas& cv, const std::vector<glm::vec2>& pts, float r) {
    if (pts.size() == 1) capsule(cv, pts[0], pts[0], r, r);
    for (size_t i = 1; i < pts.size(); ++i) capsule(cv, pts[i - 1], pts[i], r, r);
}

// Splits a polyline into its dash "on" pieces (lengths already in output pixels).
std::vector<std::vector<glm::vec2>> dash_pieces(const std::vector<glm::vec2>& pts,
                                                const std::vector<double>& dash) {
    std::vector<std::vector<glm::vec2>> pieces(1);
    size_t k = 0;
    double left = dash[0];
    bool on = true;
    pieces[0].push_back(pts[0]);
    for (size_t i = 1; i < pts.size(); ++i) {
        glm::vec2 a = pts[i - 1];
        double seg = glm::length(pts[i] - a);
        const glm::vec2 dir = seg > 0 ? (pts[i] - a) / float(seg) : glm::vec2(0);
        while (seg >= left) {
            a += dir * float(left);
            seg -= left;
            if (on) pieces.back().push_back(a);
            on = !on;
            if (on) pieces.push_back({a});
            k = (k + 1) % dash.size();
            left = dash[k];
        }
        left -= seg;
        if (on) pieces.back().push_back(pts[i]);
    }
    std::erase_if(pieces, [](const auto& piece) { return piece.size() < 2; });
    return pieces;
}

std::vector<glm::vec2> to_output(const std::vector<glm::vec2>& pts, const RasterTransform& t) {
    std::vector<glm::vec2> out(pts.size());
    for (size_t i = 0; i < pts.size(); ++i)
        out[i] = glm::vec2(pts[i].x * t.scale + t.offset_x, pts[i].y * t.scale + t.offset_y);
    return out;
}

void stroke(Canvas& cv, const StyledPath& p, const RasterTransform& t) {
    const std::vector<glm::vec2> pts = to_output(p.points, t);
    const float r = float(0.5 * p.width * t.scale);
    if (!p.widths.empty()) {  // variable width: each segment's pen from its ends' widths
        const auto radius = [&](size_t i) { return float(0.5 * p.widths[i] * t.scale); };
        if (pts.size() == 1) capsule(cv, pts[0], pts[0], radius(0), radius(0));
        for (size_t i = 1; i < pts.size(); ++i) capsule(cv, pts[i - 1], pts[i], radius(i - 1), radius(i));
    } else if (p.dash.empty() || pts.size() < 2) {
        polyline(cv, pts, r);
    } else {
        std::vector<double> dash = p.dash;
        for (double& d : dash) d *= t.scale;
        for (const auto& piece : dash_pieces(pts, dash)) polyline(cv, piece, r);
    }
    cv.paint(p.color, p.opacity);
}

// Adds the horizontal span [xa, xb) with weight `wgt` to row y, fractional at the ends.
void span(Canvas& cv, int y, float xa, float xb, float wgt) {
    xa = std::clamp(xa, 0.0f, float(cv.w));
    xb = std::clamp(xb, 0.0f, float(cv.w));
    if (xb <= xa) return;
    const int ia = int(xa), ib = int(xb);
    if (ia == ib) return cv.add(ia, y, (xb - xa) * wgt);
    cv.add(ia, y, (ia + 1 - xa) * wgt);
    for (int x = ia + 1; x < ib; ++x) cv.add(x, y, wgt);
    if (ib < cv.w && xb > ib) cv.add(ib, y, (xb - ib) * wgt);
}

void fill_rings(Canvas& cv, const std::vector<Ring>& rings, const RasterTransform& t) {
    constexpr int sub = 4;
    std::vector<std::vector<float>> xs(size_t(cv.h) * sub);
    for (const Ring& ring : rings) {
        if (ring.size() < 3) continue;
        const std::vector<glm::vec2> r = to_output(ring, t);
        for (size_t i = 0; i < r.size(); ++i) {
            const glm::vec2 a = r[i], b = r[(i + 1) % r.size()];
            if (a.y == b.y) continue;
            const float lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
            const int s0 = std::max(0, int(std::ceil(lo * sub - 0.5f)));
            const int s1 = std::min(cv.h * sub - 1, int(std::ceil(hi * sub - 0.5f)) - 1);
            for (int s = s0; s <= s1; ++s) {
                const float y = (s + 0.5f) / sub;
                xs[s].push_back(a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y));
            }
        }
    }
    for (int s = 0; s < cv.h * sub; ++s) {
        std::sort(xs[s].begin(), xs[s].end());
        for (size_t i = 0; i + 1 < xs[s].size(); i += 2) span(cv, s / sub, xs[s][i], xs[s][i + 1], 1.0f / sub);
    }
}

}  // namespace

RgbImage rasterise(const StyledDrawing& d, const RasterTransform& t) {
    Canvas cv;
    cv.w = t.width;
    cv.h = t.height;
    cv.cov.assign(size_t(cv.w) * cv.h, 0.0f);
    cv.rgb.resize(size_t(cv.w) * cv.h * 3);
    for (size_t i = 0; i < size_t(cv.w) * cv.h; ++i) {
        cv.rgb[3 * i] = d.background.r / 255.0f;
        cv.rgb[3 * i + 1] = d.background.g / 255.0f;
        cv.rgb[3 * i + 2] = d.background.b / 255.0f;
    }
    for (const StyledLayer& l : d.layers) {
        if (!l.fill.empty()) {
            fill_rings(cv, l.fill, t);
            cv.paint(l.fill_color, 1.0);
        }
        for (const StyledGroup& g : l.groups)
            for (const StyledPath& p : g.paths) stroke(cv, p, t);
    }
    RgbImage img{cv.w, cv.h, std::vector<std::uint8_t>(cv.rgb.size())};
    for (size_t i = 0; i < cv.rgb.size(); ++i)
        img.rgb[i] = static_cast<std::uint8_t>(std::lround(std::clamp(cv.rgb[i], 0.0f, 1.0f) * 255.0f));
    return img;
}

}  // namespace penink
