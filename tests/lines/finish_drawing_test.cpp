// finish_drawing: joining (same kind, junctions kept), simplification, dropping of short strokes
// (with re-joining), distance thinning, sketch / overshoot / repeat exactly once, image- versus
// object-space layers, seeded determinism independent of input order, plotter ordering.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "lines/finish_drawing.hpp"

using namespace penink;

namespace {

Stroke line(std::vector<glm::vec2> pts, const std::string& kind = "silhouette", float depth = 10.0f) {
    Stroke s;
    s.depth.assign(pts.size(), depth);
    s.points = std::move(pts);
    s.kind = kind;
    return s;
}

// A straight line from a to b with n points.
Stroke dense(glm::vec2 a, glm::vec2 b, int n, const std::string& kind = "silhouette", float depth = 10.0f) {
    std::vector<glm::vec2> pts;
    for (int i = 0; i < n; ++i) pts.push_back(a + (b - a) * (float(i) / float(n - 1)));
    return line(pts, kind, depth);
}

FinishOptions plain() {
    FinishOptions o;
    o.seed = 7;
    return o;
}

std::vector<Stroke> finish(std::vector<Stroke> s, const FinishOptions& o, const LayerFinish& l = {}) {
    LayerFinishStats st;
    return finish_strokes(std::move(s), o, l, 100.0, st);
}

double length(const Stroke& s) {
    double l = 0;
    for (size_t i = 1; i < s.points.size(); ++i) l += glm::length(s.points[i] - s.points[i - 1]);
    return l;
}

}  // namespace

TEST(FinishDrawing, JoinsPiecesWithinToleranceOfSameKindOnly) {
    // Three collinear pieces, gaps 0.6 px (< 1 px tolerance); a fourth of another kind touching.
    std::vector<Stroke> in = {dense({0, 0}, {20, 0}, 21), dense({40.6f, 0}, {60, 0}, 20),
                              dense({20.6f, 0}, {40, 0}, 20), dense({60, 0}, {60, 30}, 31, "outline")};
    const auto out = finish(in, plain());
    ASSERT_EQ(out.size(), 2u);
    size_t sil = out[0].kind == "silhouette" ? 0 : 1;
    EXPECT_EQ(out[sil].points.size(), 2u);  // joined then simplified to one segment
    EXPECT_NEAR(length(out[sil]), 60.0, 0.5);
    EXPECT_EQ(out[1 - sil].kind, "outline");
}

TEST(FinishDrawing, KeepsJunctionsOfThreeEnds) {
    std::vector<Stroke> in = {dense({0, 0}, {10, 0}, 5), dense({10, 0}, {20, 0}, 5), dense({10, 0}, {10, 10}, 5)};
    const auto out = finish(in, plain());
    EXPECT_EQ(out.size(), 3u);
}

TEST(FinishDrawing, SimplifiesWithinTolerance) {
    std::vector<glm::vec2> zig;
    for (int i = 0; i <= 100; ++i) zig.push_back({float(i), i % 2 ? 0.2f : 0.0f});
    FinishOptions o = plain();
    auto out = finish({line(zig)}, o);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].points.size(), 2u);
    o.simplify_tolerance = 0.1f;
    out = finish({line(zig)}, o);
    EXPECT_EQ(out[0].points.size(), 101u);
}

TEST(FinishDrawing, DropsShortStrokesAndRejoinsWhatTheyLeft) {
    // A junction of three where one branch is 1.5 px long: it goes, the other two then join.
    std::vector<Stroke> in = {dense({0, 0}, {10, 0}, 5), dense({10, 0}, {20, 5}, 5), dense({10, 0}, {10, 1.5f}, 2),
                              dense({50, 50}, {51, 51}, 2)};
    const auto out = finish(in, plain());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].points.size(), 3u);
    EXPECT_NEAR(length(out[0]), 10.0 + std::sqrt(125.0), 1e-3);
}

TEST(FinishDrawing, SketchRepeatAndOvershootAppliedOnce) {
    LayerFinish l;
    l.overshoot = 2.0f;
    l.repeat = 3;
    auto out = finish({dense({10, 10}, {50, 10}, 2)}, plain(), l);
    ASSERT_EQ(out.size(), 3u);  // the stroke and two repeats
    for (const Stroke& s : out) EXPECT_NEAR(length(s), 44.0, 1e-4);  // 40 + 2 * 2, no sketch
    l.sketch = 1.5f;
    out = finish({dense({10, 10}, {50, 10}, 2)}, plain(), l);
    ASSERT_EQ(out.size(), 3u);
    for (const Stroke& s : out) {
        const glm::vec2 a = s.points.front().x < s.points.back().x ? s.points.front() : s.points.back();
        EXPECT_LE(glm::length(a - glm::vec2(8, 10)), 1.5f + 1e-4f);
    }
    EXPECT_NE(out[0].points, out[1].points);  // every repeat has its own perturbation
}

TEST(FinishDrawing, ObjectSpaceLayersAreNotPerturbedOrRepeatedHere) {
    LayerFinish l;
    l.sketch = 3.0f, l.repeat = 2, l.overshoot = 1.0f, l.space = SketchSpace::object;
    const auto out = finish({dense({10, 10}, {50, 10}, 2, "crease")}, plain(), l);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].points.front().y, 10.0f);
    EXPECT_EQ(out[0].points.back().y, 10.0f);
    EXPECT_NEAR(length(out[0]), 42.0, 1e-4);  // overshoot still applied, in the image
}

TEST(FinishDrawing, SameSeedSameOutputWhateverTheInputOrder) {
    std::vector<Stroke> in;
    for (int i = 0; i < 30; ++i)
        in.push_back(dense({float(7 * i % 53), float(3 * i)}, {float(7 * i % 53 + 20), float(3 * i + 10)}, 6));
    LayerFinish l;
    l.sketch = 1.5f, l.repeat = 2, l.overshoot = 1.0f;
    const auto a = finish(in, plain(), l);
    std::vector<Stroke> shuffled(in.rbegin(), in.rend());
    std::rotate(shuffled.begin(), shuffled.begin() + 11, shuffled.end());
    const auto b = finish(shuffled, plain(), l);
    ASSERT_EQ(a.size(), 60u);
    ASSERT_EQ(b.size(), a.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].points, b[i].points) << i;
    FinishOptions other = plain();
    other.seed = 8;
    const auto c = finish(in, other, l);
    size_t same = 0;
    for (size_t i = 0; i < a.size(); ++i) same += a[i].points == c[i].points;
    EXPECT_EQ(same, 0u);
}

TEST(FinishDrawing, ThinsByDistanceAndOrdersForThePlotter) {
    std::vector<Stroke> in;
    for (int i = 0; i < 200; ++i)  // near strokes (depth 0) and far strokes (depth 100)
        in.push_back(dense({float(i % 20) * 10, float(i / 20) * 10}, {float(i % 20) * 10 + 5, float(i / 20) * 10}, 2,
                           "silhouette", i % 2 ? 100.0f : 0.0f));
    std::reverse(in.begin(), in.end());
    LayerFinish l;
    l.keep_far = 0.25f;
    LayerFinishStats st;
    const auto out = finish_strokes(in, plain(), l, 100.0, st);
    size_t far = 0, near = 0;
    for (const Stroke& s : out) (s.depth[0] > 50 ? far : near)++;
    EXPECT_EQ(near, 100u);
    EXPECT_GT(far, 12u);  // binomial(100, 0.25): 25 +- 4.3
    EXPECT_LT(far, 40u);
    EXPECT_EQ(st.strokes_in, 200u);
    EXPECT_EQ(st.strokes, out.size());
    EXPECT_NEAR(st.length, 5.0 * out.size(), 1e-3);
    EXPECT_LT(st.travel_after, 0.5 * st.travel_before);
}

TEST(FinishDrawing, LeavesSurfaceFillAndFinishesEveryLayer) {
    Drawing d;
    d.width = 100, d.height = 100;
    d.layer(LayerKind::surface).fill = {{{0, 0}, {100, 0}, {100, 100}, {0, 100}}};
    d.layer(LayerKind::silhouettes).strokes = {dense({0, 0}, {10, 0}, 11), dense({10, 0}, {20, 0}, 11)};
    d.layer(LayerKind::creases).strokes = {dense({0, 5}, {1, 5}, 2, "crease")};
    const FinishStats st = finish_drawing(d, plain());
    EXPECT_EQ(d.layer(LayerKind::surface).fill[0].size(), 4u);
    EXPECT_EQ(d.layer(LayerKind::silhouettes).strokes.size(), 1u);
    EXPECT_TRUE(d.layer(LayerKind::creases).strokes.empty());  // 1 px < min_length
    EXPECT_EQ(st.layers[size_t(LayerKind::silhouettes)].strokes_in, 2u);
    EXPECT_EQ(st.layers[size_t(LayerKind::silhouettes)].joined, 1u);
    EXPECT_NEAR(st.layers[size_t(LayerKind::silhouettes)].length, 20.0, 1e-4);
}

// min_length is the layer's: a 6 px stroke survives the default 2 px, not a layer's 8 px.
TEST(FinishDrawing, MinimumLengthIsPerLayer) {
    Drawing d;
    d.width = d.height = 100;
    d.layer(LayerKind::silhouettes).strokes = {dense({0, 0}, {6, 0}, 7), dense({0, 50}, {20, 50}, 21)};
    d.layer(LayerKind::ridges).strokes = {dense({0, 9}, {6, 9}, 7, "ridge")};
    FinishOptions o = plain();
    o.layer(LayerKind::silhouettes).min_length = 8.0f;
    finish_drawing(d, o);
    ASSERT_EQ(d.layer(LayerKind::silhouettes).strokes.size(), 1u);
    EXPECT_NEAR(length(d.layer(LayerKind::silhouettes).strokes[0]), 20.0, 1e-4);
    EXPECT_EQ(d.layer(LayerKind::ridges).strokes.size(), 1u);
}

TEST(FinishDrawing, ObjectCopiesStayInTheTangentPlane) {
    Camera cam;
    cam.fov = 90.0, cam.width = 200;
    EXPECT_NEAR(world_per_pixel(cam, 100.0), 1.0, 1e-9);
    ObjectLine line;
    for (int i = 0; i < 5; ++i) {
        line.points.push_back({float(i) * 10, 0, float(i)});
        line.normals.push_back(glm::normalize(glm::vec3(-0.1f, 0, 1)));
        line.depth.push_back(100.0f);
    }
    const auto copies = sketch_object_copies(line, 2.0f, 3, cam, 5);  // 2 px = 2 world units
    ASSERT_EQ(copies.size(), 3u);
    for (const ObjectLine& c : copies)
        for (size_t i = 0; i < c.points.size(); ++i) {
            const glm::vec3 off = c.points[i] - line.points[i];
            EXPECT_NEAR(glm::dot(off, line.normals[i]), 0.0f, 1e-4f);
            EXPECT_LE(glm::length(off), 2.0f + 1e-4f);
        }
    EXPECT_NE(copies[0].points, copies[1].points);
    EXPECT_EQ(sketch_object_copies(line, 2.0f, 3, cam, 5)[2].points, copies[2].points);
    EXPECT_EQ(sketch_object_copies(line, 0.0f, 2, cam, 5)[1].points, line.points);
}
