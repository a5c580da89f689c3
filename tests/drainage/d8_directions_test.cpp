// Hand-computed D8 codes, point classes, accumulation, basins and Strahler order on small grids.
#include <gtest/gtest.h>

#include "drainage/d8.hpp"
#include "drainage/drainage_grid.hpp"
#include "drainage/flow_network.hpp"

namespace penink {
namespace {

GridShape shape_of(const DrainageGrid& g) { return {g.cols, g.rows, g.valid.data()}; }

// Point classes (Mower, "Concurrent Drainage Network Rendering"): pit (no downhill), ridge (no
// neighbour drains into it), channel (one), junction (more than one); none for invalid cells.
enum class PointClass : std::uint8_t { pit, ridge, channel, junction, none };

std::vector<PointClass> classify_points(const std::vector<std::uint8_t>& dir, const GridShape& g) {
    const CellBytes in = inflow_counts(dir, g);
    std::vector<PointClass> cls(g.size(), PointClass::none);
    for (std::size_t i = 0; i < g.size(); ++i)
        if (g.valid[i])
            cls[i] = dir[i] == 0 ? PointClass::pit
                     : in[i] == 0 ? PointClass::ridge
                     : in[i] == 1 ? PointClass::channel
                                  : PointClass::junction;
    return cls;
}

// 3x3 slope falling to the south-east corner.
DrainageGrid slope3() { return make_regular_grid(3, 3, 1.0, {9, 8, 7, 6, 5, 4, 3, 2, 1}); }

// 5x3 saddle-free ridge along the middle column draining to outlets on the west and east edges.
DrainageGrid ridge5x3() {
    return make_regular_grid(5, 3, 1.0, {3, 4, 5, 4, 3, 2, 3, 4, 3, 2, 3, 4, 5, 4, 3});
}

TEST(D8, SlopeCodes) {
    DrainageGrid g = slope3();
    const auto dir = d8_directions(g.z, shape_of(g), g.dx, g.dy);
    EXPECT_EQ(dir, (std::vector<std::uint8_t>{4, 4, 4, 4, 4, 4, 1, 1, 0}));
}

TEST(D8, RidgeCodesTieBreakInCodeOrder) {
    DrainageGrid g = ridge5x3();
    const auto dir = d8_directions(g.z, shape_of(g), g.dx, g.dy);
    EXPECT_EQ(dir, (std::vector<std::uint8_t>{4, 8, 2, 2, 4, 0, 16, 1, 1, 0, 64, 32, 32, 128, 64}));
}

TEST(D8, DistanceWeightsUseCellSize) {
    // dx = 1, dy = 10: a 1 m drop east beats a 5 m drop south (0.5 per metre).
    DrainageGrid g = make_regular_grid(2, 2, 1.0, {10, 9, 5, 9.5f});
    g.dy = 10.0;
    const auto dir = d8_directions(g.z, shape_of(g), g.dx, g.dy);
    EXPECT_EQ(dir[0], 1);
}

TEST(D8, PointClasses) {
    DrainageGrid g = slope3();
    const auto dir = d8_directions(g.z, shape_of(g), g.dx, g.dy);
    using P = PointClass;
    EXPECT_EQ(classify_points(dir, shape_of(g)),
              (std::vector<P>{P::ridge, P::ridge, P::ridge, P::channel, P::channel, P::channel,
                              P::channel, P::junction, P::pit}));
}

TEST(Flow, SlopeAccumulationAndOrder) {
    DrainageGrid g = slope3();
    const auto dir = d8_directions(g.z, shape_of(g), g.dx, g.dy);
    FlowNetwork net;
    accumulate_flow(dir, shape_of(g), net);
    EXPECT_EQ(net.acc, (CellWords{1, 1, 1, 2, 2, 2, 3, 6, 9}));
    EXPECT_EQ(net.order, (CellBytes{1, 1, 1, 1, 1, 1, 1, 2, 2}));
    EXPECT_EQ(net.indeg, inflow_counts(dir, shape_of(g)));  // kept whole for the branches
    EXPECT_EQ(net.indeg, (CellBytes{0, 0, 0, 1, 1, 1, 1, 2, 2}));
}

TEST(Flow, RidgeBasinsAndNormalisedFlow) {
    DrainageGrid g = ridge5x3();
    const auto dir = d8_directions(g.z, shape_of(g), g.dx, g.dy);
    FlowNetwork net;
    accumulate_flow(dir, shape_of(g), net);
    label_basins(dir, shape_of(g), net);
    EXPECT_EQ(net.outlet, (std::vector<std::uint32_t>{5, 9}));
    EXPECT_EQ(net.basin, (CellWords{1, 1, 2, 2, 2, 1, 1, 2, 2, 2, 1, 1, 1, 2, 2}));
    EXPECT_EQ(net.acc, (CellWords{1, 1, 1, 1, 1, 7, 2, 1, 3, 8, 1, 1, 1, 1, 1}));
    EXPECT_EQ(net.acc[5] + net.acc[9], 15u);  // total flow at outlets = number of points
    EXPECT_FLOAT_EQ(normalised_flow(net, 5), 1.0f);
    EXPECT_FLOAT_EQ(normalised_flow(net, 9), 1.0f);
    EXPECT_FLOAT_EQ(normalised_flow(net, 6), 2.0f / 7.0f);
}

// Hand-made tree: four sources into J1, two into J2, J1 + two sources into a trunk that meets J2
// at the outlet: Strahler 2 on J1, J2 and the trunk, 3 at the outlet.
std::vector<std::uint8_t> tree_dirs() {
    return {2, 4, 8, 2, 4,  //
            1, 4, 8, 2, 4,  //
            1, 1, 1, 1, 0};
}

TEST(Flow, StrahlerOnTree) {
    DrainageGrid g = make_regular_grid(5, 3, 1.0, std::vector<float>(15, 0.0f));
    FlowNetwork net;
    accumulate_flow(tree_dirs(), shape_of(g), net);
    EXPECT_EQ(net.order, (CellBytes{1, 1, 1, 1, 1, 1, 2, 1, 1, 2, 1, 2, 2, 2, 3}));
    EXPECT_EQ(net.acc[14], 15u);
    EXPECT_EQ(net.acc[6], 5u);
    EXPECT_EQ(net.acc[11], 8u);
}

TEST(Flow, CycleIsAnInternalError) {
    DrainageGrid g = make_regular_grid(2, 1, 1.0, {0, 0});
    const std::vector<std::uint8_t> dir{1, 16};  // east <-> west
    FlowNetwork net;
    try {
        accumulate_flow(dir, shape_of(g), net);
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "penink: drainage: flow directions contain a cycle");
    }
}

// Basin labelling runs beside the accumulation: on a cycle it must stop and say so too.
TEST(Flow, CycleStopsBasinLabelling) {
    DrainageGrid g = make_regular_grid(3, 1, 1.0, {0, 0, 0});
    const std::vector<std::uint8_t> dir{0, 1, 16};  // outlet, then cells 1 and 2 point at each other
    FlowNetwork net;
    try {
        label_basins(dir, shape_of(g), net);
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "penink: drainage: flow directions contain a cycle");
    }
}

TEST(D8, NodataNeighboursMakeBoundaryCells) {
    std::vector<std::uint8_t> valid(49, 1);
    valid[3 * 7 + 3] = 0;
    DrainageGrid g = make_regular_grid(7, 7, 1.0, std::vector<float>(49, 1.0f), valid);
    EXPECT_TRUE(is_boundary_cell(shape_of(g), 2, 2));   // diagonal to the hole
    EXPECT_TRUE(is_boundary_cell(shape_of(g), 3, 4));   // below the hole
    EXPECT_FALSE(is_boundary_cell(shape_of(g), 1, 1));  // two cells away
    EXPECT_TRUE(is_boundary_cell(shape_of(g), 0, 3));   // grid border
}

}  // namespace
}  // namespace penink
