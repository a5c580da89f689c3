// Hachures traced along the fall line and spaced by tone (hachures.hpp).
#include "lines/hachures.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>

#include "core/stroke_taper.hpp"
#include "lines/hachure_coverage.hpp"
#include "lines/mesh_visibility.hpp"
#include "lines/simplify.hpp"

namespace penink {

bool hachure_tone_named(const std::string& name, HachureTone& out) {
    for (HachureTone t : {HachureTone::light, HachureTone::slope, HachureTone::blend})
        if (name == hachure_tone_name(t)) {
            out = t;
            return true;
        }
    return false;
}

const char* hachure_tone_name(HachureTone tone) {
    switch (tone) {
        case HachureTone::slope: return "slope";
        case HachureTone::blend: return "blend";
        case HachureTone::light: break;
    }
    return "light";
}

HachureParams hachure_defaults() {
    HachureParams p;
    p.enabled = true;
    p.tone = HachureTone::light;
    p.blend = 0.5;
    p.contrast = 1.0;
    p.gamma = 1.0;
    p.min_slope_deg = 1.0;
    p.spacing_min_px = 1.6;
    p.spacing_max_px = 16.0;
    p.width_px = 0.0;
    p.d_test = 0.6;
    p.yield_px = 0.5;  // a hair's clearance: wider clearances lighten the shaded slopes the creases gather on (docs/tone.md)
    p.max_turn_deg = 25.0;
    p.aerial = 0.6;
    p.min_length_px = 4.0;
    return p;
}

double hachure_pen_width(double tone, double width, double weight_min, double weight_max) {
    const double c = std::pow(std::clamp(tone, 0.0, 1.0), hachure_width_exponent);
    return width * (weight_min + (weight_max - weight_min) * c);
}

double hachure_tone(HachureTone tone, double blend, const glm::dvec3& normal, const glm::dvec3& light) {
    const auto lit = [&] { return 1.0 - std::max(0.0, glm::dot(normal, light)); };
    const auto steep = [&] { return std::min(1.0, glm::degrees(std::acos(std::clamp(normal.z, -1.0, 1.0))) / 45.0); };
    switch (tone) {
        case HachureTone::slope: return steep();
        case HachureTone::blend: return (1.0 - blend) * lit() + blend * steep();
        case HachureTone::light: break;
    }
    return lit();
}

namespace {

// Parallel streamlines lie d_sep apart (seeded at d_sep beside each other), so d_sep = w / t;
// where they converge and end at d_test x d_sep the mean spacing is wider (the measure reports it).
constexpr double kFill = 1.0;

// The coverage feedback (Tracer::balance): cells of 8 px (the measure's sigma), a gain of at
// most 4 (the pens' widest range is 4: 0.55-2.2).
constexpr float kCoverageCell = 8.0f;
constexpr double kMaxGain = 4.0;
// The image length of a tracing step, px (hachures.hpp: the chord's departure from the curve;
// 1 px drew the same tone, r and SSIM within 0.005, for half again the tracing's cost).
constexpr double kStepPx = 2.0;
// The lattice's blocks of cells wider than this on the image, px, get sub-lattices (run(); 6 px
// drew the same tone, r and SSIM within 0.005, for a tenth more of the tracing).
constexpr double kSeedBlockPx = 9.0;
// A point whose wanted width is under this share of the lightest pen is cut out (Tracer::balance).
constexpr double kDropWidth = 1.0;
// reseed(): cells that even the heaviest pen leaves this much lighter than their target, and the
// tightest separation, as a share of the tone's.
constexpr double kReseedGain = 1.05;
constexpr double kMinTighten = 0.35;

// The segments of a polyline of n image points at(i) with a pen's taper factor at each
// segment's middle (core/stroke_taper.hpp): f(i, taper) for the segment i -> i + 1. The one walk
// of the ink the coverage counts, of the lines yielded to and of the hachures.
template <class At, class F>
void tapered_segments(std::size_t n, const At& at, double taper_px, double taper_min, const F& f) {
    double length = 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i) length += glm::length(at(i + 1) - at(i));
    double arc = 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double len = glm::length(at(i + 1) - at(i));
        f(i, taper_factor(arc + 0.5 * len, length, taper_px, taper_min));
        arc += len;
    }
}

// The nodes of a grid, in memory or read on demand through its cache of tiles.
NodeTiles grid_tiles(const HachureGrid& g) {
    if (g.pos && g.valid) return NodeTiles(g.cols, g.rows, g.pos, g.valid);
    return NodeTiles(g.cols, g.rows, g.read, g.cache_bytes, g.tile_cols, g.tile_rows);
}

// The grid as a continuous surface: bilinear positions, bilinearly interpolated node gradients.
class SlopeField {
public:
    explicit SlopeField(const HachureGrid& g)
        : g_(g), tiles_(grid_tiles(g)), cache_(std::size_t(kCacheSide) * kCacheSide) {}
    // Node gradients from differences over +-k nodes (the slope at the scale of the drawing).
    void set_stencil(int k) {
        k_ = std::max(1, k), cells_[0] = cells_[1] = Cell{};
        std::fill(cache_.begin(), cache_.end(), CachedGradient{});
    }
    glm::dvec3 node_position(int c, int r) { return node(c, r); }
    // The same, its tile not read when not held (a lattice of a few nodes over the whole grid).
    glm::dvec3 probe_position(int c, int r) { return drawn(tiles_.probe_pos(c, r)); }
    // Whether node (c, r) is one the lines may use and holds data.
    bool valid(int c, int r) {
        return c >= g_.c0 && c < g_.c1 && r >= g_.r0 && r < g_.r1 && tiles_.valid(c, r);
    }
    // The tiles the nodes are read in (the whole grid when in memory), and what their cache did.
    int tile_cols() const { return tiles_.tile_cols(); }
    int tile_rows() const { return tiles_.tile_rows(); }
    const NodeTileCounts& node_counts() const { return tiles_.counts(); }
    // The row the seed lattice's sweep has reached (< 0: none): the nodes north of it go first.
    void sweep(int r) { tiles_.sweep(r); }

    struct Point {
        glm::dvec3 p{0.0};    // world
        glm::dvec2 grad{0.0}; // dz/dx, dz/dy (world)
        glm::dvec2 du{0.0}, dv{0.0};  // d(x, y)/dc, d(x, y)/dr
    };

    // False outside [c0, c1 - 1) x [r0, r1 - 1) or on a cell with an invalid node.
    bool eval(glm::dvec2 uv, Point& out) {
        const double fc = std::floor(uv.x), fr = std::floor(uv.y);
        if (!(fc >= g_.c0 && fc + 1 < g_.c1 && fr >= g_.r0 && fr + 1 < g_.r1)) return false;
        const int c = int(fc), r = int(fr);
        // the last two cells kept: a step's midpoint and end often lie on either side of an edge
        if (cells_[0].c != c || cells_[0].r != r) {
            std::swap(cells_[0], cells_[1]);
            if (cells_[0].c != c || cells_[0].r != r) cells_[0].ok = load_cell(c, r, cells_[0]);
        }
        const Cell& cell = cells_[0];
        if (!cell.ok) return false;
        const glm::dvec3* pos = cell.n;
        const glm::dvec2* grad = cell.gr;
        const double a = uv.x - fc, b = uv.y - fr;
        const double w00 = (1 - a) * (1 - b), w10 = a * (1 - b), w01 = (1 - a) * b, w11 = a * b;
        out.p = w00 * pos[0] + w10 * pos[1] + w01 * pos[2] + w11 * pos[3];
        out.grad = w00 * grad[0] + w10 * grad[1] + w01 * grad[2] + w11 * grad[3];
        const glm::dvec3 du = (1 - b) * (pos[1] - pos[0]) + b * (pos[3] - pos[2]);
        const glm::dvec3 dv = (1 - a) * (pos[2] - pos[0]) + a * (pos[3] - pos[1]);
        out.du = glm::dvec2(du), out.dv = glm::dvec2(dv);
        return true;
    }

private:
    glm::dvec3 node(int c, int r) { return drawn(tiles_.pos(c, r)); }
    // A stored position as drawn: z exaggerated, no lower than the floor.
    glm::dvec3 drawn(glm::vec3 stored) const {
        glm::dvec3 p(stored);
        p.z = std::max(double(float(p.z * g_.z_scale)), double(g_.floor_z));
        return p;
    }
    // Central differences (one-sided beside the edge or nodata) solved for the world gradient.
    glm::dvec2 node_gradient(int c, int r) {
        int cm = c, cp = c, rm = r, rp = r;
        for (int k = k_; k >= 1 && cm == c; --k) cm = valid(c - k, r) ? c - k : c;
        for (int k = k_; k >= 1 && cp == c; --k) cp = valid(c + k, r) ? c + k : c;
        for (int k = k_; k >= 1 && rm == r; --k) rm = valid(c, r - k) ? r - k : r;
        for (int k = k_; k >= 1 && rp == r; --k) rp = valid(c, r + k) ? r + k : r;
        if (cm == cp || rm == rp) return glm::dvec2(0.0);
        const glm::dvec3 pc = (node(cp, r) - node(cm, r)) / double(cp - cm);
        const glm::dvec3 pr = (node(c, rp) - node(c, rm)) / double(rp - rm);
        // gx pc.x + gy pc.y = pc.z, gx pr.x + gy pr.y = pr.z
        const double det = pc.x * pr.y - pc.y * pr.x;
        if (std::abs(det) < 1e-12) return glm::dvec2(0.0);
        return glm::dvec2((pc.z * pr.y - pc.y * pr.z) / det, (pc.x * pr.z - pc.z * pr.x) / det);
    }
    // A cell's four nodes (c, r), (c + 1, r), (c, r + 1), (c + 1, r + 1) and their gradients.
    struct Cell {
        int c = -1, r = -1;
        bool ok = false;
        glm::dvec3 n[4];
        glm::dvec2 gr[4];
    };
    bool load_cell(int c, int r, Cell& out) {
        out.c = c, out.r = r;
        const int cs[4] = {c, c + 1, c, c + 1}, rs[4] = {r, r, r + 1, r + 1};
        for (int k = 0; k < 4; ++k) {
            if (!valid(cs[k], rs[k])) return false;
            out.n[k] = node(cs[k], rs[k]);
            out.gr[k] = cached_gradient(cs[k], rs[k]);
        }
        return true;
    }
    // node_gradient through a direct-mapped cache of kCacheSide^2 nodes (node (c, r) in slot
    // (c mod side, r mod side): any kCacheSide x kCacheSide block of nodes fits): the lines and
    // their neighbours walk the same cells again and again, and a window may hold millions of
    // nodes, too many to keep a gradient for each. The same values as node_gradient.
    glm::dvec2 cached_gradient(int c, int r) {
        const std::int64_t key = std::int64_t(r) * g_.cols + c;
        CachedGradient& e = cache_[std::size_t(r & (kCacheSide - 1)) * kCacheSide + std::size_t(c & (kCacheSide - 1))];
        if (e.key != key) e.key = key, e.grad = node_gradient(c, r);
        return e.grad;
    }

    const HachureGrid& g_;
    NodeTiles tiles_;
    int k_ = 1;
    Cell cells_[2];  // the cell eval() used last, and the one before
    static constexpr int kCacheSide = 128;  // 16 Ki nodes, 384 KiB
    struct CachedGradient {
        std::int64_t key = -1;  // node index r cols + c; -1: empty
        glm::dvec2 grad{0.0};
    };
    std::vector<CachedGradient> cache_;
};

// World direction (x, y) -> grid parameter direction: solve [du dv] t = d.
glm::dvec2 to_param(const SlopeField::Point& f, glm::dvec2 d) {
    const double det = f.du.x * f.dv.y - f.dv.x * f.du.y;
    if (std::abs(det) < 1e-12) return glm::dvec2(0.0);
    return glm::dvec2((d.x * f.dv.y - f.dv.x * d.y) / det, (f.du.x * d.y - d.x * f.du.y) / det);
}

// Points of all lines on the image, bucketed in square cells: each cell a chain through one
// array of entries, newest first (no allocation per cell; the queries' answers do not depend on
// the order).
class Occupancy {
public:
    static constexpr std::uint32_t obstacle = 0xffffffffu;
    Occupancy(int width, int height, float cell) : cell_(cell) {
        cols_ = std::max(1, int(std::ceil(width / cell))) + 2;
        rows_ = std::max(1, int(std::ceil(height / cell))) + 2;
        head_.assign(std::size_t(cols_) * rows_, kEnd);
    }
    void add(glm::vec2 p, std::uint32_t line) {
        const int cx = cell_of(p.x, cols_), cy = cell_of(p.y, rows_);
        std::uint32_t& head = head_[std::size_t(cy) * cols_ + cx];
        entries_.push_back({p, line, head});
        head = std::uint32_t(entries_.size() - 1);
    }
    // True when a point of another line lies within r_line, or an obstacle within r_obstacle.
    // The cells are visited from p's outwards (ring by ring), where a blocking point is most
    // likely; the answer does not depend on the order.
    bool blocked(glm::vec2 p, std::uint32_t self, float r_line, float r_obstacle) const {
        const float r = std::max(r_line, r_obstacle);
        const int x0 = cell_of(p.x - r, cols_), x1 = cell_of(p.x + r, cols_);
        const int y0 = cell_of(p.y - r, rows_), y1 = cell_of(p.y + r, rows_);
        const int cx = cell_of(p.x, cols_), cy = cell_of(p.y, rows_);
        const float rl2 = r_line * r_line, ro2 = r_obstacle * r_obstacle;
        const auto hit = [&](int x, int y) {
            for (std::uint32_t i = head_[std::size_t(y) * cols_ + x]; i != kEnd; i = entries_[i].next) {
                const Entry& e = entries_[i];
                if (e.line == self) continue;
                const glm::vec2 d = e.p - p;
                const float d2 = d.x * d.x + d.y * d.y;
                if (d2 < (e.line == obstacle ? ro2 : rl2)) return true;
            }
            return false;
        };
        const int rings = std::max({cx - x0, x1 - cx, cy - y0, y1 - cy});
        for (int k = 0; k <= rings; ++k)
            if (ring(cx, cy, k, x0, x1, y0, y1, hit)) return true;
        return false;
    }

    // The nearest point of another line (or an obstacle) on each side of p across the unit
    // tangent t, within a cone of 45 degrees about the normal and a distance r; r where none.
    // Rings of cells outwards from p's; a point of ring k lies at least (k - 1) cells from p, and
    // one in the cone at least that over sqrt(2) across, so the search stops at the ring that can
    // no longer bring either side nearer (the answer is the full search's).
    void gaps(glm::vec2 p, glm::vec2 t, std::uint32_t self, float r, float& left, float& right) const {
        left = right = r;
        const int x0 = cell_of(p.x - r, cols_), x1 = cell_of(p.x + r, cols_);
        const int y0 = cell_of(p.y - r, rows_), y1 = cell_of(p.y + r, rows_);
        const int cx = cell_of(p.x, cols_), cy = cell_of(p.y, rows_);
        const auto visit = [&](int x, int y) {
            for (std::uint32_t i = head_[std::size_t(y) * cols_ + x]; i != kEnd; i = entries_[i].next) {
                const Entry& e = entries_[i];
                if (e.line == self) continue;
                const glm::vec2 d = e.p - p;
                const float along = d.x * t.x + d.y * t.y, across = d.y * t.x - d.x * t.y;
                if (std::abs(along) > std::abs(across)) continue;
                if (across > 0.0f) left = std::min(left, across);
                else right = std::min(right, -across);
            }
            return false;
        };
        const int rings = std::max({cx - x0, x1 - cx, cy - y0, y1 - cy});
        for (int k = 0; k <= rings; ++k) {
            if (float(k - 1) * cell_ * 0.7f >= std::max(left, right)) break;  // 0.7 < 1 / sqrt(2): a margin
            ring(cx, cy, k, x0, x1, y0, y1, visit);
        }
    }

private:
    static constexpr std::uint32_t kEnd = 0xffffffffu;  // no further entry in the cell
    struct Entry {
        glm::vec2 p;
        std::uint32_t line;
        std::uint32_t next;  // the cell's previous entry, or kEnd
    };
    // clamp(floor(v / cell) + 1, 0, n - 1), truncating where the quotient is >= 0
    int cell_of(float v, int n) const {
        const float f = v / cell_;
        if (!(f >= 0.0f)) return 0;
        return f >= float(n) ? n - 1 : std::min(int(f) + 1, n - 1);
    }
    // The cells of [x0, x1] x [y0, y1] at Chebyshev distance k from (cx, cy), each given to f
    // until it returns true; true when it did.
    template <class F>
    static bool ring(int cx, int cy, int k, int x0, int x1, int y0, int y1, const F& f) {
        if (k == 0) return f(cx, cy);
        const int xa = std::max(x0, cx - k), xb = std::min(x1, cx + k);
        if (cy - k >= y0)
            for (int x = xa; x <= xb; ++x)
                if (f(x, cy - k)) return true;
        if (cy + k <= y1)
            for (int x = xa; x <= xb; ++x)
                if (f(x, cy + k)) return true;
        const int ya = std::max(y0, cy - k + 1), yb = std::min(y1, cy + k - 1);
        if (cx - k >= x0)
            for (int y = ya; y <= yb; ++y)
                if (f(cx - k, y)) return true;
        if (cx + k <= x1)
            for (int y = ya; y <= yb; ++y)
                if (f(cx + k, y)) return true;
        return false;
    }
    float cell_;
    int cols_ = 0, rows_ = 0;
    std::vector<std::uint32_t> head_;  // per cell, its newest entry or kEnd
    std::vector<Entry> entries_;
};

struct Sample {
    glm::dvec2 uv{0.0};
    SlopeField::Point f;
    glm::vec2 px{0.0f};
    double depth = 0.0;
    double tone = 0.0;  // drawn tone
    double sep = 0.0;   // separation, pixels
};

class Tracer {
public:
    Tracer(const HachureGrid& grid, const HachureFrame& frame, const HachureParams& params)
        : field_(grid), frame_(frame), p_(params), cam_(*frame.camera), project_(cam_),
          occ_(cam_.width, cam_.height, 3.0f), cov_(cam_.width, cam_.height, kCoverageCell) {
        min_grad_ = std::tan(glm::radians(std::clamp(p_.min_slope_deg, 0.0, 89.9)));
        width_ = frame.width_px > 0.0 ? frame.width_px : default_hachure_width_px;
        perspective_ = !is_orthographic(cam_);
        toward_ortho_ = toward_viewer(cam_, glm::dvec3(0.0));  // the same at every point
        visibility_.rel_tolerance = 0.002f;  // as the outline: the lines lie on the rendered surface
        near_ = frame.max_distance;  // the nearest visible eye distance: where the aerial fade starts
        if (frame.toward) {
            if (perspective_)  // the fade's alone
                for (float d : frame.toward->depth)
                    if (std::isfinite(d)) near_ = std::min(near_, double(d));
            cov_.set_terrain(*frame.toward);
        }
    }

    void add_obstacles() {
        for (std::size_t layer = 0; layer < frame_.obstacles.size(); ++layer) {
            const HachurePen pen = layer < frame_.obstacle_pens.size() ? frame_.obstacle_pens[layer] : HachurePen{};
            for (const Stroke& s : *frame_.obstacles[layer]) {
                const auto at = [&](std::size_t i) { return s.points[i]; };
                tapered_segments(s.points.size(), at, pen.taper_px, pen.taper_min, [&](std::size_t i, double taper) {
                    // the segment's part inside the image (Liang-Barsky), sampled every pixel
                    const glm::vec2 a = s.points[i], d = s.points[i + 1] - a;
                    float t0 = 0.0f, t1 = 1.0f;
                    const float p[4] = {-d.x, d.x, -d.y, d.y};
                    const float q[4] = {a.x + 2.0f, cam_.width + 2.0f - a.x, a.y + 2.0f, cam_.height + 2.0f - a.y};
                    bool inside = true;
                    for (int e = 0; e < 4 && inside; ++e) {
                        if (p[e] == 0.0f) inside = q[e] >= 0.0f;
                        else if (p[e] < 0.0f) t0 = std::max(t0, q[e] / p[e]);
                        else t1 = std::min(t1, q[e] / p[e]);
                    }
                    if (!inside || t0 > t1) return;
                    const int n = std::max(1, int(std::ceil(glm::length(d) * (t1 - t0))));
                    for (int k = 0; k <= n; ++k) occ_.add(a + d * (t0 + (t1 - t0) * float(k) / n), Occupancy::obstacle);
                    // its ink as the style draws it: weight and taper at the segment's middle
                    const double u = 0.5 * (double(weight_at(s, i)) + double(weight_at(s, i + 1)));
                    const double w = pen.width_px * (pen.weight_min + u * (pen.weight_max - pen.weight_min)) * taper;
                    cov_.add_ink(a + d * t0, a + d * t1, w, true);
                });
            }
        }
    }

    // The surface, image and drawn tone at uv; false off the cells with data or the image, or
    // turned away (hidden points are visible()'s).
    bool place(glm::dvec2 uv, Sample& s) {
        s.uv = uv;
        if (!field_.eval(uv, s.f)) return false;
        const glm::dvec3 n = glm::normalize(glm::dvec3(-s.f.grad.x, -s.f.grad.y, 1.0));
        if (glm::dot(n, perspective_ ? toward_viewer(cam_, s.f.p) : toward_ortho_) <= 0.0) return false;  // turned away: silhouette
        glm::dvec2 px;
        if (!project_(s.f.p, px, s.depth)) return false;
        if (!(px.x >= 0.0 && px.y >= 0.0 && px.x < cam_.width && px.y < cam_.height)) return false;
        s.px = glm::vec2(px);
        double t = hachure_tone(p_.tone, p_.blend, n, frame_.light);
        t = std::clamp(0.5 + p_.contrast * (t - 0.5), 0.0, 1.0);
        if (p_.gamma != 1.0) t = std::pow(t, p_.gamma);
        if (perspective_ && frame_.max_distance > near_) {
            // the fade grows with the square of the depth's fraction: the middle distance keeps
            // its tone, the far ridges (where the creases and skylines crowd) lose most of theirs
            const double f = std::clamp((s.depth - near_) / (frame_.max_distance - near_), 0.0, 1.0);
            t *= 1.0 - p_.aerial * f * f;
        }
        s.tone = t;
        s.sep = 0.0;
        return true;
    }

    // Whether placed sample s is not hidden (against the frame's depth image).
    bool visible(const Sample& s) const {
        if (!frame_.toward || is_empty(*frame_.toward)) return true;
        VisibilityOptions v = visibility_;
        // the level of detail's 1 px, and a cell: the rendered PN surface and this bilinear one
        // differ by up to a fraction of a cell's relief, which a grazing ray stretches in depth
        v.abs_tolerance = float(3.0 * project_.world_per_pixel(s.depth) + cell_m_);
        return pixel_visible(*frame_.toward, cam_, glm::dvec2(s.px), s.depth, v);  // place() projected it
    }

    // The surface, image and drawn tone at uv; false where it is not drawn terrain (place, then
    // visible).
    bool surface(glm::dvec2 uv, Sample& s) { return place(uv, s) && visible(s); }

    // Whether a hachure may pass a drawn point (steep and dark enough); sets its separation.
    bool hatched(Sample& s) const {
        const double g = glm::length(s.f.grad);
        if (!(g >= min_grad_) || g <= 0.0) return false;
        const double sep = kFill * hachure_pen_width(s.tone, width_, p_.weight_min, p_.weight_max) / s.tone;
        if (!(s.tone > 0.0) || sep > p_.spacing_max_px) return false;
        s.sep = std::max(sep, p_.spacing_min_px);
        if (tighten_) s.sep *= std::clamp(1.0 / cov_.gain(s.px, kMaxGain), kMinTighten, 1.0);
        return true;
    }

    // The surface, image and tone at uv; false where no hachure may be.
    bool sample(glm::dvec2 uv, Sample& s) { return place(uv, s) && hatched(s) && visible(s); }
    // A seed at uv where no hachure is near (the depth test, the costliest check, last).
    bool free_seed(glm::dvec2 uv, Sample& s) { return place(uv, s) && hatched(s) && seed_free(s) && visible(s); }

    // Image pixels per unit of grid parameter along param direction t at sample s.
    double px_per_unit(const Sample& s, glm::dvec2 t) const {
        const glm::dvec2 w = s.f.du * t.x + s.f.dv * t.y;
        const double eps = 1e-3;
        const glm::dvec3 q = s.f.p + eps * glm::dvec3(w, glm::dot(s.f.grad, w));
        glm::dvec2 px;
        double d;
        if (!project_(q, px, d)) return 0.0;
        return glm::length(px - glm::dvec2(s.px)) / eps;
    }

    // Image area (px^2) of the parallelogram of grid parameter sides dc x dr on the surface's
    // tangent plane at s.
    double image_area(const Sample& s, double dc, double dr) const {
        const auto offset = [&](glm::dvec2 w) {
            glm::dvec2 px;
            double d;
            if (!project_(s.f.p + glm::dvec3(w, glm::dot(s.f.grad, w)), px, d)) return glm::dvec2(0.0);
            return px - glm::dvec2(s.px);
        };
        const glm::dvec2 a = offset(dc * s.f.du), b = offset(dr * s.f.dv);
        return std::abs(a.x * b.y - a.y * b.x);
    }

    // Fall-line direction in grid parameters (sign +1 downhill, -1 uphill), unit world length.
    static glm::dvec2 fall(const SlopeField::Point& f, double sign) {
        const double g = glm::length(f.grad);
        return to_param(f, -sign * f.grad / g);
    }

    // Grows one half of a line from s; appends the points after s.
    void grow(const Sample& start, double sign, std::uint32_t id, std::vector<Sample>& out) {
        Sample cur = start;
        glm::vec2 prev_dir(0.0f);
        const std::size_t max_points = std::size_t(4 * (cam_.width + cam_.height));
        const double max_turn = glm::radians(p_.max_turn_deg);
        for (std::size_t k = 0; k < max_points; ++k) {
            const glm::dvec2 t0 = fall(cur.f, sign);
            const double ppu = px_per_unit(cur, t0);
            if (!(ppu > 0.0)) return;
            const double h = std::min(kStepPx / ppu, 4.0 / std::max(glm::length(t0), 1e-12));  // at most ~4 cells
            SlopeField::Point mid;
            if (!field_.eval(cur.uv + 0.5 * h * t0, mid) || !(glm::length(mid.grad) > 0.0)) return;
            Sample next;
            if (!place(cur.uv + h * fall(mid, sign), next) || !hatched(next)) return;
            const glm::vec2 step = next.px - cur.px;
            const float len = glm::length(step);
            if (!(len > 1e-4f)) return;
            const glm::vec2 dir = step / len;
            if (k > 0) {
                const double turn = std::acos(std::clamp(double(glm::dot(dir, prev_dir)), -1.0, 1.0));
                if (turn > max_turn * std::max(1.0, double(len))) return;
            }
            if (occ_.blocked(next.px, id, float(p_.d_test * next.sep), float(p_.yield_px)) || !visible(next))
                return;
            prev_dir = dir;
            out.push_back(next);
            cur = next;
        }
    }

    // A line from a seed (accepted and recorded, or nothing); true when accepted.
    bool line_from(const Sample& seed) {
        const std::uint32_t id = std::uint32_t(lines_.size());
        std::vector<Sample> line;
        line.reserve(64);
        grow(seed, -1.0, id, line);  // up, then reversed: the line runs downhill
        std::reverse(line.begin(), line.end());
        line.push_back(seed);
        grow(seed, +1.0, id, line);
        float length = 0.0f;
        for (std::size_t i = 1; i < line.size(); ++i) length += glm::length(line[i].px - line[i - 1].px);
        if (line.size() < 2 || length < p_.min_length_px) return false;
        for (const Sample& s : line) occ_.add(s.px, id);
        lines_.push_back(std::move(line));
        queue_.push_back(id);
        return true;
    }

    bool seed_free(const Sample& s) const {
        return !occ_.blocked(s.px, Occupancy::obstacle - 1, float(0.95 * s.sep), float(p_.yield_px + 1.0));
    }

    // Jobard & Lefer: seeds beside each new line until none is left.
    void drain_queue() {
        while (!queue_.empty()) {
            const std::uint32_t id = queue_.front();
            queue_.pop_front();
            double since = 1e30;
            for (std::size_t i = 0; i < lines_[id].size(); ++i) {
                if (i > 0) since += glm::length(lines_[id][i].px - lines_[id][i - 1].px);
                if (since < 0.5 * lines_[id][i].sep) continue;
                const Sample s = lines_[id][i];  // copy: lines_ grows below
                since = 0.0;
                const double g = glm::length(s.f.grad);
                const glm::dvec2 contour = to_param(s.f, glm::dvec2(-s.f.grad.y, s.f.grad.x) / g);
                const double ppu = px_per_unit(s, contour);
                if (!(ppu > 0.0)) continue;
                for (double side : {-1.0, 1.0}) {
                    Sample cand;
                    if (free_seed(s.uv + side * (s.sep / ppu) * contour, cand)) line_from(cand);
                }
            }
        }
    }

    // With a sea, in perspective: the aerial fade starts at the nearest land node in the image
    // (the water in front of a coast is not toned), not at the nearest water. A node no nearer
    // to the eye than the nearest so far is not projected (its depth is that distance).
    // The nodes are visited a tile of the field's at a time (each read once; the nearest does
    // not depend on the order).
    void near_land(const HachureGrid& grid) {
        double nearest = std::numeric_limits<double>::infinity();
        const int tc = field_.tile_cols(), tr = field_.tile_rows();
        for (int r0 = grid.r0; r0 < grid.r1; r0 = (r0 / tr + 1) * tr)
            for (int c0 = grid.c0; c0 < grid.c1; c0 = (c0 / tc + 1) * tc)
                for (int r = r0; r < std::min(grid.r1, (r0 / tr + 1) * tr); ++r)
                    for (int c = c0; c < std::min(grid.c1, (c0 / tc + 1) * tc); ++c) {
                        if (!field_.valid(c, r)) continue;
                        const glm::dvec3 p = field_.node_position(c, r);
                        if (!(p.z > double(grid.floor_z))) continue;
                        if (glm::length(p - cam_.eye) > nearest * (1.0 + 1e-9)) continue;  // a margin for rounding
                        glm::dvec2 px;
                        double d;
                        if (project_(p, px, d) && px.x >= 0.0 && px.y >= 0.0 && px.x < cam_.width && px.y < cam_.height)
                            nearest = std::min(nearest, d);
                    }
        if (nearest < frame_.max_distance) near_ = std::max(near_, nearest);
    }

    // The stencil: about 1.5 px of ground, from the median image size of a cell over a lattice
    // of 16 x 16 nodes that project into the image (and the median cell size, metres); the
    // lattice's nodes read alone where their tiles are not held.
    int stencil(const HachureGrid& grid) {
        std::vector<double> px_per_cell, cell_m;
        for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j) {
                const int c = grid.c0 + (grid.c1 - grid.c0 - 2) * i / 15, r = grid.r0 + (grid.r1 - grid.r0 - 2) * j / 15;
                glm::dvec2 a, b, e;
                double da, db, de;
                if (!project_(field_.probe_position(c, r), a, da) ||
                    !project_(field_.probe_position(c + 1, r), b, db) ||
                    !project_(field_.probe_position(c, r + 1), e, de))
                    continue;
                if (a.x < 0 || a.y < 0 || a.x >= cam_.width || a.y >= cam_.height) continue;
                px_per_cell.push_back(std::max(glm::length(b - a), glm::length(e - a)));
                cell_m.push_back(glm::length(glm::dvec2(field_.probe_position(c + 1, r) - field_.probe_position(c, r))));
            }
        if (!cell_m.empty()) {
            std::nth_element(cell_m.begin(), cell_m.begin() + cell_m.size() / 2, cell_m.end());
            cell_m_ = cell_m[cell_m.size() / 2];
        }
        if (px_per_cell.empty()) return 1;
        std::nth_element(px_per_cell.begin(), px_per_cell.begin() + px_per_cell.size() / 2, px_per_cell.end());
        const double m = px_per_cell[px_per_cell.size() / 2];
        return m > 0.0 ? std::clamp(int(std::lround(1.5 / m)), 1, 16) : 1;
    }

    void run(const HachureGrid& grid) {
        field_.set_stencil(stencil(grid));
        floor_z_ = grid.floor_z;
        if (std::isfinite(grid.floor_z) && perspective_) near_land(grid);
        add_obstacles();
        const double cells = double(std::max(grid.c1 - grid.c0 - 1, 0)) * std::max(grid.r1 - grid.r0 - 1, 0);
        const double target = double(cam_.width) * cam_.height / std::pow(2.0 * std::max(p_.spacing_min_px, 0.5), 2.0);
        const int stride = std::max(1, int(std::sqrt(cells / std::max(target, 1.0))));
        for (int r = grid.r0; r + 1 < grid.r1; r += stride) {
            field_.sweep(r);
            for (int c = grid.c0; c + 1 < grid.c1; c += stride) {
                // a block of cells larger than kSeedBlockPx on the image (the near ground of a perspective
                // view) gets a sub-lattice, so every region between creases has seeds of its own
                const int c2 = std::min(c + stride, grid.c1 - 1), r2 = std::min(r + stride, grid.r1 - 1);
                glm::dvec2 a, b;
                double da, db;
                int m = 1;
                if (project_(field_.node_position(c, r), a, da) &&
                    project_(field_.node_position(c2, r2), b, db))
                    m = std::clamp(int(std::ceil(glm::length(b - a) / kSeedBlockPx)), 1, 16);
                for (int j = 0; j < m; ++j)
                    for (int i = 0; i < m; ++i) {
                        Sample s;
                        const glm::dvec2 uv(c + (c2 - c) * (i + 0.5) / m, r + (r2 - r) * (j + 0.5) / m);
                        if (!surface(uv, s)) continue;
                        // the tone the coverage feedback aims at; water (flat at the sea level)
                        // is left white, as a map leaves it
                        const bool water = std::isfinite(floor_z_) && s.f.p.z <= double(floor_z_) + 1e-6 * std::abs(double(floor_z_));
                        const bool flat = !(glm::length(s.f.grad) >= min_grad_);
                        cov_.add_target(s.px, water || flat ? 0.0 : s.tone,
                                        image_area(s, double(c2 - c) / m, double(r2 - r) / m));
                        if (!hatched(s)) continue;
                        seeds_.push_back({uv, s.px});
                        if (seed_free(s) && line_from(s)) drain_queue();
                    }
            }
        }
        field_.sweep(-1);
    }

    // The pen's weight at each point of line id: the width that makes the ink between its
    // neighbours the tone, w = t (g_left + g_right) / 2 (g the gaps across the line on the image,
    // each at most 2 s; a side with no line within 2 s counts s), as a fraction of the style's
    // range [weight_min, weight_max] x width, smoothed over 5 points.
    std::vector<float> weights(std::uint32_t id, const std::vector<glm::vec2>& gap) const {
        const std::vector<Sample>& line = lines_[id];
        const double lo = p_.weight_min * width_, hi = p_.weight_max * width_;
        std::vector<float> u(line.size(), 0.0f);
        if (!(hi > lo)) return {};
        for (std::size_t i = 0; i < line.size(); ++i) {
            if (!(gap[i].x > 0.0f)) continue;
            // a side with no line within 2 s counts s
            const float r = float(2.0 * line[i].sep), s = float(line[i].sep);
            const float gl = gap[i].x >= r ? s : gap[i].x, gr = gap[i].y >= r ? s : gap[i].y;
            const double w = line[i].tone * 0.5 * (double(gl) + double(gr));
            u[i] = float(std::clamp((w - lo) / (hi - lo), 0.0, 1.0));
        }
        std::vector<float> out(u.size());
        for (std::size_t i = 0; i < u.size(); ++i) {
            const std::size_t i0 = i >= 2 ? i - 2 : 0, i1 = std::min(u.size() - 1, i + 2);
            double sum = 0.0;
            for (std::size_t k = i0; k <= i1; ++k) sum += u[k];
            out[i] = float(sum / double(i1 - i0 + 1));
        }
        return out;
    }

    // The gaps across line id at each point on the image (left, right): the nearest other
    // hachure or obstacle point within 45 deg of the normal, 2 s at most; 0 where the line has no
    // direction. Searched at every other point (the points are about 2 px apart and the widths
    // are smoothed over 5), the points between taking the mean of their neighbours'.
    std::vector<glm::vec2> gaps(std::uint32_t id) const {
        const std::vector<Sample>& line = lines_[id];
        const std::size_t n = line.size();
        std::vector<glm::vec2> out(n, glm::vec2(0.0f));
        const auto search = [&](std::size_t i) {
            const glm::vec2 a = line[i > 0 ? i - 1 : i].px, b = line[i + 1 < n ? i + 1 : i].px;
            const float len = glm::length(b - a);
            if (!(len > 0.0f)) return;
            const float r = float(2.0 * line[i].sep);
            occ_.gaps(line[i].px, (b - a) / len, id, r, out[i].x, out[i].y);
        };
        for (std::size_t i = 0; i < n; i += 2) search(i);
        if (n > 1 && (n - 1) % 2 == 1) search(n - 1);
        for (std::size_t i = 1; i + 1 < n; i += 2)
            out[i] = out[i - 1].x > 0.0f && out[i + 1].x > 0.0f ? 0.5f * (out[i - 1] + out[i + 1]) : out[i - 1];
        return out;
    }

    // Ink of every line at the widths width(line, point), with the pen's taper, into cov_. A line
    // inks half its width on each side, but no more than the gap to its neighbour there (what
    // overlaps is paper already black).
    template <class Width>
    void lay_ink(const Width& width, const std::vector<std::vector<glm::vec2>>& gap) {
        cov_.clear_ink();
        for (std::uint32_t id = 0; id < lines_.size(); ++id) {
            const std::vector<Sample>& line = lines_[id];
            const auto ink = [&](std::size_t i) {
                const double w = width(id, i);
                if (!(gap[id][i].x > 0.0f)) return w;
                return 0.5 * (std::min(w, double(gap[id][i].x)) + std::min(w, double(gap[id][i].y)));
            };
            const auto at = [&](std::size_t i) { return line[i].px; };
            tapered_segments(line.size(), at, p_.taper_px, p_.taper_min, [&](std::size_t i, double taper) {
                cov_.add_ink(line[i].px, line[i + 1].px, 0.5 * (ink(i) + ink(i + 1)) * taper);
            });
        }
    }

    // Where even the heaviest pen leaves a cell lighter than its target (the holes between line
    // ends on rough ground, where fall lines meet and part every few pixels), the lattice seeds
    // of those cells are tried again with the separation tightened by the shortfall,
    // s x max(kMinTighten, 1 / gain), and so are the seeds beside the lines they start.
    void reseed() {
        // the heaviest pen, no wider than the line's separation (its neighbours' gap as placed)
        const double hi = p_.weight_max * width_;
        std::vector<std::vector<glm::vec2>> gap(lines_.size());
        for (std::uint32_t id = 0; id < lines_.size(); ++id)
            for (const Sample& s : lines_[id]) gap[id].push_back(glm::vec2(float(s.sep)));
        lay_ink([&](std::uint32_t, std::size_t) { return hi; }, gap);
        cov_.update(kMaxGain);
        tighten_ = true;
        for (const LatticeSeed& seed : seeds_) {
            if (cov_.gain(seed.px, kMaxGain) < kReseedGain) continue;
            Sample s;
            if (free_seed(seed.uv, s) && line_from(s)) drain_queue();
        }
        tighten_ = false;
        seeds_ = {};
    }

    // The coverage feedback: the widths of the gap rule (weights) scaled by the gain of the ink
    // they lay against the target tone per image cell (InkCoverage: lines of the pen's widths
    // with its taper, and the lines yielded to), clamped to the pen's range, and in the same
    // round the points that would want less than kDropWidth of the lightest pen (cells the
    // lines yielded to already darken, the far creases of a panorama) cut out of their lines,
    // pieces shorter than min_length_px dropped; one more round sets the widths of what is left
    // (a second round before the cut changed r and SSIM by under 0.01 on the tone views and
    // cost a twentieth of the tracing).
    void balance() {
        const double lo = p_.weight_min * width_, hi = p_.weight_max * width_;
        weights_.assign(lines_.size(), {});
        if (!(hi > lo)) return;
        std::vector<std::vector<double>> w(lines_.size());
        std::vector<std::vector<glm::vec2>> gap(lines_.size());
        for (std::uint32_t id = 0; id < lines_.size(); ++id) {
            gap[id] = gaps(id);
            for (float u : weights(id, gap[id])) w[id].push_back(lo + double(u) * (hi - lo));
        }
        rebalance(w, gap, lo, hi, true);
        rebalance(w, gap, lo, hi, false);
        weights_.assign(lines_.size(), {});
        for (std::uint32_t id = 0; id < lines_.size(); ++id) {
            for (double v : w[id]) weights_[id].push_back(float((v - lo) / (hi - lo)));
        }
    }

    // One round of balance(): the ink of widths w, then each width times its gain, clamped; with
    // `cut`, the points wanting under kDropWidth x lo are cut out of their lines.
    void rebalance(std::vector<std::vector<double>>& w, std::vector<std::vector<glm::vec2>>& gap, double lo, double hi,
                   bool cut) {
        lay_ink([&](std::uint32_t id, std::size_t i) { return w[id][i]; }, gap);
        cov_.update(kMaxGain);
        if (!cut) {  // every line stays whole (each is min_length_px long or more)
            for (std::uint32_t id = 0; id < lines_.size(); ++id)
                for (std::size_t i = 0; i < lines_[id].size(); ++i)
                    w[id][i] = std::clamp(w[id][i] * cov_.gain(lines_[id][i].px, kMaxGain), lo, hi);
            return;
        }
        std::vector<std::vector<Sample>> kept_lines;
        std::vector<std::vector<double>> kept_w;
        std::vector<std::vector<glm::vec2>> kept_gap;
        std::vector<double> want;
        const auto dropped = [&](std::size_t i) { return want[i] < kDropWidth * lo; };
        for (std::uint32_t id = 0; id < lines_.size(); ++id) {
            const std::size_t n = lines_[id].size();
            want.resize(n);
            for (std::size_t i = 0; i < n; ++i) want[i] = w[id][i] * cov_.gain(lines_[id][i].px, kMaxGain);
            // each run of points not dropped, kept when it has 2 points and min_length_px
            for (std::size_t i = 0, e = 0; i < n; i = e) {
                if (dropped(i)) {
                    e = i + 1;
                    continue;
                }
                float length = 0.0f;
                for (e = i + 1; e < n && !dropped(e); ++e) length += glm::length(lines_[id][e].px - lines_[id][e - 1].px);
                if (e - i < 2 || !(length >= p_.min_length_px)) continue;
                std::vector<double> piece_w(want.begin() + std::ptrdiff_t(i), want.begin() + std::ptrdiff_t(e));
                for (double& v : piece_w) v = std::clamp(v, lo, hi);
                kept_w.push_back(std::move(piece_w));
                if (i == 0 && e == n) {  // the whole line
                    kept_lines.push_back(std::move(lines_[id])), kept_gap.push_back(std::move(gap[id]));
                } else {
                    kept_lines.emplace_back(lines_[id].begin() + std::ptrdiff_t(i), lines_[id].begin() + std::ptrdiff_t(e));
                    kept_gap.emplace_back(gap[id].begin() + std::ptrdiff_t(i), gap[id].begin() + std::ptrdiff_t(e));
                }
            }
        }
        lines_ = std::move(kept_lines), w = std::move(kept_w), gap = std::move(kept_gap);
    }

    const NodeTileCounts& node_counts() const { return field_.node_counts(); }

    std::vector<Stroke> strokes() const {
        std::vector<Stroke> out;
        out.reserve(lines_.size());
        for (std::uint32_t id = 0; id < lines_.size(); ++id) {
            const std::vector<Sample>& line = lines_[id];
            Stroke s;
            s.kind = "hachure";
            double tone = 0.0;
            s.points.reserve(line.size()), s.depth.reserve(line.size());
            for (const Sample& p : line) {
                s.points.push_back(p.px);
                s.depth.push_back(float(p.depth));
                tone += p.tone;
            }
            s.weight = id < weights_.size() ? weights_[id] : weights(id, gaps(id));
            s.strength = float(tone / double(line.size()));
            out.push_back(simplify_stroke(s, 0.2f));
        }
        return out;
    }

private:
    SlopeField field_;
    const HachureFrame& frame_;
    const HachureParams& p_;
    const Camera& cam_;
    PixelProjector project_;
    Occupancy occ_;
    VisibilityOptions visibility_;
    double min_grad_ = 0.0, width_ = 1.0;
    double cell_m_ = 0.0;  // median node spacing, metres
    double near_ = 0.0;    // nearest visible eye distance (of land, with a sea)
    float floor_z_ = -std::numeric_limits<float>::infinity();
    bool perspective_ = true;
    glm::dvec3 toward_ortho_{0.0};  // towards the viewer, orthographic
    std::vector<std::vector<Sample>> lines_;
    std::vector<std::vector<float>> weights_;  // per line and point, after balance()
    std::deque<std::uint32_t> queue_;
    InkCoverage cov_;
    struct LatticeSeed {
        glm::dvec2 uv;
        glm::vec2 px;
    };
    std::vector<LatticeSeed> seeds_;  // the lattice's hatched seeds, for reseed()
    bool tighten_ = false;            // reseed(): separations tightened by the coverage
};

}  // namespace

std::vector<Stroke> trace_hachures(const HachureGrid& grid, const HachureFrame& frame, const HachureParams& params) {
    if (!params.enabled || !frame.camera || (!(grid.pos && grid.valid) && !grid.read) || grid.c1 - grid.c0 < 2 ||
        grid.r1 - grid.r0 < 2)
        return {};
    Tracer tracer(grid, frame, params);
    tracer.run(grid);
    tracer.reseed();
    tracer.balance();
    if (grid.counts) *grid.counts = tracer.node_counts();
    return tracer.strokes();
}

}  // namespace penink
