// The reach of a stem from its network cells (stem_reach.hpp) holds the crease the whole build
// makes of it: every stem's built plan box lies in the plan box of its reach, on volcano at its
// automatic factor and at factor 1, on a DEM with nodata holes at factor 2 and on geographic
// jacksboro's curvilinear grid; the bound is not the whole DEM (its mean area over the DEM's:
// 0.27 on volcano at factor 5, where the margin of 20 DEM cells is a quarter of the DEM's width,
// 0.32 at factor 1, 0.33 with holes, 0.022 on jacksboro), and without the corridor's margin some
// traced creases leave their cells' boxes (77, 12 and 32 stems).
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "line_test_dems.hpp"

#include "drainage/draped_lines.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/stem_reach.hpp"

namespace penink {
namespace {

struct ReachCheck {
    std::size_t stems = 0, outside = 0;
    double area_share = 0.0;  // mean reach area over the DEM's plan box area
};

ReachCheck check_reach(const DrainageGrid& g, const DrainageResult& res, const DrainageDb& db, const FallLineOptions& o) {
    std::vector<std::uint32_t> cells;
    const DrapedLineSet walked = network_stems(g, res.dir, res.net, &cells);
    const PlanBoxes boxes(g);
    glm::vec2 all_lo, all_hi;
    boxes.plan_box(CellBox{0.0, 0.0, double(g.cols - 1), double(g.rows - 1)}, all_lo, all_hi);
    const double all = double(all_hi.x - all_lo.x) * double(all_hi.y - all_lo.y);
    ReachCheck c;
    EXPECT_EQ(walked.lines.size(), db.creases.lines.size());
    for (std::size_t s = 0; s < walked.lines.size() && s < db.creases.lines.size(); ++s) {
        const DrapedLine& l = walked.lines[s];
        glm::vec2 lo, hi;
        boxes.plan_box(stem_cell_reach(cells.data() + l.first, l.count, g, o), lo, hi);
        const DrapedLine& built = db.creases.lines[s];
        c.outside += !(built.lo.x >= lo.x && built.lo.y >= lo.y && built.hi.x <= hi.x && built.hi.y <= hi.y);
        c.area_share += double(hi.x - lo.x) * double(hi.y - lo.y) / all;
        ++c.stems;
    }
    c.area_share /= double(std::max<std::size_t>(1, c.stems));
    return c;
}

void expect_reach_holds(const Terrain& t, int factor, const std::string& what) {
    DrainageGrid g = resample_pn(t, factor);
    DrainageResult res;
    const DrainageDb db = drainage_db_from_grid(g, {}, &res);
    ASSERT_FALSE(db.creases.lines.empty()) << what;
    const ReachCheck c = check_reach(g, res, db, fall_line_options(g));
    EXPECT_EQ(c.outside, 0u) << what;
    EXPECT_LT(c.area_share, 0.4) << what;
    // no margin: the cells' own box (and the reflections'), which traced creases leave
    FallLineOptions none = fall_line_options(g);
    none.max_corridor = -1.0;
    EXPECT_GT(check_reach(g, res, db, none).outside, 0u) << what;
    ::testing::Test::RecordProperty(what + "_mean_area_share_ppm", int(1e6 * c.area_share));
}

TEST(StemReach, CreasesLieInTheirReach) {
    for (const LineTestDem& dem : line_test_dems()) expect_reach_holds(dem.terrain, dem.factor, dem.name);
}

}  // namespace
}  // namespace penink
