#include "lines/line_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "core/error.hpp"

namespace penink {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double sample_step = 0.1;

struct Segment {
    glm::dvec2 a, b;
};

double point_segment_distance(glm::dvec2 p, const Segment& s) {
    const glm::dvec2 d = s.b - s.a;
    const double dd = glm::dot(d, d);
    const double t = dd > 0 ? std::clamp(glm::dot(p - s.a, d) / dd, 0.0, 1.0) : 0.0;
    return glm::length(p - (s.a + d * t));
}

// Uniform grid of reference segments (cells of `cell` px) for nearest-segment queries.
class SegmentGrid {
public:
    SegmentGrid(const std::vector<ImagePolyline>& lines, double cell) : cell_(cell) {
        for (const ImagePolyline& l : lines) {
            for (std::size_t i = 0; i + 1 < l.size(); ++i) segs_.push_back({glm::dvec2(l[i]), glm::dvec2(l[i + 1])});
            if (l.size() == 1) segs_.push_back({glm::dvec2(l[0]), glm::dvec2(l[0])});
        }
        if (segs_.empty()) return;
        lo_ = hi_ = segs_[0].a;
        for (const Segment& s : segs_) lo_ = glm::min(lo_, glm::min(s.a, s.b)), hi_ = glm::max(hi_, glm::max(s.a, s.b));
        nx_ = int((hi_.x - lo_.x) / cell_) + 1, ny_ = int((hi_.y - lo_.y) / cell_) + 1;
        cells_.resize(std::size_t(nx_) * ny_);
        for (std::size_t i = 0; i < segs_.size(); ++i) {
            const glm::dvec2 a = glm::min(segs_[i].a, segs_[i].b), b = glm::max(segs_[i].a, segs_[i].b);
            for (int y = cy(a.y); y <= cy(b.y); ++y)
                for (int x = cx(a.x); x <= cx(b.x); ++x) cells_[std::size_t(y) * nx_ + x].push_back(i);
        }
    }
    // Exact distance to the nearest segment (+inf when there is none).
    double nearest(glm::dvec2 p) const {
        if (segs_.empty()) return inf;
        const int px = std::clamp(cx(p.x), 0, nx_ - 1), py = std::clamp(cy(p.y), 0, ny_ - 1);
        const double outside = glm::length(glm::max(glm::max(lo_ - p, p - hi_), glm::dvec2(0.0)));
        double best = inf;
        for (int r = 0; r <= std::max(nx_, ny_); ++r) {
            // Every segment in ring r or beyond is at least (r - 1) cells away from p's cell.
            if (best < inf && (r - 1) * cell_ > best + outside) break;
            for (int y = py - r; y <= py + r; ++y)
                for (int x = px - r; x <= px + r; ++x) {
                    if (std::max(std::abs(x - px), std::abs(y - py)) != r) continue;
                    if (x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
                    for (std::size_t i : cells_[std::size_t(y) * nx_ + x])
                        best = std::min(best, point_segment_distance(p, segs_[i]));
                }
        }
        return best;
    }

private:
    int cx(double x) const { return int(std::floor((x - lo_.x) / cell_)); }
    int cy(double y) const { return int(std::floor((y - lo_.y) / cell_)); }
    double cell_;
    std::vector<Segment> segs_;
    glm::dvec2 lo_{0.0}, hi_{0.0};
    int nx_ = 0, ny_ = 0;
    std::vector<std::vector<std::size_t>> cells_;
};

// Distance from p to the nearest set pixel centre of the mask, searched in square rings.
double nearest_pixel(const PixelMask& m, glm::dvec2 p) {
    const int px = int(std::floor(p.x)), py = int(std::floor(p.y));
    double best = inf;
    const int rmax = m.width + m.height + std::abs(px) + std::abs(py);
    for (int r = 0; r <= rmax; ++r) {
        if (best < inf && r - 1 > best) break;
        for (int y = py - r; y <= py + r; ++y) {
            if (y < 0 || y >= m.height) continue;
            const int step = (y == py - r || y == py + r) ? 1 : 2 * r;
            for (int x = px - r; x <= px + r; x += std::max(step, 1)) {
                if (x < 0 || x >= m.width || !m.on[std::size_t(y) * m.width + x]) continue;
                best = std::min(best, glm::length(glm::dvec2(x + 0.5, y + 0.5) - p));
            }
        }
    }
    return best;
}

struct Sample {
    glm::dvec2 p;
    double weight;  // length it stands for, px
};

std::vector<Sample> sample_polylines(const std::vector<ImagePolyline>& lines) {
    std::vector<Sample> out;
    for (const ImagePolyline& l : lines)
        for (std::size_t i = 0; i + 1 < l.size(); ++i) {
            const glm::dvec2 a(l[i]), b(l[i + 1]);
            const double len = glm::length(b - a);
            const int n = std::max(1, int(std::ceil(len / sample_step)));
            for (int k = 0; k < n; ++k) out.push_back({a + (b - a) * ((k + 0.5) / n), len / n});
        }
    return out;
}

}  // namespace

const ToleranceScore& LineAccuracy::at(double tolerance) const {
    for (const ToleranceScore& s : scores)
        if (s.tolerance == tolerance) return s;
    throw Error("lines", "", "no accuracy score at tolerance " + std::to_string(tolerance) + " px",
                ExitCode::internal);
}

LineAccuracy line_accuracy(const PixelMask& drawn, const std::vector<ImagePolyline>& reference,
                           const std::vector<double>& tolerances) {
    check_mask(drawn, "drawn lines");
    LineAccuracy acc;
    const SegmentGrid grid(reference, 4.0);
    std::vector<double> d_drawn;
    for (int y = 0; y < drawn.height; ++y)
        for (int x = 0; x < drawn.width; ++x)
            if (drawn.on[std::size_t(y) * drawn.width + x]) d_drawn.push_back(grid.nearest({x + 0.5, y + 0.5}));
    acc.drawn_pixels = d_drawn.size();
    const std::vector<Sample> samples = sample_polylines(reference);
    std::vector<double> d_ref(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        d_ref[i] = nearest_pixel(drawn, samples[i].p);
        acc.reference_length += samples[i].weight;
    }
    for (double tau : tolerances) {
        ToleranceScore s{tau, 1.0, 1.0};
        if (!d_drawn.empty())
            s.precision = double(std::count_if(d_drawn.begin(), d_drawn.end(), [&](double d) { return d <= tau; })) / d_drawn.size();
        if (acc.reference_length > 0) {
            double near = 0;
            for (std::size_t i = 0; i < samples.size(); ++i) near += d_ref[i] <= tau ? samples[i].weight : 0.0;
            s.recall = near / acc.reference_length;
        }
        acc.scores.push_back(s);
    }
    for (double d : d_drawn) acc.mean_drawn_to_reference += d / double(d_drawn.size());
    for (std::size_t i = 0; i < samples.size(); ++i)
        acc.mean_reference_to_drawn += d_ref[i] * samples[i].weight / acc.reference_length;
    return acc;
}

PixelMask rasterize_polylines(const std::vector<ImagePolyline>& lines, int width, int height) {
    PixelMask m;
    m.width = width, m.height = height;
    m.on.assign(std::size_t(std::max(width, 0)) * std::max(height, 0), 0);
    const auto mark = [&](glm::dvec2 p) {
        const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
        if (x >= 0 && y >= 0 && x < width && y < height) m.on[std::size_t(y) * width + x] = 1;
    };
    for (const ImagePolyline& l : lines) {
        if (l.size() == 1) mark(glm::dvec2(l[0]));
        for (std::size_t i = 0; i + 1 < l.size(); ++i) {
            const glm::dvec2 a(l[i]), b(l[i + 1]);
            const int n = std::max(1, int(std::ceil(glm::length(b - a) / sample_step)));
            for (int k = 0; k <= n; ++k) mark(a + (b - a) * (double(k) / n));
        }
    }
    return m;
}

PixelMask rasterize_strokes(const std::vector<Stroke>& strokes, int width, int height) {
    std::vector<ImagePolyline> lines;
    lines.reserve(strokes.size());
    for (const Stroke& s : strokes) lines.push_back(s.points);
    return rasterize_polylines(lines, width, height);
}

}  // namespace penink
