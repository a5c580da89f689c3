// Row-wise UTM projection (utm_projection.hpp) against projecting every node with GeographicLib:
// the cubic between exact nodes every 16 columns stays within 1 µm, also across a whole 6° zone
// (and beyond its edge), near the equator, at high latitude, in the other hemisphere and on a
// rotated grid (latitude changing along the row); rows too short to interpolate are exact. The
// lattice form (exact rows every 16 rows, cubic along the columns between) stays within 1 µm on
// affine grids too, its rows' ends exact.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include <GeographicLib/Constants.hpp>
#include <gtest/gtest.h>

#include "input/utm_projection.hpp"

namespace penink {
namespace {

// Rows of w nodes from (lon0, lat) stepping dlon east and dlat_per_col north along the row.
std::vector<glm::dvec2> grid(int w, const std::vector<double>& lats, double lon0, double dlon, double dlat_per_col) {
    std::vector<glm::dvec2> ll;
    for (double lat : lats)
        for (int c = 0; c < w; ++c) ll.push_back({lon0 + c * dlon, lat + c * dlat_per_col});
    return ll;
}

UtmNodes project(const std::vector<glm::dvec2>& ll, int w, int zone, bool north, int step = 16) {
    const int h = int(ll.size()) / w;
    return project_grid_to_utm(w, h, [&](int c, int r) { return ll[std::size_t(r) * w + c]; }, zone, north, step);
}

double max_error(const std::vector<glm::dvec2>& ll, int w, int zone, bool north, int step = 16) {
    const UtmNodes out = project(ll, w, zone, north, step);
    double worst = 0.0;
    for (std::size_t i = 0; i < ll.size(); ++i) {
        const glm::dvec2 e = project_to_utm(ll[i], zone, north);  // node by node
        worst = std::max({worst, std::abs(out[i].x - e.x), std::abs(out[i].y - e.y)});
    }
    return worst;
}

TEST(UtmProjection, ThreeArcSecondRowsAcrossAZoneStayWithinOneMicrometre) {
    // 3" cells (SRTM), 7300 columns: 84.6 W .. 78.5 W, through zone 17 (84 W .. 78 W) and past its
    // west edge; rows at the equator, mid and high latitude
    const double cell = 3.0 / 3600.0;
    const std::vector<glm::dvec2> ll = grid(7300, {0.0004, 36.7, 71.9}, -84.6, cell, 0.0);
    EXPECT_LT(max_error(ll, 7300, 17, true), 1e-6);
}

TEST(UtmProjection, SouthernRowsInANorthernZoneAndRotatedGrids) {
    const double cell = 1.0 / 3600.0;
    // a row south of the equator projected in the northern hemisphere's frame (Transfer)
    EXPECT_LT(max_error(grid(2001, {-0.2, -12.5}, 174.0, cell, 0.0), 2001, 60, true), 1e-6);
    // latitude changing along the row (a rotated geotransform)
    EXPECT_LT(max_error(grid(3000, {45.0}, 6.0, cell, 0.3 * cell), 3000, 32, true), 1e-6);
    // an odd last interval: 1000 = 62 * 16 + 8 columns
    EXPECT_LT(max_error(grid(1000, {10.0}, 8.0, 5 * cell, 0.0), 1000, 32, true), 1e-6);
}

TEST(UtmProjection, ShortRowsAndStepOneAreExact) {
    const double cell = 3.0 / 3600.0;
    EXPECT_EQ(max_error(grid(63, {36.7, 36.6}, -84.4, cell, 0.0), 63, 16, true), 0.0);  // < 4 steps
    EXPECT_EQ(max_error(grid(500, {36.7}, -84.4, cell, 0.0), 500, 16, true, 1), 0.0);
}

TEST(UtmProjection, ANodeOutsideTheZonesRangeThrows) {
    // jacksboro's longitudes forced into zone 40 (57 E): GeographicLib refuses, as it does node by node
    const std::vector<glm::dvec2> ll = grid(400, {36.7}, -84.4, 3.0 / 3600.0, 0.0);
    EXPECT_THROW(project(ll, 400, 40, true), GeographicLib::GeographicErr);
}

// Largest difference between the lattice form's rows of an affine w x h grid (node (c, r) at
// lon0 + c * dlon + r * dlon_r, lat0 - r * dlat + c * dlat_c) and projecting every node; `ends`
// set when the rows' two ends were exact.
double max_lattice_error(int w, int h, double lon0, double lat0, double dlon, double dlat, double dlon_r, double dlat_c,
                         int zone, bool& ends) {
    const NodeLonLat ll = [=](int c, int r) { return glm::dvec2(lon0 + c * dlon + r * dlon_r, lat0 - r * dlat + c * dlat_c); };
    const UtmRowProjector rows(w, h, ll, zone, true);
    std::vector<glm::dvec2> out(std::size_t(w), glm::dvec2(0.0));
    double worst = 0.0;
    ends = true;
    for (int r = 0; r < h; ++r) {
        rows.row(r, out.data());
        for (int c = 0; c < w; ++c) {
            const glm::dvec2 e = project_to_utm(ll(c, r), zone, true);
            worst = std::max({worst, std::abs(out[std::size_t(c)].x - e.x), std::abs(out[std::size_t(c)].y - e.y)});
            if ((c == 0 || c == w - 1) && out[std::size_t(c)] != e) ends = false;
        }
    }
    return worst;
}

TEST(UtmProjection, LatticeRowsOfAffineGridsStayWithinOneMicrometre) {
    const double cell = 3.0 / 3600.0;
    bool ends = false;
    // 3" cells, 1.5 degrees square over zone 17's west edge at mid latitude; 601 rows: an odd last
    // lattice interval (600 = 37 * 16 + 8)
    EXPECT_LT(max_lattice_error(1800, 601, -84.6, 37.5, cell, cell, 0.0, 0.0, 17, ends), 1e-6);
    EXPECT_TRUE(ends);
    // high latitude, and a rotated grid (both coordinates changing along rows and columns)
    EXPECT_LT(max_lattice_error(700, 500, -81.0, 71.0, cell, cell, 0.0, 0.0, 17, ends), 1e-6);
    EXPECT_LT(max_lattice_error(700, 500, 6.0, 46.0, cell, cell, 0.2 * cell, 0.3 * cell, 32, ends), 1e-6);
    EXPECT_TRUE(ends);
}

TEST(UtmProjection, LatticeFormOfAShortGridIsTheRowForm) {
    const double cell = 1.0 / 3600.0;  // 40 rows < 4 lattice steps: every row's samples exact
    const NodeLonLat ll = [=](int c, int r) { return glm::dvec2(-84.4 + c * cell, 36.7 - r * cell); };
    const UtmRowProjector lattice(500, 40, ll, 16, true), rows(500, ll, 16, true);
    std::vector<glm::dvec2> a(500), b(500);
    for (int r = 0; r < 40; ++r) {
        lattice.row(r, a.data()), rows.row(r, b.data());
        ASSERT_EQ(a, b) << r;
    }
}

// Any span of a row is that row's nodes bit for bit (a cache recomputes a block of nodes so), and
// every k-th node of a span too (a sampled grid's): spans starting and ending inside, on and next
// to sample columns, at the row's ends, of one node, strides of 1 to past a sample interval, in
// the lattice form, the row form and a row too short to interpolate (every node exact).
TEST(UtmProjection, SpansOfARowAreTheRowBitForBit) {
    const double cell = 1.0 / 3600.0;
    const NodeLonLat ll = [=](int c, int r) { return glm::dvec2(-84.4 + c * cell + r * 0.1 * cell, 36.7 - r * cell); };
    for (const int w : {403, 50}) {
        const UtmRowProjector lattice(w, 344, ll, 16, true), rows(w, ll, 16, true);
        for (const UtmRowProjector* p : {&lattice, &rows}) {
            SCOPED_TRACE(testing::Message() << w << (p == &lattice ? " lattice" : " rows"));
            std::vector<glm::dvec2> whole(static_cast<std::size_t>(w)), span(static_cast<std::size_t>(w) + 1);
            for (const int r : {0, 1, 17, 200, 343}) {
                p->row(r, whole.data());
                for (const int c0 : {0, 1, 15, 16, 17, 100, w - 20, w - 2, w - 1})
                    for (const int n : {1, 2, 16, 33, 256, w}) {
                        const int c1 = std::min(w, c0 + n);
                        for (const int every : {1, 2, 3, 4, 16, 37}) {
                            std::fill(span.begin(), span.end(), glm::dvec2(-1.0));
                            p->row_span(r, c0, c1, every, span.data());
                            for (int c = c0; c < c1; c += every) {
                                const glm::dvec2 a = span[std::size_t((c - c0) / every)], b = whole[std::size_t(c)];
                                ASSERT_TRUE(std::memcmp(&a, &b, sizeof a) == 0)
                                    << r << " " << c0 << " " << c1 << " " << every << " " << c;
                            }
                            if (c0 < c1) {
                                EXPECT_EQ(span[std::size_t((c1 - c0 + every - 1) / every)], glm::dvec2(-1.0))
                                    << "past the nodes asked for";
                            }
                        }
                    }
            }
        }
    }
}

// A row's samples held (row_samples) give every node of the row as row() does, bit for bit, on
// rows of the lattice, rows between, the first and last rows, and row lengths one past a sample
// column and on one.
TEST(UtmProjection, NodesFromARowsSamplesAreTheRowBitForBit) {
    const double cell = 1.0 / 3600.0;
    const NodeLonLat ll = [=](int c, int r) { return glm::dvec2(-84.4 + c * cell + r * 0.1 * cell, 36.7 - r * cell); };
    for (const int w : {403, 401, 64, 65}) {
        const UtmRowProjector p(w, 344, ll, 16, true);
        ASSERT_GE(p.sample_count(), 5u) << w;
        std::vector<glm::dvec2> whole(static_cast<std::size_t>(w)), samples(p.sample_count());
        for (const int r : {0, 1, 15, 16, 17, 200, 342, 343}) {
            p.row(r, whole.data());
            p.row_samples(r, samples.data());
            for (int c = 0; c < w; ++c) {
                const glm::dvec2 a = p.node_from_samples(c, samples.data()), b = whole[std::size_t(c)];
                ASSERT_TRUE(std::memcmp(&a, &b, sizeof a) == 0) << w << " " << r << " " << c;
            }
        }
    }
    const UtmRowProjector rows_only(403, ll, 16, true);  // no lattice: no samples to hold
    EXPECT_EQ(rows_only.sample_count(), 0u);
}

// The lattice's rows are projected as rows need them, a band at a time: rows near the top of a
// 3000-row grid project the few bands around them, not the 188 lattice rows; the nodes are the
// same bits whatever order the rows are asked in, and from several threads at once.
TEST(UtmProjection, LatticeRowsAreProjectedWhereRowsNeedThem) {
    const double cell = 1.0 / 3600.0;
    const NodeLonLat ll = [=](int c, int r) { return glm::dvec2(-84.4 + c * cell + r * 0.1 * cell, 36.7 - r * cell); };
    const int w = 400, h = 3000;
    const UtmRowProjector ahead(w, h, ll, 16, true);
    std::vector<glm::dvec2> row(static_cast<std::size_t>(w));
    ahead.row(40, row.data());
    // lattice rows 1..4 hold row 40's window: the first band of 8
    EXPECT_EQ(ahead.lattice_rows_projected(), UtmRowProjector::lattice_band);
    const std::vector<int> asked = {2999, 40, 1500, 0, 17, 2990, 777};
    std::vector<std::vector<glm::dvec2>> forward, backward(asked.size());
    for (const int r : asked) {
        ahead.row(r, row.data());
        forward.push_back(row);
    }
    EXPECT_LT(ahead.lattice_rows_projected(), 188u / 2);
    const UtmRowProjector behind(w, h, ll, 16, true);
    std::vector<std::thread> threads;
    for (std::size_t i = asked.size(); i-- > 0;)
        threads.emplace_back([&, i] {
            backward[i].resize(static_cast<std::size_t>(w));
            behind.row(asked[i], backward[i].data());
        });
    for (std::thread& t : threads) t.join();
    for (std::size_t i = 0; i < asked.size(); ++i)
        ASSERT_TRUE(std::memcmp(forward[i].data(), backward[i].data(), sizeof(glm::dvec2) * std::size_t(w)) == 0) << asked[i];
}

// The lattice handed on (what a terrain cache stores): all of it projected and copied out, then
// taken by another projector of the same grid, which projects none of it and gives every row
// the same bits.
TEST(UtmProjection, AnAdoptedLatticeGivesTheSameRowsAndProjectsNothing) {
    const double cell = 1.0 / 3600.0;
    const NodeLonLat ll = [=](int c, int r) { return glm::dvec2(-84.4 + c * cell + r * 0.1 * cell, 36.7 - r * cell); };
    const int w = 400, h = 300;
    const UtmRowProjector made(w, h, ll, 16, true);
    ASSERT_EQ(made.lattice_size(), std::size_t(26 * 20));  // samples 0, 16, ..., and the last node
    std::vector<glm::dvec2> lattice(made.lattice_size());
    made.lattice(lattice.data());
    EXPECT_EQ(made.lattice_rows_projected(), 20u);
    const UtmRowProjector taken(w, h, ll, 16, true);
    taken.adopt_lattice([&](glm::dvec2* nodes) { std::copy(lattice.begin(), lattice.end(), nodes); });
    std::vector<glm::dvec2> a(static_cast<std::size_t>(w)), b(a.size());
    for (int r = 0; r < h; r += 7) {
        made.row(r, a.data()), taken.row(r, b.data());
        ASSERT_TRUE(std::memcmp(a.data(), b.data(), sizeof(glm::dvec2) * a.size()) == 0) << r;
    }
    EXPECT_EQ(taken.lattice_rows_projected(), 0u);
    EXPECT_EQ(UtmRowProjector(w, ll, 16, true).lattice_size(), 0u);  // the row form: no lattice
}

}  // namespace
}  // namespace penink
