#include "input/utm_projection.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <utility>

#include <GeographicLib/UTMUPS.hpp>

#include "core/parallel_chunks.hpp"

namespace penink {

namespace {

// Lagrange weights of the cubic through the nodes at columns s[0..3], evaluated at column c.
std::array<double, 4> cubic_weights(const int* s, int c) {
    std::array<double, 4> l{1.0, 1.0, 1.0, 1.0};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (j != i) l[std::size_t(i)] *= double(c - s[j]) / double(s[i] - s[j]);
    return l;
}

// The weights for equally spaced nodes (-step, 0, step, 2 step) at k = 1 .. step - 1: the same for
// every interior interval of every row, so computed once.
std::vector<std::array<double, 4>> uniform_weights(int step) {
    std::vector<std::array<double, 4>> w(std::size_t(std::max(step, 1)));
    const int s[4] = {-step, 0, step, 2 * step};
    for (int k = 1; k < step; ++k) w[std::size_t(k)] = cubic_weights(s, k);
    return w;
}

// The sample indices of n nodes: every step-th and the last (n >= 2).
std::vector<int> samples(int n, int step) {
    std::vector<int> s;
    for (int i = 0; i < n - 1; i += step) s.push_back(i);
    s.push_back(n - 1);
    return s;
}

// Whether n nodes are interpolated between samples (else every node is exact).
bool interpolated(int n, int step) { return step > 1 && n >= 4 * step; }

// The four samples around interval i of s (shifted inwards at the ends): the first of them and
// whether they are equally spaced (their cubic weights then computed once: `weights`).
struct Window {
    std::size_t first;
    bool uniform;
    Window(const std::vector<int>& s, std::size_t i, int step)
        : first(std::min(i == 0 ? 0 : i - 1, s.size() - 4)),
          uniform(first + 1 == i && s[first + 3] - s[first] == 3 * step) {}
    // The cubic's weights at index x inside interval i (s[i] < x < s[i + 1]).
    std::array<double, 4> at(const std::vector<int>& s, std::size_t i, int x,
                             const std::vector<std::array<double, 4>>& weights) const {
        return uniform ? weights[std::size_t(x - s[i])] : cubic_weights(&s[first], x);
    }
};

}  // namespace

glm::dvec2 project_to_utm(glm::dvec2 lonlat, int zone, bool north) {
    int z = 0;
    bool n = true;
    double x = 0, y = 0, gamma = 0, k = 0;
    GeographicLib::UTMUPS::Forward(lonlat.y, lonlat.x, z, n, x, y, gamma, k, zone);
    if (n != north) GeographicLib::UTMUPS::Transfer(z, n, x, y, z, north, x, y, z);
    return {x, y};
}

UtmRowProjector::UtmRowProjector(int w, NodeLonLat lonlat, int zone, bool north, int step)
    : w_(w), zone_(zone), step_(step), step_shift_(step > 0 && std::has_single_bit(unsigned(step)) ? std::countr_zero(unsigned(step)) : -1),
      north_(north), lonlat_(std::move(lonlat)), weights_(uniform_weights(step)) {
    if (interpolated(w, step)) cols_ = samples(w, step);
}

UtmRowProjector::UtmRowProjector(int w, int h, NodeLonLat lonlat, int zone, bool north, int step)
    : UtmRowProjector(w, std::move(lonlat), zone, north, step) {
    if (cols_.empty() || !interpolated(h, step)) return;
    rows_ = samples(h, step);
    lattice_ = std::make_shared<Lattice>();
    lattice_->nodes.reset(new glm::dvec2[rows_.size() * cols_.size()]);  // not zeroed: written before read
    lattice_->done = std::make_unique<std::atomic<bool>[]>((rows_.size() + lattice_band - 1) / lattice_band);
}

glm::dvec2 UtmRowProjector::exact(int c, int r) const { return project_to_utm(lonlat_(c, r), zone_, north_); }

void UtmRowProjector::project_rows(std::size_t t0, std::size_t t1) const {
    Lattice& l = *lattice_;
    for (std::size_t b = t0 / lattice_band, last = (t1 - 1) / lattice_band; b <= last; ++b) {
        if (l.done[b].load(std::memory_order_acquire)) continue;
        const std::lock_guard<std::mutex> lock(l.mutex);
        if (l.done[b].load(std::memory_order_relaxed)) continue;  // projected meanwhile
        const std::size_t r0 = b * lattice_band, r1 = std::min(r0 + lattice_band, rows_.size()), n = cols_.size();
        parallel_chunks((r1 - r0) * n, 256, [&](std::size_t i0, std::size_t i1) {
            for (std::size_t i = i0; i < i1; ++i)
                l.nodes[r0 * n + i] = exact(cols_[i % n], rows_[r0 + i / n]);
        });
        l.projected += r1 - r0;
        l.done[b].store(true, std::memory_order_release);
    }
}

void UtmRowProjector::lattice(glm::dvec2* out) const {
    if (!lattice_) return;
    project_rows(0, rows_.size());
    std::copy_n(lattice_->nodes.get(), lattice_size(), out);
}

void UtmRowProjector::adopt_lattice(const std::function<void(glm::dvec2* nodes)>& fill) const {
    if (!lattice_) return;
    Lattice& l = *lattice_;
    const std::lock_guard<std::mutex> lock(l.mutex);
    fill(l.nodes.get());
    for (std::size_t b = 0; b < (rows_.size() + lattice_band - 1) / lattice_band; ++b)
        l.done[b].store(true, std::memory_order_release);
}

std::size_t UtmRowProjector::lattice_rows_projected() const {
    if (!lattice_) return 0;
    const std::lock_guard<std::mutex> lock(lattice_->mutex);
    return lattice_->projected;
}

UtmRowProjector::LatticeRow UtmRowProjector::lattice_row(int r) const {
    const std::size_t t = std::size_t(std::upper_bound(rows_.begin(), rows_.end(), r) - rows_.begin()) - 1;
    LatticeRow l;
    l.on = rows_[t] == r;
    if (l.on) {
        l.first = t;
        project_rows(t, t + 1);
        return l;
    }
    const Window win(rows_, t, step_);
    l.first = win.first, l.weights = win.at(rows_, t, r, weights_);
    project_rows(win.first, win.first + 4);
    return l;
}

glm::dvec2 UtmRowProjector::from_lattice(const LatticeRow& l, std::size_t k) const {
    const std::size_t n = cols_.size();
    const glm::dvec2* nodes = lattice_->nodes.get();
    if (l.on) return nodes[l.first * n + k];
    auto at = [&](std::size_t j) { return nodes[(l.first + j) * n + k]; };
    return utm_cubic(l.weights, at(0), at(1), at(2), at(3));
}

// Exact at the sample columns (their values from the lattice, the row's two ends always
// projected), cubic between: each node from the four samples around its interval, so a span
// computes only the samples its intervals use and its nodes are the whole row's, bit for bit.
void UtmRowProjector::row_span(int r, int c0, int c1, int every, glm::dvec2* out) const {
    if (c0 >= c1) return;
    const int last = c0 + (c1 - 1 - c0) / every * every;  // the span's last node
    if (cols_.empty()) {
        for (int c = c0; c <= last; c += every) out[(c - c0) / every] = exact(c, r);
        return;
    }
    const std::size_t n = cols_.size();
    // the sample intervals [cols_[i], cols_[i + 1]) holding c0 and the last node (the row's last
    // node: the last interval's end)
    const auto interval = [&](int c) {
        return std::min(std::size_t(std::upper_bound(cols_.begin(), cols_.end(), c) - cols_.begin()) - 1, n - 2);
    };
    const std::size_t i0 = interval(c0), i1 = interval(last);
    const std::size_t k0 = Window(cols_, i0, step_).first, k1 = Window(cols_, i1, step_).first + 4;
    thread_local std::vector<glm::dvec2> v;  // samples k0 .. k1 - 1
    v.resize(k1 - k0);
    const LatticeRow l = lattice_ ? lattice_row(r) : LatticeRow{};  // found (and projected) once a row
    for (std::size_t k = k0; k < k1; ++k) v[k - k0] = sample(l, k, r);
    for (std::size_t i = i0; i <= i1; ++i) {  // node_in's, its window found once an interval
        const Window win(cols_, i, step_);
        const glm::dvec2* s = v.data() + (win.first - k0);
        const int from = std::max(cols_[i], c0), first = c0 + (from - c0 + every - 1) / every * every;
        for (int c = first; c < std::min(cols_[i + 1], last + 1); c += every)
            out[(c - c0) / every] = c == cols_[i] ? v[i - k0] : utm_cubic(win.at(cols_, i, c, weights_), s[0], s[1], s[2], s[3]);
    }
    if (last == w_ - 1) out[(w_ - 1 - c0) / every] = v[n - 1 - k0];
}

glm::dvec2 UtmRowProjector::sample(const LatticeRow& l, std::size_t k, int r) const {
    return !lattice_ || k == 0 || k + 1 == cols_.size() ? exact(cols_[k], r) : from_lattice(l, k);
}

glm::dvec2 UtmRowProjector::node_in(std::size_t i, int c, const glm::dvec2* samples, std::size_t k0) const {
    if (c == cols_[i]) return samples[i - k0];
    const Window win(cols_, i, step_);
    const glm::dvec2* s = samples + (win.first - k0);
    return utm_cubic(win.at(cols_, i, c, weights_), s[0], s[1], s[2], s[3]);
}

void UtmRowProjector::row_samples(int r, glm::dvec2* out) const {
    if (!lattice_) return;
    const LatticeRow l = lattice_row(r);
    for (std::size_t k = 0; k < cols_.size(); ++k) out[k] = sample(l, k, r);
}

void UtmRowProjector::row(int r, glm::dvec2* out) const { row_span(r, 0, w_, out); }

UtmNodes project_grid_to_utm(int w, int h, const NodeLonLat& lonlat, int zone, bool north, int step) {
    UtmNodes out(std::size_t(std::max(w, 0)) * std::size_t(std::max(h, 0)));
    const UtmRowProjector rows(w, lonlat, zone, north, step);
    const std::size_t min_rows = std::max<std::size_t>(1, 20000 / std::size_t(std::max(w, 1)));
    parallel_chunks(std::size_t(std::max(h, 0)), min_rows, [&](std::size_t r0, std::size_t r1) {
        for (std::size_t r = r0; r < r1; ++r) rows.row(int(r), out.data() + r * std::size_t(w));
    });
    return out;
}

}  // namespace penink
