// Projection of a DEM's lon/lat node grid (degrees, w nodes per row, row-major) to UTM/UPS
// easting/northing (metres, GeographicLib UTMUPS, zone and hemisphere given). Along a row the
// map is a smooth function of the column, so every `step`-th node (and the last) is projected
// exactly and the nodes between are interpolated by the cubic through the four nearest exact
// nodes (Lagrange): on 16-node steps of 3" cells the result differs from projecting every node
// by < 1 µm (tests/input/utm_projection_test.cpp), at about a tenth of the cost. Rows are
// projected in parallel chunks; the result does not depend on the number of threads. Given the
// grid's height as well (a grid affine in both directions, as a DEM's is), the exact nodes of a
// row between every `step`-th row are themselves the cubic along the column through the four
// nearest such rows' (a lattice projected once), all but the row's two ends: again < 1 µm, at
// about a hundredth of the cost of projecting every node. The lattice's rows are projected when
// a row first needs them, a band of lattice_band of them at a time (in parallel chunks), so a
// view of part of a large DEM projects the part it reads (the values do not depend on the
// order: each is one exact projection). Copies share the lattice; thread-safe.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include <glm/vec2.hpp>

#include "core/big_allocator.hpp"

namespace penink {

// One point: (longitude, latitude) in degrees -> (easting, northing) in metres in UTM/UPS `zone`,
// transferred to hemisphere `north` when the point lies in the other one. Throws
// GeographicLib::GeographicErr when it cannot be projected in that zone.
glm::dvec2 project_to_utm(glm::dvec2 lonlat, int zone, bool north);

// lonlat(c, r) = (longitude, latitude) in degrees of node (c, r), linear in c along a row (and
// in r along a column, for the lattice); asked only at the exactly projected nodes.
using NodeLonLat = std::function<glm::dvec2(int c, int r)>;

// The cubic through a, b, c, d with weights k (Lagrange's: utm_projection.cpp).
inline glm::dvec2 utm_cubic(const std::array<double, 4>& k, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
    return k[0] * a + k[1] * b + k[2] * c + k[3] * d;
}

// One row of w nodes at a time, as project_grid_to_utm gives it (for callers that use each row
// once and need not hold the whole grid). Throws like project_grid_to_utm.
class UtmRowProjector {
public:
    UtmRowProjector(int w, NodeLonLat lonlat, int zone, bool north, int step = 16);
    // The lattice form (rows of an h-row grid affine in both directions; rows in parallel chunks).
    UtmRowProjector(int w, int h, NodeLonLat lonlat, int zone, bool north, int step = 16);
    void row(int r, glm::dvec2* out) const;  // out: w nodes
    // Nodes c0 .. c1 - 1 of row r (0 <= c0 <= c1 <= w), exactly as row() gives them; out: c1 - c0
    // nodes. Projects or interpolates only the samples around the span.
    void row_span(int r, int c0, int c1, glm::dvec2* out) const { row_span(r, c0, c1, 1, out); }
    // Every `every`-th node of the span from c0 (c0, c0 + every, ... < c1; every >= 1), each as
    // row() gives it; out: (c1 - c0 + every - 1) / every nodes. The nodes between are not computed.
    void row_span(int r, int c0, int c1, int every, glm::dvec2* out) const;
    // A row's samples held by a caller (the exact and lattice-interpolated nodes row_span
    // interpolates between; sample_count() of them a row, 0 where every node is exact): row_samples
    // writes row r's, node_from_samples(c, samples) gives node c of the row they are of, exactly
    // as row() gives it, without projecting or interpolating any sample again (a caller holding
    // every row's samples, 16 B every step-th node, has any node for a cubic of four of them).
    std::size_t sample_count() const { return lattice_ ? cols_.size() : 0; }
    void row_samples(int r, glm::dvec2* out) const;
    glm::dvec2 node_from_samples(int c, const glm::dvec2* samples) const {
        const std::size_t n = cols_.size();
        if (c >= w_ - 1) return samples[n - 1];
        // the interval holding c: the samples are every step_-th column, then the last
        const std::size_t i = std::min(std::size_t(step_shift_ >= 0 && c >= 0 ? c >> step_shift_ : c / step_), n - 2);
        const int k = c - cols_[i];
        // an interval whose four samples around are all every step_-th column (all but the first
        // and the last two): node_in's uniform window, its weights and its sum, without finding it
        if (k > 0 && i >= 1 && i + 2 < n - 1)
            return utm_cubic(weights_[std::size_t(k)], samples[i - 1], samples[i], samples[i + 1], samples[i + 2]);
        return node_in(i, c, samples, 0);
    }
    int zone() const { return zone_; }
    bool north() const { return north_; }
    // Lattice rows projected so far (0 without a lattice).
    std::size_t lattice_rows_projected() const;
    // The lattice's exact nodes, row-major (lattice rows x sample columns; 0 without a lattice):
    // all of them projected and copied into out (what a terrain cache stores), or written in place
    // by fill(nodes) (adopt_lattice: none projected again; they must be what lattice() gives, bit
    // for bit: a cache of the same grid; where fill throws, none is taken: rows project as before).
    std::size_t lattice_size() const { return lattice_ ? rows_.size() * cols_.size() : 0; }
    void lattice(glm::dvec2* out) const;
    void adopt_lattice(const std::function<void(glm::dvec2* nodes)>& fill) const;

    static constexpr std::size_t lattice_band = 8;

private:
    // rows_ x cols_ exact nodes, projected a band of rows at a time (done: each band's flag).
    struct Lattice {
        std::unique_ptr<glm::dvec2[]> nodes;
        std::unique_ptr<std::atomic<bool>[]> done;
        std::mutex mutex;
        std::size_t projected = 0;  // rows, under mutex
    };
    int w_, zone_, step_;
    int step_shift_;  // log2(step_) where step_ is a power of two (node_from_samples: a shift, not a division), else -1
    bool north_;
    NodeLonLat lonlat_;
    std::vector<std::array<double, 4>> weights_;  // cubic weights of equally spaced samples
    std::vector<int> cols_, rows_;                // sample columns; lattice rows (lattice form)
    std::shared_ptr<Lattice> lattice_;            // lattice form only

    // Where row r lies in the lattice: on lattice row `first`, or the cubic through the four from
    // `first` with `weights`; those rows projected (lattice_row).
    struct LatticeRow {
        std::size_t first = 0;
        std::array<double, 4> weights{};
        bool on = false;
    };
    glm::dvec2 exact(int c, int r) const;
    glm::dvec2 sample(const LatticeRow& l, std::size_t k, int r) const;  // sample k of row r (l: its lattice row)
    // Node c of sample interval i (cols_[i] <= c < cols_[i + 1]) from its samples: samples[k - k0]
    // is sample k (those from the four around the interval)
    glm::dvec2 node_in(std::size_t i, int c, const glm::dvec2* samples, std::size_t k0) const;
    LatticeRow lattice_row(int r) const;
    glm::dvec2 from_lattice(const LatticeRow& l, std::size_t k) const;  // sample column k of that row
    void project_rows(std::size_t t0, std::size_t t1) const;  // lattice rows [t0, t1) projected
};

using UtmNodes = std::vector<glm::dvec2, BigAllocator<glm::dvec2>>;

// (easting, northing) in metres of the w x h nodes, row-major. step 1 projects every node.
// Throws GeographicLib::GeographicErr when a node cannot be projected (the first and last node
// of every row are always projected exactly, so a row leaving the zone's range is caught).
UtmNodes project_grid_to_utm(int w, int h, const NodeLonLat& lonlat, int zone, bool north, int step = 16);

}  // namespace penink
