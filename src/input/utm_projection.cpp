#include "input/utm_projection.hpp"

#include <algorithm>
#include <array>

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

// One row of w nodes: exact at the sample columns (multiples of step, and w - 1), cubic between
// (weights computed once where the four samples are equally spaced, per node at the row's ends).
void project_row(glm::dvec2* row, int w, int r, const NodeLonLat& lonlat, int zone, bool north, int step,
                 const std::vector<std::array<double, 4>>& weights) {
    if (step <= 1 || w < 4 * step) {
        for (int c = 0; c < w; ++c) row[c] = project_to_utm(lonlat(c, r), zone, north);
        return;
    }
    std::vector<int> s;
    for (int c = 0; c < w - 1; c += step) s.push_back(c);
    s.push_back(w - 1);
    std::vector<glm::dvec2> v(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) v[i] = project_to_utm(lonlat(s[i], r), zone, north);
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
        // the window of four samples around interval i, shifted inwards at the row's ends
        const std::size_t first = std::min(i == 0 ? 0 : i - 1, s.size() - 4);
        const bool uniform = first + 1 == i && s[first + 3] - s[first] == 3 * step;
        row[s[i]] = v[i];
        for (int c = s[i] + 1; c < s[i + 1]; ++c) {
            const std::array<double, 4> k = uniform ? weights[std::size_t(c - s[i])] : cubic_weights(&s[first], c);
            row[c] = k[0] * v[first] + k[1] * v[first + 1] + k[2] * v[first + 2] + k[3] * v[first + 3];
        }
    }
    row[w - 1] = v.back();
}

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
    : w_(w), zone_(zone), step_(step), north_(north), lonlat_(std::move(lonlat)), weights_(uniform_weights(step)) {}

void UtmRowProjector::row(int r, glm::dvec2* out) const {
    project_row(out, w_, r, lonlat_, zone_, north_, step_, weights_);
}

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
