#include "lines/sketchy.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "lines/distance_thinning.hpp"
#include "lines/random_bits.hpp"

namespace penink {
namespace {

Stroke polyline() {
    Stroke s;
    for (int i = 0; i <= 20; ++i) s.points.emplace_back(5.0f * i, 0.25f * i * i), s.depth.push_back(float(i));
    return s;
}

TEST(Sketchy, SplitMixReferenceValue) {
    // First output of splitmix64 seeded with 0 (reference implementation, Vigna).
    EXPECT_EQ(splitmix64(0), 0xE220A8397B1DCDAFull);
}

TEST(Sketchy, SameSeedIdenticalDifferentSeedDifferent) {
    SketchParams p;
    p.amount = 2.0f;
    Stroke s = polyline();
    Stroke a = sketch_stroke(s, p, 7, 42), b = sketch_stroke(s, p, 7, 42);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.depth, s.depth);
    EXPECT_NE(sketch_stroke(s, p, 8, 42).points, a.points);
    EXPECT_NE(sketch_stroke(s, p, 7, 43).points, a.points);
    EXPECT_NE(sketch_stroke(s, p, 7, 42, 1).points, a.points);
}

TEST(Sketchy, AmountBoundRespectedAndInteriorSmooth) {
    SketchParams p;
    p.amount = 1.5f;
    Stroke s = polyline();
    float max_end = 0.0f;
    for (std::uint64_t id = 0; id < 500; ++id) {
        Stroke o = sketch_stroke(s, p, 99, id);
        for (std::size_t i = 0; i < s.points.size(); ++i) EXPECT_LE(glm::length(o.points[i] - s.points[i]), 1.5f + 1e-5f);
        max_end = std::max(max_end, glm::length(o.points[0] - s.points[0]));
    }
    EXPECT_GT(max_end, 1.3f);  // the bound is actually used
}

TEST(Sketchy, OvershootExtendsStraightStrokeAndRepeatMakesCopies) {
    SketchParams p;
    p.amount = 0.0f;
    p.overshoot = 2.0f;
    p.repeat = 2;
    Stroke s{{{0, 0}, {10, 0}, {20, 0}}, {1, 1, 1}, 1.0f, "crease"};
    auto copies = sketch_copies(s, p, 1, 2);
    ASSERT_EQ(copies.size(), 3u);
    EXPECT_EQ(copies[0].points, (std::vector<glm::vec2>{{-2, 0}, {10, 0}, {22, 0}}));
    p.amount = 1.0f;
    copies = sketch_copies(s, p, 1, 2);
    EXPECT_NE(copies[1].points, copies[2].points);
}

TEST(Sketchy, ClosedStrokeStaysClosed) {
    SketchParams p;
    p.amount = 3.0f;
    Stroke s{{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, {0, 0, 0, 0, 0}, 1.0f, "outline"};
    Stroke o = sketch_stroke(s, p, 5, stroke_geometry_id(s));
    EXPECT_EQ(o.points.front(), o.points.back());
    EXPECT_NE(o.points.front(), s.points.front());
}

TEST(Sketchy, ThreeDOffsetsLieInTheTangentPlane) {
    std::vector<glm::vec3> pts, normals;
    for (int i = 0; i < 10; ++i) {
        float a = 0.3f * i;
        pts.emplace_back(std::cos(a), std::sin(a), 0.1f * i);
        normals.push_back(glm::normalize(glm::vec3(std::cos(a), std::sin(a), 0.3f + 0.1f * i)));
    }
    normals[9] = {0, 0, -1};  // the basis must handle a normal pointing down
    for (std::uint64_t id = 0; id < 50; ++id) {
        auto out = sketch_polyline_3d(pts, normals, 0.05f, 11, id);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            glm::vec3 d = out[i] - pts[i];
            EXPECT_NEAR(glm::dot(d, normals[i]), 0.0f, 1e-5f);
            EXPECT_LE(glm::length(d), 0.05f + 1e-6f);
        }
        EXPECT_EQ(out, sketch_polyline_3d(pts, normals, 0.05f, 11, id));
    }
    EXPECT_NE(sketch_polyline_3d(pts, normals, 0.05f, 11, 0), sketch_polyline_3d(pts, normals, 0.05f, 12, 0));
    try {
        sketch_polyline_3d(pts, {}, 0.05f, 1, 1);
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: lines: sketch_polyline_3d: 10 points but 0 normals");
    }
}

TEST(DistanceThinning, ProbabilityAndDeterministicDecision) {
    EXPECT_DOUBLE_EQ(keep_probability(50, 100, 1000, 0.25f), 1.0);
    EXPECT_DOUBLE_EQ(keep_probability(550, 100, 1000, 0.25f), 0.625);
    EXPECT_DOUBLE_EQ(keep_probability(5000, 100, 1000, 0.25f), 0.25f);
    EXPECT_DOUBLE_EQ(keep_probability(INFINITY, 100, 1000, 0.25f), 0.25f);
    int kept = 0;
    for (std::uint64_t id = 0; id < 10000; ++id) {
        bool k = keep_stroke(550, 100, 1000, 0.25f, 3, id);
        EXPECT_EQ(k, keep_stroke(550, 100, 1000, 0.25f, 3, id));
        kept += k;
        EXPECT_TRUE(keep_stroke(100, 100, 1000, 0.0f, 3, id));
        EXPECT_FALSE(keep_stroke(1000, 100, 1000, 0.0f, 3, id));
    }
    EXPECT_NEAR(kept, 6250, 200);
}

}  // namespace
}  // namespace penink
