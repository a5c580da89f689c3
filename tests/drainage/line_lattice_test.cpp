// The lattice of crease vertices (src/drainage/line_lattice.hpp): its steps for a cell, how far a
// vertex moves when snapped (x, y at most half a plan step, z half a z step, the normal under 0.56
// degrees, the flow 2^-7 of itself), a snapped vertex's code giving it back bit for bit and
// snapping it again leaving it, and the vertices without a code left as they are.
#include "drainage/line_lattice.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace penink {
namespace {

bool same_bits(const DrapedVertex& a, const DrapedVertex& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(LineLattice, StepsAreAPowerOfTwoUnderASixtyFourthOfTheCell) {
    for (double cell : {0.3, 1.0, 9.26, 14.9, 30.0, 64.0, 90.0, 1000.0}) {
        const LineLattice l = line_lattice(cell);
        const double plan = std::ldexp(1.0, l.plan_exp), z = std::ldexp(1.0, l.z_exp);
        EXPECT_LE(plan, cell / 64.0) << cell;
        EXPECT_GT(plan, cell / 128.0) << cell;
        EXPECT_EQ(z, plan / 2.0) << cell;
    }
    EXPECT_EQ(line_lattice(64.0).plan_exp, 0);
    EXPECT_EQ(line_lattice(14.9).plan_exp, -3);  // 14.9 / 64 = 0.233: 1/8 m
}

TEST(LineLattice, SnappingMovesAVertexByLessThanItsStepsAndIsKept) {
    const LineLattice l = line_lattice(14.9);
    const double plan = std::ldexp(1.0, l.plan_exp), zs = std::ldexp(1.0, l.z_exp);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-60000.0f, 60000.0f), h(-400.0f, 4800.0f), c(-1.0f, 1.0f),
        f(-12.0f, 0.0f);
    double worst_angle = 0.0, worst_flow = 0.0;
    for (int i = 0; i < 200000; ++i) {
        // normals up to vertical cliffs (nz near 0), flows from 1e-12 to 1
        float nx = c(rng), ny = c(rng) * std::sqrt(1.0f - nx * nx);
        const float nz = std::sqrt(std::max(0.0f, 1.0f - nx * nx - ny * ny));
        const DrapedVertex v{pos(rng), pos(rng), h(rng), nx, ny, nz, std::pow(10.0f, f(rng))};
        const DrapedVertex s = snapped_vertex(v, l);
        ASSERT_LE(std::fabs(double(s.x) - v.x), 0.5 * plan);
        ASSERT_LE(std::fabs(double(s.y) - v.y), 0.5 * plan);
        ASSERT_LE(std::fabs(double(s.z) - v.z), 0.5 * zs);
        const double dot = double(s.nx) * v.nx + double(s.ny) * v.ny + double(s.nz) * v.nz;
        const double len = std::sqrt(double(s.nx) * s.nx + double(s.ny) * s.ny + double(s.nz) * s.nz);
        ASSERT_NEAR(len, 1.0, 1e-6);
        worst_angle = std::max(worst_angle, std::acos(std::min(1.0, dot / len)) * 180.0 / M_PI);
        worst_flow = std::max(worst_flow, std::fabs(double(s.flow) / v.flow - 1.0));
        VertexCode code;
        ASSERT_TRUE(vertex_code(s, l, code)) << i;
        ASSERT_TRUE(same_bits(lattice_vertex(code, l), s)) << i;
        ASSERT_TRUE(same_bits(snapped_vertex(s, l), s)) << i;
    }
    // the normal's step: 2 / 254 in a and b, half of it at most in u and v on the octahedron's
    // face (|du| + |dv| = max(|da|, |db|) <= 1 / 254), as much in its z: at most sqrt(2) / 254 off
    // on the face, sqrt(3) times that in angle where the face is nearest the centre (0.553 degrees)
    EXPECT_LT(worst_angle, std::sqrt(6.0) / 254.0 * 180.0 / M_PI);
    EXPECT_GT(worst_angle, 0.4);  // a real rounding, near its bound
    EXPECT_LE(worst_flow, std::ldexp(1.0, -flow_bits - 1));
    ::testing::Test::RecordProperty("worst_normal_degrees", std::to_string(worst_angle));
}

TEST(LineLattice, ZeroNormalsAndVerticesWithoutACode) {
    const LineLattice l = line_lattice(30.0);
    // off the surface: a zero normal stays zero (a signed one too), its other fields snapped
    const DrapedVertex off{10.01f, -3.3f, 250.07f, -0.0f, 0.0f, 0.0f, 0.25f};
    const DrapedVertex s = snapped_vertex(off, l);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(s.nx), 0u);
    EXPECT_EQ(s.ny, 0.0f);
    EXPECT_EQ(s.nz, 0.0f);
    EXPECT_EQ(s.flow, 0.25f);  // a power of two is on the flow's lattice
    VertexCode code;
    EXPECT_TRUE(vertex_code(s, l, code));
    EXPECT_FALSE(vertex_code(off, l, code));  // not snapped
    // a coordinate past 2^31 steps, a NaN, an infinity: no code, left as they are
    for (const DrapedVertex v : {DrapedVertex{3e9f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.5f},
                                 DrapedVertex{1.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 0.0f, 1.0f, 0.5f},
                                 DrapedVertex{1.0f, 1.0f, std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 1.0f, 0.5f}}) {
        EXPECT_TRUE(same_bits(snapped_vertex(v, l), v));
        EXPECT_FALSE(vertex_code(v, l, code));
    }
    // in a box: rounded back inside where rounding took x or y out (steps of 1/4 m at 30 m cells)
    const DrapedVertex edge{10.13f, -3.38f, 250.0f, 0.0f, 0.0f, 1.0f, 0.25f};
    const DrapedVertex in = snapped_vertex(edge, l, glm::vec2(9.0f, -3.38f), glm::vec2(10.13f, 0.0f));
    EXPECT_EQ(in.x, 10.0f);   // 10.25 nearest, beyond 10.13
    EXPECT_EQ(in.y, -3.25f);  // -3.5 nearest, below -3.38
    EXPECT_EQ(snapped_vertex(edge, l).x, 10.25f);
    EXPECT_EQ(snapped_vertex(edge, l).y, -3.5f);
    EXPECT_TRUE(vertex_code(in, l, code));
    // a NaN flow is kept (its payload's high bits): the vertex has a code
    const DrapedVertex nan{1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 1.0f, std::numeric_limits<float>::quiet_NaN()};
    EXPECT_TRUE(same_bits(snapped_vertex(nan, l), nan));
    EXPECT_TRUE(vertex_code(nan, l, code));
}

}  // namespace
}  // namespace penink
