#include "surface/terrain_lod.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "core/parallel_chunks.hpp"

namespace penink {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kDeg = 3.14159265358979323846 / 180.0;

void check_terrain(const Terrain& t) {
    if (t.cols < 0 || t.rows < 0 || t.pos.size() != t.size() || t.valid.size() != t.size())
        throw std::invalid_argument("terrain lod: terrain positions/valid flags do not match its grid");
}

void check_nodes(const GridNodes& t) {
    if (t.cols < 0 || t.rows < 0 || (t.size() > 0 && (!t.pos || !t.valid)))
        throw std::invalid_argument("terrain lod: terrain positions/valid flags do not match its grid");
    if (std::max(t.cols, t.rows) > (1 << 30))
        throw std::invalid_argument("terrain lod: grid too large");
}

// Rows [0, n] of a level in parallel when there are enough of them.
template <class F> void each_row(int first, int last, int step, std::size_t work_per_row, F&& f) {
    if (last < first) return;
    const std::size_t count = std::size_t((last - first) / step + 1);
    const std::size_t min_rows = std::max<std::size_t>(1, (1u << 16) / std::max<std::size_t>(work_per_row, 1));
    parallel_chunks(count, min_rows, [&](std::size_t b, std::size_t e) {
        for (std::size_t k = b; k < e; ++k) f(first + int(k) * step);
    });
}

// An upper bound on the largest singular value, over the full-resolution triangles, of the plan
// positions' piecewise-linear map from grid units (column, row) to metres (lod_cells_lipschitz2).
double plan_lipschitz(const GridNodes& t) {
    const std::size_t rows = std::size_t(std::max(t.rows - 1, 0));
    const std::size_t per = chunk_length(rows, 64);
    std::vector<float> part((rows + per - 1) / per + 1, 0.0f);
    parallel_chunks(rows, 64, [&](std::size_t r0, std::size_t r1) {
        float best = 0.0f;
        for (std::size_t r = r0; r < r1; ++r)
            best = std::max(best, lod_cells_lipschitz2(&t.pos[t.index(0, int(r))].x, &t.pos[t.index(0, int(r) + 1)].x,
                                                       t.cols, 3));
        part[r0 / per] = best;
    });
    return std::sqrt(double(*std::max_element(part.begin(), part.end())));
}

// Nested plan radii by level. A node's radius is L times a grid-unit radius nested exactly over
// its children's distances: R(edge, 2) = 1 (the finest diamonds' corners), R(centre, s) =
// R(edge, s) + s/2, R(edge, 2s) = R(centre, s) + s/sqrt(2), for the squares of side s = 2^(k+1);
// padding nodes take the same values (positions clamped to the DEM are L-Lipschitz too).
struct LevelRadii {
    float edge[32] = {}, centre[32] = {};  // by k = log2(s / 2)
};

LevelRadii level_radii(float lip, int levels) {
    const double grow = 1.0 + 1e-5;  // rounding of L, of the products and of the sums below
    LevelRadii out;
    double r_centre = 0.0;  // R of the centre nodes of the previous level
    for (int k = 0; k < levels && k < 32; ++k) {
        const int s = 2 << k, half = s / 2;
        const double r_edge = s == 2 ? 1.0 : r_centre + (s / 4) * std::sqrt(2.0);
        r_centre = r_edge + half;
        out.edge[k] = float(lip * r_edge * grow), out.centre[k] = float(lip * r_centre * grow);
    }
    return out;
}

// The level of node (c, r) (its squares' side is 2^(k+1)) and whether it is a square's centre;
// false at the padded square's corners.
bool node_level(int c, int r, int levels, int& k, bool& centre) {
    const unsigned u = unsigned(c) | unsigned(r);
    if (u == 0) return false;
    k = std::countr_zero(u);
    if (k >= levels) return false;
    centre = std::countr_zero(unsigned(c)) == k && std::countr_zero(unsigned(r)) == k;
    return true;
}

}  // namespace

float TerrainLod::radius(int c, int r) const {
    int k = 0;
    bool centre = false;
    if (!node_level(c, r, levels, k, centre)) return 0.0f;
    const LevelRadii radii = level_radii(lipschitz, levels);
    return centre ? radii.centre[k] : radii.edge[k];
}

// For a triangle's Jacobian [u v], sigma^2 = the largest eigenvalue of [[u.u, u.v], [u.v, v.v]]
// <= max(u.u, v.v) + |u.v| (Gershgorin; equal on a grid with perpendicular axes).
float lod_cells_lipschitz2(const float* p, const float* q, int cols, int stride) {
    auto bound2 = [](float ux, float uy, float vx, float vy) {
        return std::max(ux * ux + uy * uy, vx * vx + vy * vy) + std::abs(ux * vx + uy * vy);
    };
    float best = 0.0f;
    for (int c = 0; c + 1 < cols; ++c) {
        // Triangles {a, s, d}: columns d - s, rows s - a; {a, d, b}: columns b - a, rows d - b.
        const float* a = p + std::ptrdiff_t(c) * stride;
        const float* b = a + stride;
        const float* sw = q + std::ptrdiff_t(c) * stride;
        const float* d = sw + stride;
        best = std::max(best, bound2(d[0] - sw[0], d[1] - sw[1], sw[0] - a[0], sw[1] - a[1]));
        best = std::max(best, bound2(b[0] - a[0], b[1] - a[1], d[0] - b[0], d[1] - b[1]));
    }
    return best;
}

TerrainLod build_terrain_lod(const Terrain& t) {
    check_terrain(t);
    return build_terrain_lod(grid_nodes(t), t.vertical_exaggeration);
}

int lod_padded_levels(int cols, int rows) {
    int k = 0;
    while ((1 << k) + 1 < std::max(cols, rows)) ++k;
    return k;
}

namespace {

// Heights, signed deviation bounds and forced flags of the padded nodes (c, r) with c, r multiples
// of g and rows b0..b1 (a strip of the padded square, or all of it at a coarser spacing).
struct LevelGrid {
    int n = 0, g = 1, b0 = 0, b1 = 0, w = 0;
    std::vector<float> h, up, lo;
    std::vector<std::uint8_t> forced;

    void shape(int n_, int g_, int b0_, int b1_) {
        n = n_, g = g_, b0 = b0_, b1 = b1_, w = n / g + 1;
        const std::size_t count = std::size_t((b1 - b0) / g + 1) * std::size_t(w);
        h.resize(count), up.assign(count, 0.0f), lo.assign(count, 0.0f), forced.resize(count);
    }
    std::size_t at(int c, int r) const { return std::size_t((r - b0) / g) * std::size_t(w) + std::size_t(c / g); }
};

// Settles the nodes of the levels s_first..s_last (square sides, powers of two) that lie in g's
// rows, bottom-up: up(m) = max over its children of up, plus max(0, delta), lo likewise with
// min, up = +inf where forced (terrain_lod.hpp). A node whose hypotenuse ends or children lie
// outside the rows is left out or takes the children it has: its value is then wrong, and so
// are the values depending on it; a node whose rows of dependence (rows within 3/2 s + 1 of
// its own, lod_apron) all lie in g is settled as on the whole square.
void settle_levels(LevelGrid& g, int s_first, int s_last) {
    const int n = g.n;
    const float* h = g.h.data();
    const std::uint8_t* forced = g.forced.data();
    float* up = g.up.data();
    float* lo = g.lo.data();
    auto at = [&g](int c, int r) { return g.at(c, r); };
    // Node m split of hypotenuse a-b, children k[0..cnt).
    auto settle = [&](std::size_t m, std::size_t a, std::size_t b, const std::size_t* k, int cnt) {
        const float d = h[m] - 0.5f * (h[a] + h[b]);
        float cu = 0.0f, cl = 0.0f;
        for (int i = 0; i < cnt; ++i) cu = std::max(cu, up[k[i]]), cl = std::min(cl, lo[k[i]]);
        up[m] = forced[m] ? kInf : cu + std::max(0.0f, d);
        lo[m] = cl + std::min(0.0f, d);
    };
    for (int s = s_first; s <= s_last; s *= 2) {
        const int half = s / 2, q = s / 4;
        // Edge nodes: midpoints of the sides of the s-squares; children the centres of the
        // s/2-squares around them (none at s = 2).
        each_row((g.b0 + half - 1) / half * half, g.b1 / half * half, half, std::size_t(n / s) + 1, [&](int r) {
            const bool horizontal = r % s == 0;  // on a row of square sides: hypotenuse along the row
            if (!horizontal && (r - half < g.b0 || r + half > g.b1)) return;
            for (int c = horizontal ? half : 0; c <= n; c += s) {
                std::size_t k[4];
                int cnt = 0;
                if (q > 0) {
                    for (const int dr : {-q, q}) {
                        if (r + dr < g.b0 || r + dr > g.b1) continue;
                        for (const int dc : {-q, q})
                            if (c + dc >= 0 && c + dc <= n) k[cnt++] = at(c + dc, r + dr);
                    }
                }
                if (horizontal) settle(at(c, r), at(c - half, r), at(c + half, r), k, cnt);
                else settle(at(c, r), at(c, r - half), at(c, r + half), k, cnt);
            }
        });
        // Centre nodes of the s-squares: the square's diagonal passes through the centre of its
        // 2s-square (the root square's: NW-SE); children the midpoints of its 4 sides.
        const int first = std::max(g.b0 + half, half), last = std::min(g.b1, n) - half;
        each_row(first + ((half - first) % s + s) % s, last - ((last - half) % s + s) % s, s, std::size_t(n / s),
                 [&](int r) {
                     for (int c = half; c < n; c += s) {
                         const bool nwse = ((c / s) & 1) == ((r / s) & 1);
                         const std::size_t k[4] = {at(c - half, r), at(c + half, r), at(c, r - half), at(c, r + half)};
                         if (nwse) settle(at(c, r), at(c - half, r - half), at(c + half, r + half), k, 4);
                         else settle(at(c, r), at(c + half, r - half), at(c - half, r + half), k, 4);
                     }
                 });
    }
}

// Rows a node of level s (squares of side s) depends on, either side of its own: its hypotenuse
// ends and children reach s - 1 rows from an edge node and 3/2 s - 1 from a centre node, and
// the forced flags one row further.
std::int64_t lod_apron(int s) { return 3 * std::int64_t(s) / 2 + 1; }

// g's rows b0..b1 (g = 1) from the DEM: heights (0 where invalid: such nodes only ever feed
// forced, +inf, nodes) and forced = invalid (nodata, padding) dilated by the 3x3 square.
void load_strip(const LodHeights& dem, LevelGrid& g) {
    const int n = g.n, side = n + 1;
    // rows g.b0 - 1 .. g.b1 + 1 (the forced flags' dilation) that the DEM has
    const int r0 = std::clamp(g.b0 - 1, 0, dem.rows), r1 = std::clamp(g.b1 + 2, r0, dem.rows);
    const LodRows rows = dem.load ? dem.load(r0, r1) : LodRows{dem.z, dem.valid, 0};
    auto z_row = [&](int r) { return rows.z + std::size_t(r - rows.first) * std::size_t(dem.cols); };
    auto valid_row = [&](int r) { return rows.valid + std::size_t(r - rows.first) * std::size_t(dem.cols); };
    auto bad_row = [&](int r, std::uint8_t* out) {
        if (r >= dem.rows) return void(std::fill(out, out + side, std::uint8_t(1)));
        const std::uint8_t* v = valid_row(r);
        for (int c = 0; c < dem.cols; ++c) out[c] = std::uint8_t(v[c] == 0);
        std::fill(out + dem.cols, out + side, std::uint8_t(1));
    };
    parallel_chunks(std::size_t(g.b1 - g.b0 + 1), 16, [&](std::size_t i0, std::size_t i1) {
        std::vector<std::uint8_t> bad(3 * std::size_t(side)), wide(side);
        for (std::size_t i = i0; i < i1; ++i) {
            const int r = g.b0 + int(i);
            float* h = &g.h[g.at(0, r)];
            std::fill(h, h + side, 0.0f);
            if (r < dem.rows) {
                const float* z = z_row(r);
                const std::uint8_t* v = valid_row(r);
                for (int c = 0; c < dem.cols; ++c)
                    if (v[c]) h[c] = z[c];
            }
            std::fill(wide.begin(), wide.end(), std::uint8_t(0));
            for (int dr = -1; dr <= 1; ++dr) {
                if (r + dr < 0 || r + dr > n) continue;
                bad_row(r + dr, bad.data());
                for (int c = 0; c < side; ++c) wide[c] |= bad[c];
            }
            std::uint8_t* f = &g.forced[g.at(0, r)];
            for (int c = 0; c < side; ++c)
                f[c] = std::uint8_t(wide[c] | (c > 0 ? wide[c - 1] : 0) | (c < n ? wide[c + 1] : 0));
        }
    });
}

}  // namespace

std::int64_t lod_strip_rows(const LodStrips& strips) { return strips.strip_rows + 2 * lod_apron(strips.fine_side); }

double lod_errors_bytes(int cols, int rows, const LodStrips& strips) {
    const int n = 1 << lod_padded_levels(cols, rows);
    const double side = double(n) + 1.0, fine = double(strips.fine_side);
    if (fine > n / 2) return 13.0 * side * side;  // one strip, every level on it
    const double strip = std::min(double(lod_strip_rows(strips)), side);
    const double top = double(n) / (fine / 2.0) + 1.0;
    return 13.0 * side * strip + 4.0 * side * (double(n) / fine + 1.0) + 13.0 * top * top;
}

void lod_errors(const LodHeights& dem, const LodStrips& strips, const std::function<void(int, int, const float*)>& emit) {
    const int levels = lod_padded_levels(dem.cols, dem.rows), n = 1 << levels, side = n + 1;
    if (dem.cols < 2 || dem.rows < 2) {
        const std::vector<float> zeros(side, 0.0f);
        for (int r = 0; r <= n; ++r) emit(r, r + 1, zeros.data());
        return;
    }
    if (strips.strip_rows < 1 || strips.fine_side < 2 || !std::has_single_bit(unsigned(strips.fine_side)))
        throw std::invalid_argument("terrain lod: strips of at least a row, fine squares a power of two >= 2");
    // The levels above fine_side, on the nodes every fine_side / 2 (their children at the
    // lowest of them are the centres of the fine_side squares): rows every fine_side, which
    // hold those nodes, wait for them.
    const int fine = strips.fine_side;
    const bool coarse = fine <= n / 2;
    const int fine_last = coarse ? fine : n;
    const std::int64_t apron = lod_apron(fine_last);
    LevelGrid top;
    if (coarse) top.shape(n, fine / 2, 0, n);
    std::vector<std::vector<float>> held(coarse ? std::size_t(n / fine + 1) : 0);
    LevelGrid g;
    for (int y0 = 0; y0 <= n; y0 = int(std::min<std::int64_t>(std::int64_t(y0) + strips.strip_rows, n + 1))) {
        const int y1 = int(std::min<std::int64_t>(std::int64_t(y0) + strips.strip_rows, n + 1));  // the strip's rows y0..y1 - 1
        g.shape(n, 1, int(std::max<std::int64_t>(0, y0 - apron)), int(std::min<std::int64_t>(n, y1 - 1 + apron)));
        load_strip(dem, g);
        settle_levels(g, 2, fine_last);
        if (coarse) {
            for (int r = (y0 + top.g - 1) / top.g * top.g; r < y1; r += top.g)
                for (int c = 0; c <= n; c += top.g) {
                    const std::size_t i = g.at(c, r), j = top.at(c, r);
                    top.h[j] = g.h[i], top.forced[j] = g.forced[i], top.up[j] = g.up[i], top.lo[j] = g.lo[i];
                }
        }
        float* e = &g.up[g.at(0, y0)];
        const float* lo = &g.lo[g.at(0, y0)];
        parallel_chunks(std::size_t(y1 - y0) * std::size_t(side), 1 << 18, [&](std::size_t b, std::size_t end) {
            for (std::size_t i = b; i < end; ++i) e[i] = std::max(e[i], -lo[i]);
        });
        for (int r = y0; r < y1;) {
            if (coarse && r % fine == 0) {
                const float* row = &g.up[g.at(0, r)];
                held[std::size_t(r / fine)].assign(row, row + side);
                ++r;
                continue;
            }
            const int end = coarse ? std::min(y1, (r / fine + 1) * fine) : y1;
            emit(r, end, &g.up[g.at(0, r)]);
            r = end;
        }
    }
    g = {};
    if (!coarse) return;
    settle_levels(top, 2 * fine, n);
    for (std::size_t k = 0; k < held.size(); ++k) {
        const int r = int(k) * fine;
        for (int c = 0; c <= n; c += fine) {
            const std::size_t j = top.at(c, r);
            held[k][std::size_t(c)] = std::max(top.up[j], -top.lo[j]);
        }
        emit(r, r + 1, held[k].data());
        held[k] = {};
    }
}

void lattice_add_row(int cols, int rows, int r, const float* z, const std::uint8_t* v, LatticeNode* lattice) {
    const int lc = lattice_size(cols), lr = lattice_size(rows);
    for (int dr = -1; dr <= 1; ++dr) {  // the lattice row at r - dr reads this row as its neighbours' row dr
        const int at = r - dr;
        if (at < 0 || at % lod_lattice_step != 0 || at / lod_lattice_step >= lr) continue;
        LatticeNode* row = lattice + std::size_t(at / lod_lattice_step) * std::size_t(lc);
        for (int k = 0; k < 7; ++k) {
            if (lattice_neighbours[k][1] != dr) continue;
            for (int j = 0; j < lc; ++j) {
                const int c = j * lod_lattice_step + lattice_neighbours[k][0];
                if (c < 0 || c >= cols) continue;
                LatticeNode& n = row[j];
                n.z[k] = z[c];
                if (v[c]) n.valid = float(int(n.valid) | (1 << k));
            }
        }
    }
}

void lattice_add_errors(int cols, int r, const float* e, LatticeNode* lattice) {
    if (r % lod_lattice_step != 0) return;
    const int lc = lattice_size(cols);
    LatticeNode* row = lattice + std::size_t(r / lod_lattice_step) * std::size_t(lc);
    for (int j = 0; j < lc; ++j) row[j].error = e[j * lod_lattice_step];
}

int lod_dem_rows(int cols, int rows, int side, int r0, int r1, const float* e, float* out) {
    const int n = std::max(0, std::min(r1, rows) - r0);
    for (int j = 0; j < n; ++j)
        std::copy_n(e + std::size_t(j) * std::size_t(side), cols, out + std::size_t(j) * std::size_t(cols));
    return n;
}

TerrainLod build_terrain_lod(const GridNodes& t, double ex) {
    check_nodes(t);
    t.need(GridWindow{0, 0, t.cols, t.rows});  // every node, read directly below (and by other threads)
    if (!(ex > 0.0) || !std::isfinite(ex)) throw std::invalid_argument("terrain lod: vertical exaggeration must be > 0");
    TerrainLod lod;
    lod.cols = t.cols, lod.rows = t.rows;
    lod.levels = lod_padded_levels(t.cols, t.rows);
    const int side = lod.side();
    auto error = std::make_shared<std::vector<float>>(std::size_t(t.cols) * std::size_t(t.rows), 0.0f);
    lod.error = *error;
    lod.storage = error;
    if (t.cols < 2 || t.rows < 2) return lod;

    // Unexaggerated heights of the valid nodes and their range.
    std::vector<float> h(t.size(), 0.0f);
    float zmin = kInf, zmax = -kInf;
    for (std::size_t i = 0; i < t.size(); ++i) {
        if (!t.valid[i]) continue;
        const float z = float(double(t.at(i).z) / ex);
        h[i] = z;
        zmin = std::min(zmin, z), zmax = std::max(zmax, z);
    }
    lod.z_min = zmin <= zmax ? zmin : 0.0f, lod.z_max = zmin <= zmax ? zmax : 0.0f;
    lod.sea_level = t.sea_level;  // at() drew the nodes clamped to it
    lod_errors(LodHeights{t.cols, t.rows, h.data(), t.valid}, LodStrips{},
               [&](int r0, int r1, const float* e) {
                   if (r0 < t.rows) lod_dem_rows(t.cols, t.rows, side, r0, r1, e, error->data() + std::size_t(r0) * t.cols);
               });
    // L: a Lipschitz constant of the nodes' plan positions over the grid (plan_lipschitz:
    // |xy(p) - xy(q)| <= L |p - q|, grid units, for any nodes p, q; the cell side on a square
    // grid); the radii follow from it and the level (level_radii).
    lod.lipschitz = float(plan_lipschitz(t));
    return lod;
}

double lod_pixel_scale(const Camera& cam) {
    const double aspect = double(cam.width) / double(cam.height);
    const double tx = std::tan(cam.fov * kDeg / 2.0), ty = tx / aspect;
    const double focal = double(cam.height) / (2.0 * ty);
    return focal * (1.0 + tx * tx + ty * ty);
}

namespace {

// Map from DEM node to (output vertex + 1) in the low 30 bits, plus two flags: open addressing
// with linear probing over the nodes a selection visits, so that its memory follows the
// selection, not the DEM.
constexpr std::uint32_t kIndexMask = (1u << 30) - 1, kActiveFlag = 1u << 31, kCellFlag = 1u << 30;

class NodeMap {
public:
    NodeMap() { resize(std::size_t(1) << 12); }
    // The entry of node `id` (0 when new).
    std::uint32_t& operator[](std::size_t id) {
        const std::uint64_t key = std::uint64_t(id) + 1;
        std::size_t i = slot(key);
        while (keys_[i] != 0 && keys_[i] != key) i = (i + 1) & mask_;
        if (keys_[i] == key) return values_[i];
        if (2 * (count_ + 1) > keys_.size()) {  // at most half full
            resize(keys_.size() * 2);
            return (*this)[id];
        }
        ++count_;
        keys_[i] = key;
        return values_[i];
    }

private:
    std::vector<std::uint64_t> keys_;  // node + 1; 0 empty
    std::vector<std::uint32_t> values_;
    std::size_t mask_ = 0, count_ = 0;

    std::size_t slot(std::uint64_t key) const { return std::size_t((key * 0x9E3779B97F4A7C15ull) >> 20) & mask_; }
    void resize(std::size_t n) {
        std::vector<std::uint64_t> keys(n, 0);
        std::vector<std::uint32_t> values(n, 0);
        mask_ = n - 1;
        for (std::size_t j = 0; j < keys_.size(); ++j) {
            if (keys_[j] == 0) continue;
            std::size_t i = slot(keys_[j]);
            while (keys[i] != 0) i = (i + 1) & mask_;
            keys[i] = keys_[j], values[i] = values_[j];
        }
        keys_ = std::move(keys), values_ = std::move(values);
    }
};

struct Frustum {
    glm::dvec4 plane[6];
    // 0 outside, 1 crossing, 2 inside (plane x >= 0 inside).
    int classify(const glm::dvec3& lo, const glm::dvec3& hi) const {
        bool inside = true;
        for (const glm::dvec4& p : plane) {
            const glm::dvec3 far(p.x >= 0 ? hi.x : lo.x, p.y >= 0 ? hi.y : lo.y, p.z >= 0 ? hi.z : lo.z);
            if (p.x * far.x + p.y * far.y + p.z * far.z + p.w < 0.0) return 0;
            const glm::dvec3 near(p.x >= 0 ? lo.x : hi.x, p.y >= 0 ? lo.y : hi.y, p.z >= 0 ? lo.z : hi.z);
            if (p.x * near.x + p.y * near.y + p.z * near.z + p.w < 0.0) inside = false;
        }
        return inside ? 2 : 1;
    }
};

Frustum frustum_of(const Camera& cam) {
    const glm::dmat4 m = view_projection(cam);
    auto row = [&](int i) { return glm::dvec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
    Frustum f;
    f.plane[0] = row(3) + row(0), f.plane[1] = row(3) - row(0);
    f.plane[2] = row(3) + row(1), f.plane[3] = row(3) - row(1);
    f.plane[4] = row(3) + row(2), f.plane[5] = row(3) - row(2);
    return f;
}

// What water adds to every error bound (terrain_lod.hpp): nodes drawn at max(z, s) (GridNodes::
// sea_level, unexaggerated s). The clamp can raise a coarse triangle's error: corners -100 and
// 100 over a linear slope (error 0) at s = 0 give the coarse plane 50 where the clamped DEM is 0
// at the middle. Bound, for a triangle with corner heights z_i, barycentric weights w_i at a node
// of height z_p, L(z) = sum w_i z_i, |L(z) - z_p| <= err: with cl(z) = max(z, s),
//  below: L(cl z) >= max(L(z), s) (convexity) and max(., s) is 1-Lipschitz, so
//         L(cl z) - cl(z_p) >= -err;
//  above: L(cl z) - cl(z_p) <= L(z) - z_p + sum w_i (s - z_i)+ <= err + (s - z_min)+ (cl(z_p) >= z_p),
//         and, when some corner is above s, L(cl z) <= z_max and cl(z_p) >= s give <= z_max - s;
//         when none is, L(cl z) = s <= cl(z_p).
// So err + min((s - z_min)+, (z_max - s)+), z_min and z_max the DEM's range: 0 for a DEM wholly
// above or below the sea (the selection is then unchanged), and a constant, so the bounds stay
// nested and the mesh crack-free.
// Unexaggerated metres: the water's drawn height over the exaggeration the errors are drawn at.
float water_error(const TerrainLod& lod, const GridNodes& t, double exaggeration) {
    if (lod.sea_level == t.sea_level) return 0.0f;  // the errors are the clamped nodes' (or no water)
    if (lod.sea_level > -std::numeric_limits<double>::infinity())
        throw std::invalid_argument("terrain lod: the pyramid was built for another sea level");
    const double s = double(t.sea_z()) / exaggeration;
    const double extra = std::min(std::max(0.0, s - double(lod.z_min)), std::max(0.0, double(lod.z_max) - s));
    return extra > 0.0 ? float(extra * (1.0 + 1e-5)) : 0.0f;  // rounded up
}

struct Item {
    int ac, ar, bc, br, cc, cr;  // hypotenuse a-b, right angle at c; grid (column, row)
    bool inside;                 // an ancestor's box lies inside the frustum
};

class Selector {
public:
    Selector(const TerrainLod& lod, const GridNodes& t, double ex, const Camera& cam, const LodOptions& o,
             std::vector<std::uint32_t>* nodes)
        : lod_(lod), t_(t), reader_(t), side_(lod.side()), cols_(t.cols), rows_(t.rows), nodes_(nodes),
          radii_(level_radii(lod.lipschitz, lod.levels)) {
        ex_ = ex;
        // Orthographic: a metre is the same number of pixels at any depth, so the test's distance
        // is 1 and the scale is pixels per metre (monotone all the same: error and radius grow
        // from a node to its parents).
        ortho_ = is_orthographic(cam);
        const double px_scale = ortho_ ? 1.0 / world_per_pixel(cam, 1.0) : lod_pixel_scale(cam);
        scale_ = ex * px_scale;
        water_ = water_error(lod, t, ex);
        tol_ = std::max(0.0, double(o.tolerance_px));
        min_radius_ = std::max(0.0, double(o.min_radius_px)) / px_scale;  // metres at unit distance
        near_ = std::max(cam.near_plane, 1e-6);
        eye_ = cam.eye;
        zlo_ = double(lod.z_min) * ex, zhi_ = double(lod.z_max) * ex;
        const double slack = 1e-6 * std::max(std::abs(zlo_), std::abs(zhi_)) + 1e-6;
        zlo_ -= slack, zhi_ += slack;
        const double vz = std::max({0.0, eye_.z - zhi_, zlo_ - eye_.z});
        vz2_ = vz * vz;
        frustum_ = frustum_of(cam);
        if (lod.blocks) errors_.emplace(*lod.blocks, TerrainLod::error_array, 4096);
        derives_ = t.derive_xy(0, 1, 0, nullptr);
        if (lod.blocks && lod.lattice_step == lod_lattice_step && derives_)
            lattice_.emplace(*lod.blocks, TerrainLod::lattice_array, 512);
        lattice_cols_ = std::size_t(lattice_size(cols_));
    }

    SurfaceMesh run(LodSelection* stats) {
        const int n = side_ - 1;
        std::vector<Item> stack;
        stack.reserve(256);
        // Root: the square halved along its NW-SE diagonal, both halves counter-clockwise from above.
        stack.push_back({0, 0, n, n, n, 0, false});
        stack.push_back({n, n, 0, 0, 0, n, false});
        while (!stack.empty()) {
            Item it = stack.back();
            stack.pop_back();
            const int c0 = std::min({it.ac, it.bc, it.cc}), r0 = std::min({it.ar, it.br, it.cr});
            if (c0 >= cols_ - 1 || r0 >= rows_ - 1) continue;  // only padding cells
            if (std::abs(it.ac - it.bc) == 1 && std::abs(it.ar - it.br) == 1) {
                leaf(it);
                continue;
            }
            const int mc = (it.ac + it.bc) / 2, mr = (it.ar + it.br) / 2;
            const float err = error(mc, mr);
            if (!it.inside) {
                const int cls = classify_triangle(it, err);
                if (cls == 0) continue;
                it.inside = cls == 2;
            }
            if (active(mc, mr)) {
                count_active(mc, mr);
                // Children keep the orientation: (b, c, m) and (c, a, m); the first pushed last.
                stack.push_back({it.bc, it.br, it.cc, it.cr, mc, mr, it.inside});
                stack.push_back({it.cc, it.cr, it.ac, it.ar, mc, mr, it.inside});
                continue;
            }
            if (ok(it.ac, it.ar) && ok(it.bc, it.br) && ok(it.cc, it.cr)) emit(it.ac, it.ar, it.bc, it.br, it.cc, it.cr);
        }
        if (stats) *stats = {out_.tri.size(), out_.pos.size(), active_count_};
        return std::move(out_);
    }

    // The grid box and bounds of the triangles that meet the frustum, descending only into those
    // that cross its boundary, down to triangles of min_side grid units.
    LodView window(int min_side) const {
        LodView v;
        v.lo = glm::dvec3(1e300), v.hi = glm::dvec3(-1e300);
        int c_lo = cols_, r_lo = rows_, c_hi = -1, r_hi = -1;
        const int n = side_ - 1;
        std::vector<Item> stack{{0, 0, n, n, n, 0, false}, {n, n, 0, 0, 0, n, false}};
        while (!stack.empty()) {
            const Item it = stack.back();
            stack.pop_back();
            const int c0 = std::min({it.ac, it.bc, it.cc}), r0 = std::min({it.ar, it.br, it.cr});
            if (c0 >= cols_ - 1 || r0 >= rows_ - 1) continue;  // only padding cells
            const int mc = (it.ac + it.bc) / 2, mr = (it.ar + it.br) / 2;
            const float err = error(mc, mr);
            glm::dvec3 lo, hi;
            const int cls = classify_triangle(it, err, lo, hi);
            if (cls == 0) continue;
            const int extent = std::max(std::abs(it.ac - it.bc), std::abs(it.ar - it.br));
            if (cls == 1 && extent > std::max(min_side, 1)) {
                stack.push_back({it.bc, it.br, it.cc, it.cr, mc, mr, false});
                stack.push_back({it.cc, it.cr, it.ac, it.ar, mc, mr, false});
                continue;
            }
            c_lo = std::min(c_lo, c0), r_lo = std::min(r_lo, r0);
            c_hi = std::max(c_hi, std::min(std::max({it.ac, it.bc, it.cc}), cols_ - 1));
            r_hi = std::max(r_hi, std::min(std::max({it.ar, it.br, it.cr}), rows_ - 1));
            v.lo = glm::min(v.lo, lo), v.hi = glm::max(v.hi, hi);
        }
        if (c_hi < 0) return {};
        v.window = {c_lo, r_lo, c_hi + 1, r_hi + 1};
        return v;
    }

private:
    const TerrainLod& lod_;
    const GridNodes& t_;
    // The nodes and errors read one at a time through small block caches (NodePointReader): the
    // selection of a whole view touches a few nodes in most blocks of a large DEM.
    mutable NodePointReader reader_;
    mutable std::optional<CheckedBlocks::Cached> errors_;
    // The node lattice (TerrainLod::lattice_step; none: empty), its last node read, and whether
    // the nodes' x, y come from the grid's formula (GridNodes::derive_xy) without a block read.
    mutable std::optional<CheckedBlocks::Cached> lattice_;
    mutable LatticeNode lattice_node_;
    mutable std::size_t lattice_at_ = std::size_t(-1), lattice_cols_ = 0;
    bool derives_ = false;
    int side_, cols_, rows_;
    std::vector<std::uint32_t>* nodes_;
    LevelRadii radii_;
    float water_ = 0.0f;  // water_error: what the sea level adds to every bound
    double ex_ = 1.0, scale_ = 1.0, tol_ = 1.0, min_radius_ = 0.0, near_ = 1.0, zlo_ = 0.0, zhi_ = 0.0, vz2_ = 0.0;
    bool ortho_ = false;
    glm::dvec3 eye_{0.0};
    Frustum frustum_;
    SurfaceMesh out_;
    NodeMap map_;
    std::size_t active_count_ = 0;

    // The error bound of node (c, r) of the padded square for the nodes as drawn (water included).
    float error(int c, int r) const {
        if (lod_.padding(c, r)) return kInf;
        const std::size_t k = lod_.index(c, r);
        float e;
        if (on_lattice(c, r)) e = lattice(c, r).error;
        else if (errors_) std::memcpy(&e, errors_->element(k), sizeof e);
        else e = lod_.error[k];
        return water_ > 0.0f ? e + water_ : e;
    }
    bool in_dem(int c, int r) const { return c < cols_ && r < rows_; }
    bool ok(int c, int r) const { return in_dem(c, r) && has_data(c, r); }

    // Node (c, r) of the DEM: on the lattice, read there (a copy, until the next lattice node).
    bool on_lattice(int c, int r) const {
        return lattice_ && c % lod_lattice_step == 0 && r % lod_lattice_step == 0;
    }
    const LatticeNode& lattice(int c, int r) const {
        const std::size_t k = std::size_t(r / lod_lattice_step) * lattice_cols_ + std::size_t(c / lod_lattice_step);
        if (k != lattice_at_) std::memcpy(&lattice_node_, lattice_->element(k), sizeof lattice_node_), lattice_at_ = k;
        return lattice_node_;
    }
    bool has_data(int c, int r) const {
        if (on_lattice(c, r)) return (int(lattice(c, r).valid) & 1) != 0;
        return reader_.has_data(t_.index(c, r));
    }
    // Its position as drawn (GridNodes::at), and its plan position alone (z unset where derived).
    glm::vec3 at(int c, int r) const {
        if (!on_lattice(c, r)) return reader_.at(c, r);
        glm::vec3 p(0.0f, 0.0f, lattice(c, r).z[0]);
        t_.derive_xy(t_.index(c, r), 1, 1, &p);
        return t_.drawn(p);
    }
    glm::vec3 plan(int c, int r) const {
        glm::vec3 p(0.0f);
        return derives_ && t_.derive_xy(t_.index(c, r), 1, 1, &p) ? p : reader_.at(c, r);
    }

    // Lindstrom & Pascucci's test: error projected at the distance from the eye to the node's
    // bounding region exceeds the tolerance. Monotone from a node to its parents.
    bool active(int c, int r) const {
        const float err = error(c, r);
        if (!(err < kInf)) return true;  // forced (or NaN)
        if (!(err > 0.0f)) return false;
        if (!in_dem(c, r)) return true;  // cannot happen: padding nodes are forced
        const glm::vec3 p = plan(c, r);  // z unused
        const double dx = double(p.x) - eye_.x, dy = double(p.y) - eye_.y;
        int level = 0;
        bool centre = false;
        if (!node_level(c, r, lod_.levels, level, centre)) return true;  // cannot happen: corners are never split
        const double rad = double(centre ? radii_.centre[level] : radii_.edge[level]), plan = std::sqrt(dx * dx + dy * dy) - rad;
        const double d = ortho_ ? 1.0 : std::max(std::sqrt((plan > 0.0 ? plan * plan : 0.0) + vz2_), near_);
        return double(err) * scale_ > tol_ * d && (min_radius_ <= 0.0 || rad > min_radius_ * d);
    }

    void count_active(int c, int r) {
        if (!in_dem(c, r)) return;
        const std::size_t id = t_.index(c, r);
        std::uint32_t& e = map_[id];
        if (e & kActiveFlag) return;
        e |= kActiveFlag;
        ++active_count_;
    }

    std::uint32_t vertex(int c, int r) {
        const std::size_t id = t_.index(c, r);
        std::uint32_t& e = map_[id];
        if (e & kIndexMask) return (e & kIndexMask) - 1;
        if (out_.pos.size() >= kIndexMask) throw std::length_error("terrain lod: too many vertices");
        const std::uint32_t v = std::uint32_t(out_.pos.size());
        e |= v + 1;
        out_.pos.push_back(at(c, r));
        out_.normal.push_back(full_res_normal(c, r));
        if (nodes_) nodes_->push_back(std::uint32_t(id));
        return v;
    }

    static glm::vec3 face_normal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
        const glm::vec3 n = glm::cross(b - a, c - a);
        const float len = glm::length(n);
        return len > 0.0f ? n / len : glm::vec3(0, 0, 1);
    }

    // compute_normals(mesh_from_terrain(t)) at node (c, r): its up-to-6 full-resolution triangles
    // in the order that mesh lists them (cells row by row; {NW, SW, SE} before {NW, SE, NE}), made
    // of the node and its neighbours k at lattice_neighbours[k] (0 the node, 1 NW, 2 W, 3 N, 4 E,
    // 5 S, 6 SE), read from the lattice where the node lies on it.
    glm::vec3 full_res_normal(int c, int r) const {
        glm::vec3 q[7];
        bool v[7] = {};
        if (on_lattice(c, r)) {
            const LatticeNode n = lattice(c, r);
            for (int k = 0; k < 7; ++k) {
                v[k] = (int(n.valid) >> k & 1) != 0;
                q[k] = glm::vec3(0.0f, 0.0f, n.z[k]);
            }
            // x, y a row at a time: columns c-1, c of row r-1; c-1, c, c+1 of r; c, c+1 of r+1
            for (int dr = -1; dr <= 1; ++dr) {
                const int rr = r + dr;
                if (rr < 0 || rr >= rows_) continue;
                const int c0 = dr <= 0 ? std::max(c - 1, 0) : c, c1 = dr >= 0 ? std::min(c + 1, cols_ - 1) : c;
                glm::vec3 row[3];
                t_.derive_xy(t_.index(c0, rr), 1, std::size_t(c1 - c0 + 1), row);
                for (int k = 0; k < 7; ++k) {
                    const int cc = c + lattice_neighbours[k][0];
                    if (lattice_neighbours[k][1] != dr || cc < c0 || cc > c1) continue;
                    q[k].x = row[cc - c0].x, q[k].y = row[cc - c0].y;
                }
            }
            for (int k = 0; k < 7; ++k)
                if (v[k]) q[k] = t_.drawn(q[k]);
        } else {
            for (int k = 0; k < 7; ++k) {
                const int cc = c + lattice_neighbours[k][0], rr = r + lattice_neighbours[k][1];
                if (cc < 0 || rr < 0 || cc >= cols_ || rr >= rows_) continue;
                const std::size_t i = t_.index(cc, rr);
                if ((v[k] = reader_.has_data(i))) q[k] = reader_.at(i);
            }
        }
        glm::vec3 sum(0.0f);
        auto tri = [&](int a, int b, int d) {
            if (v[a] && v[b] && v[d]) sum += face_normal(q[a], q[b], q[d]);
        };
        if (c > 0 && r > 0) {  // node is the SE corner of cell (c-1, r-1)
            tri(1, 2, 0);
            tri(1, 0, 3);
        }
        if (c + 1 < cols_ && r > 0) tri(3, 0, 4);           // SW of cell (c, r-1)
        if (c > 0 && r + 1 < rows_) tri(2, 5, 0);           // NE of cell (c-1, r)
        if (c + 1 < cols_ && r + 1 < rows_) {               // NW of cell (c, r)
            tri(0, 5, 6);
            tri(0, 6, 4);
        }
        const float len = glm::length(sum);
        return len > 1e-12f ? sum / len : glm::vec3(0, 0, 1);
    }

    void emit(int ac, int ar, int bc, int br, int cc, int cr) {
        const glm::uvec3 tri(vertex(ac, ar), vertex(bc, br), vertex(cc, cr));
        out_.tri.push_back(tri);
        out_.face_normal.push_back(face_normal(out_.pos[tri.x], out_.pos[tri.y], out_.pos[tri.z]));
    }

    // Box of the DEM nodes of a triangle, culled against the frustum.
    int classify_triangle(const Item& it, float err) const {
        glm::dvec3 lo, hi;
        return classify_triangle(it, err, lo, hi);
    }
    // The same, with the box (lo, hi) that was classified.
    int classify_triangle(const Item& it, float err, glm::dvec3& lo, glm::dvec3& hi) const {
        if (err < kInf && ok(it.ac, it.ar) && ok(it.bc, it.br) && ok(it.cc, it.cr)) {
            // Every node inside lies within err (times e) of the triangle's plane, and (on an
            // affine grid) inside the plan triangle of its corners.
            const glm::dvec3 a(at(it.ac, it.ar)), b(at(it.bc, it.br)), c(at(it.cc, it.cr));
            lo = glm::min(glm::min(a, b), c), hi = glm::max(glm::max(a, b), c);
            const double dz = double(err) * ex_;
            lo.z -= dz, hi.z += dz;
        } else {
            // Forced: the grid box clipped to the DEM, all elevations.
            const int c0 = std::min({it.ac, it.bc, it.cc}), r0 = std::min({it.ar, it.br, it.cr});
            const int c1 = std::min({std::max({it.ac, it.bc, it.cc}), cols_ - 1});
            const int r1 = std::min({std::max({it.ar, it.br, it.cr}), rows_ - 1});
            lo = glm::dvec3(1e300), hi = glm::dvec3(-1e300);
            for (const int c : {c0, c1})
                for (const int r : {r0, r1}) {
                    const glm::dvec3 p(at(c, r));
                    lo = glm::min(lo, p), hi = glm::max(hi, p);
                }
            lo.z = zlo_, hi.z = zhi_;
        }
        // 1 % of the plan size: the bulge of a curvilinear (geographic) grid's interior nodes
        // beyond the corners' plan box, and rounding.
        const double m = 0.01 * std::max(hi.x - lo.x, hi.y - lo.y) + 1e-3;
        lo -= glm::dvec3(m, m, 1e-3), hi += glm::dvec3(m, m, 1e-3);
        return frustum_.classify(lo, hi);
    }

    bool visible(std::initializer_list<std::pair<int, int>> nodes) const {
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const auto& [c, r] : nodes) {
            const glm::dvec3 p(at(c, r));
            lo = glm::min(lo, p), hi = glm::max(hi, p);
        }
        const glm::dvec3 m(1e-3);
        return frustum_.classify(lo - m, hi + m) != 0;
    }

    // A half-cell. Kept as is when its diagonal is NW-SE (the full-resolution split) or the other
    // half of the cell is coarser; else both halves are selected and the cell is emitted once,
    // as the full-resolution mesh splits it.
    void leaf(const Item& it) {
        const bool nwse = (it.ac - it.bc) == (it.ar - it.br);
        const int oc = it.ac + it.bc - it.cc, orr = it.ar + it.br - it.cr;  // the other half's right angle
        if (nwse || !active(oc, orr)) {
            if (!(ok(it.ac, it.ar) && ok(it.bc, it.br) && ok(it.cc, it.cr))) return;
            if (!it.inside && !visible({{it.ac, it.ar}, {it.bc, it.br}, {it.cc, it.cr}}))
                return;
            emit(it.ac, it.ar, it.bc, it.br, it.cc, it.cr);
            return;
        }
        const int c = std::min(it.ac, it.bc), r = std::min(it.ar, it.br);  // NW corner, inside the DEM
        const std::size_t nw = t_.index(c, r);
        std::uint32_t& e = map_[nw];
        if (e & kCellFlag) return;
        e |= kCellFlag;
        const bool vnw = ok(c, r), vne = ok(c + 1, r), vsw = ok(c, r + 1), vse = ok(c + 1, r + 1);
        const bool first = vnw && vsw && vse, second = vnw && vse && vne;
        if (!first && !second) return;
        // The cell box: the other half may lie beyond this triangle's ancestors' boxes.
        if (!visible_cell(c, r, vnw, vne, vsw, vse)) return;
        if (first) emit(c, r, c, r + 1, c + 1, r + 1);
        if (second) emit(c, r, c + 1, r + 1, c + 1, r);
    }

    bool visible_cell(int c, int r, bool vnw, bool vne, bool vsw, bool vse) const {
        glm::dvec3 lo(1e300), hi(-1e300);
        auto add = [&](bool v, int cc, int rr) {
            if (!v) return;
            const glm::dvec3 p(at(cc, rr));
            lo = glm::min(lo, p), hi = glm::max(hi, p);
        };
        add(vnw, c, r), add(vne, c + 1, r), add(vsw, c, r + 1), add(vse, c + 1, r + 1);
        const glm::dvec3 m(1e-3);
        return frustum_.classify(lo - m, hi + m) != 0;
    }
};

}  // namespace

SurfaceMesh select_lod_mesh(const TerrainLod& lod, const GridNodes& t, double exaggeration, const Camera& camera,
                            const LodOptions& options, LodSelection* stats, std::vector<std::uint32_t>* vertex_nodes) {
    check_nodes(t);
    if (lod.cols != t.cols || lod.rows != t.rows || lod.error.size() != std::size_t(lod.cols) * std::size_t(lod.rows))
        throw std::invalid_argument("terrain lod: the lod was built for another grid");
    if (vertex_nodes) vertex_nodes->clear();
    if (t.cols < 2 || t.rows < 2) {
        if (stats) *stats = {};
        return {};
    }
    Selector s(lod, t, exaggeration, camera, options, vertex_nodes);
    return s.run(stats);
}

LodView lod_visible_window(const TerrainLod& lod, const GridNodes& t, double exaggeration, const Camera& camera,
                           int min_side) {
    check_nodes(t);
    if (lod.cols != t.cols || lod.rows != t.rows || lod.error.size() != std::size_t(lod.cols) * std::size_t(lod.rows))
        throw std::invalid_argument("terrain lod: the lod was built for another grid");
    if (t.cols < 2 || t.rows < 2) return {};
    return Selector(lod, t, exaggeration, camera, LodOptions{}, nullptr).window(min_side);
}

SurfaceMesh select_lod_mesh(const TerrainLod& lod, const Terrain& t, const Camera& camera, const LodOptions& options,
                            LodSelection* stats, std::vector<std::uint32_t>* vertex_nodes) {
    check_terrain(t);
    return select_lod_mesh(lod, grid_nodes(t), t.vertical_exaggeration, camera, options, stats, vertex_nodes);
}

SurfaceMesh select_lod_mesh(const TerrainLod& lod, const Terrain& t, const Camera& camera, float tolerance_px,
                            LodSelection* stats, std::vector<std::uint32_t>* vertex_nodes) {
    LodOptions o;
    o.tolerance_px = tolerance_px;
    return select_lod_mesh(lod, t, camera, o, stats, vertex_nodes);
}

}  // namespace penink
