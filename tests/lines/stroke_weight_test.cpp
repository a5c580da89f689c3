// Stroke weights (lines/stroke_weight.hpp): creases heavier with flow, silhouettes heavier with
// the depth gap behind them, and the weights carried through joining, simplifying and merging.
#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "lines/chain_segments.hpp"
#include "lines/doubled_lines.hpp"
#include "lines/simplify.hpp"
#include "lines/stroke_weight.hpp"

using namespace penink;

namespace {

constexpr float inf = std::numeric_limits<float>::infinity();

// 20 x 20 px: the near surface (100 m) left of x = 10, `behind` right of it.
DepthImage step_image(float behind) {
    DepthImage d{20, 20, std::vector<float>(400, 100.0f)};
    for (int y = 0; y < 20; ++y)
        for (int x = 10; x < 20; ++x) d.depth[std::size_t(y) * 20 + x] = behind;
    return d;
}

Stroke vertical_stroke() {
    Stroke s;
    for (int y = 2; y <= 18; ++y) s.points.emplace_back(10.0f, float(y)), s.depth.push_back(100.0f);
    return s;
}

}  // namespace

TEST(FlowWeight, LogFlowRisesWithFlow) {
    EXPECT_FLOAT_EQ(log_flow(1.0f), 0.0f);
    EXPECT_NEAR(log_flow(0.01f), -2.0f, 1e-6f);
    EXPECT_FLOAT_EQ(log_flow(0.0f), -12.0f);  // no flow: the floor
    float last = -13.0f;
    for (float f = 1e-9f; f <= 1.0f; f *= 1.5f) {
        EXPECT_GT(log_flow(f), last) << f;
        last = log_flow(f);
    }
}

namespace {
// Length-weighted CV of widths 0.5 + 1.25 w (the technical creases' weight_min, weight_max) over
// the strokes' segments (mean of their ends' widths).
double width_cv(const std::vector<Stroke>& strokes) {
    double sum = 0.0, sum2 = 0.0, total = 0.0;
    for (const Stroke& s : strokes)
        for (std::size_t i = 1; i < s.points.size(); ++i) {
            const double len = glm::length(s.points[i] - s.points[i - 1]);
            const double w = 0.5 + 1.25 * 0.5 * (s.weight[i - 1] + s.weight[i]);
            sum += len * w, sum2 += len * w * w, total += len;
        }
    const double mean = sum / total;
    return std::sqrt(std::max(0.0, sum2 / total - mean * mean)) / mean;
}
}  // namespace

// A frame of twigs: log flows within half a decade of each other, flow rising down each stroke.
// Ranked, they span the whole range of weights; the order (trunk over twig, downstream over
// upstream) is kept; ties at the top weigh 1.
TEST(EqualiseWeights, SpreadsACompressedLayerOverTheRangeKeepingItsOrder) {
    std::vector<Stroke> strokes;
    for (int k = 0; k < 10; ++k) {
        Stroke s;
        for (int i = 0; i <= 20; ++i) {
            s.points.emplace_back(float(10 * k), float(i));
            s.weight.push_back(log_flow(0.001f * (1.0f + 0.1f * float(k) + 0.01f * float(i))));
        }
        strokes.push_back(s);
    }
    std::vector<Stroke> raw = strokes;
    for (Stroke& s : raw)  // the three-decade rule of a basin: 1 + log10 f / 3, about 0 for all
        for (float& w : s.weight) w = std::clamp(1.0f + w / 3.0f, 0.0f, 1.0f);
    equalise_weights(strokes);
    float lo = 1.0f, hi = 0.0f;
    for (const Stroke& s : strokes)
        for (std::size_t i = 0; i < s.weight.size(); ++i) {
            lo = std::min(lo, s.weight[i]), hi = std::max(hi, s.weight[i]);
            if (i > 0) EXPECT_GT(s.weight[i], s.weight[i - 1]);  // downstream heavier
        }
    EXPECT_LT(lo, 0.01f);
    EXPECT_FLOAT_EQ(hi, 1.0f);
    for (std::size_t k = 1; k < strokes.size(); ++k) EXPECT_GT(strokes[k].weight[10], strokes[k - 1].weight[10]);
    EXPECT_LT(width_cv(raw), 0.1);
    EXPECT_GT(width_cv(strokes), 0.3);  // uniform weights: 1.25 / sqrt 12 / 1.125 = 0.32
    // ties: every point at the top weighs 1; strokes without weights are left alone
    std::vector<Stroke> ties(2);
    for (Stroke& s : ties) s.points = {{0, 0}, {0, 5}, {0, 10}};
    ties[0].weight = {0.2f, 0.2f, 1.0f};
    equalise_weights(ties);
    EXPECT_FLOAT_EQ(ties[0].weight[2], 1.0f);
    EXPECT_FLOAT_EQ(ties[0].weight[0], 0.75f);  // 7.5 of 10 px at 0.2 (the third point's half segment above)
    EXPECT_TRUE(ties[1].weight.empty());
}

TEST(DepthGapWeight, SkyHeaviestThenFarValleyThenFoldCloseBehind) {
    const auto weight_of = [](float behind) {
        std::vector<Stroke> s{vertical_stroke()};
        weigh_by_depth_gap(s, step_image(behind));
        double sum = 0.0;
        for (float w : s[0].weight) sum += w;
        EXPECT_EQ(s[0].weight.size(), s[0].points.size());
        return sum / double(s[0].weight.size());
    };
    const double sky = weight_of(inf), valley = weight_of(300.0f), fold = weight_of(103.0f);
    EXPECT_DOUBLE_EQ(sky, 1.0);
    EXPECT_NEAR(valley, 2.0 / 2.1, 1e-5);  // gap 2: 2 / (2 + 0.1)
    EXPECT_NEAR(fold, 0.03 / 0.13, 1e-5);  // gap 0.03
    EXPECT_GT(valley, fold + 0.5);
}

TEST(DepthGapWeight, BeyondTheFrameIsNotSky) {
    DepthImage d{10, 10, std::vector<float>(100, 50.0f)};
    EXPECT_FLOAT_EQ(depth_gap_at(d, {0.5f, 0.5f}, 2), 0.0f);  // only pixels in the frame count
    d.depth[0] = inf;
    EXPECT_TRUE(std::isinf(depth_gap_at(d, {1.5f, 1.5f}, 2)));
}

TEST(SmoothAlong, RunningMeanOverArcLength) {
    std::vector<glm::vec2> p;
    for (int i = 0; i < 11; ++i) p.emplace_back(float(i), 0.0f);
    std::vector<float> v(11, 0.0f);
    v[5] = 7.0f;
    smooth_along(p, v, 3.0f);
    EXPECT_FLOAT_EQ(v[5], 1.0f);         // 7 over the 7 points within 3 px
    EXPECT_FLOAT_EQ(v[2], 7.0f / 6.0f);  // points 0 .. 5
    EXPECT_FLOAT_EQ(v[1], 0.0f);         // points 0 .. 4
    EXPECT_FLOAT_EQ(v[0], 0.0f);
}

TEST(StrokeWeightCarried, ThroughJoinSimplifyAndMerge) {
    Stroke a, b;
    a.points = {{0, 0}, {10, 0}}, a.depth = {1, 1}, a.weight = {0.0f, 0.5f}, a.kind = "crease";
    b.points = {{10, 0}, {20, 0.01f}, {30, 0}}, b.depth = {1, 1, 1}, b.weight = {0.5f, 0.75f, 1.0f}, b.kind = "crease";
    std::vector<Stroke> joined = join_strokes({a, b}, 0.5f);
    ASSERT_EQ(joined.size(), 1u);
    ASSERT_EQ(joined[0].weight.size(), joined[0].points.size());
    const float first = joined[0].weight.front(), last = joined[0].weight.back();
    EXPECT_FLOAT_EQ(std::min(first, last), 0.0f);
    EXPECT_FLOAT_EQ(std::max(first, last), 1.0f);
    // the middle point where the weight bends (x = 10) stays, the one on the weight's chord goes
    std::vector<Stroke> simple = simplify_strokes(joined, 0.4f);
    ASSERT_EQ(simple[0].weight.size(), simple[0].points.size());
    EXPECT_EQ(simple[0].points.size(), 3u);
    // a weaker stroke beside it from x = 12 to 18 is cut; a stroke crossing keeps its weights,
    // its cut ends interpolated
    Stroke c;
    c.points = {{15, -20}, {15, 20}}, c.depth = {1, 1}, c.weight = {0.0f, 1.0f}, c.strength = 0.0f, c.kind = "crease";
    Stroke along;
    along.points = {{-20, 1}, {40, 1}}, along.depth = {1, 1}, along.weight = {0.2f, 0.2f}, along.strength = 2.0f;
    std::vector<Stroke> merged = merge_doubled({c}, 1.5f, 4.0f, {along});
    ASSERT_EQ(merged.size(), 1u);  // a crossing touches over a pixel or two: left whole
    EXPECT_EQ(merged[0].weight, c.weight);
    Stroke beside;
    beside.points = {{0, 1}, {20, 1}}, beside.depth = {1, 1}, beside.weight = {0.0f, 1.0f};
    Stroke over;
    over.points = {{10, 0}, {30, 0}}, over.depth = {1, 1}, over.strength = 5.0f;
    merged = merge_doubled({beside}, 1.5f, 4.0f, {over});
    ASSERT_EQ(merged.size(), 1u);  // what is left: x 0 .. ~8.5
    ASSERT_EQ(merged[0].weight.size(), merged[0].points.size());
    EXPECT_NEAR(merged[0].weight.back(), merged[0].points.back().x / 20.0f, 1e-4f);
}

// Ridges by height: each vertex's z, a vertex off the surface (zero normal) the lowest z on it
// (900 m off the surface does not count); ranked by equalise_weights, the lowest ridge vertex and
// the one off the surface weigh the same, the highest 1.
TEST(HeightWeight, RidgesWeighByTheReliefTheyStandAbove) {
    VertexLines lines;
    const glm::vec3 up(0.0f, 0.0f, 1.0f), off(0.0f);
    lines.positions = {{0, 0, 100}, {1, 0, 200}, {2, 0, 300}, {3, 0, 900}, {0, 5, 250}};
    lines.normals = {up, up, up, off, up};
    lines.runs = {{0, 4}, {4, 1}};
    EXPECT_EQ(ridge_heights(lines), (std::vector<float>{100, 200, 300, 100, 250}));
    VertexLines none = lines;
    for (glm::vec3& n : none.normals) n = off;
    EXPECT_EQ(ridge_heights(none), std::vector<float>(5, 0.0f));
    // a ridge falling evenly from a summit: its ranked weights spread evenly over [0, 1], widths
    // between the styles' weight_min 0.35 and weight_max 1.65 varying by CV >= 0.3 (uniform
    // weights: mean 1.0, standard deviation 1.3 / sqrt 12 = 0.375)
    VertexLines fall;
    for (int k = 0; k <= 100; ++k) fall.positions.emplace_back(float(k), 0.0f, float(1000 - 5 * k)), fall.normals.push_back(up);
    fall.runs = {{0, 101}};
    Stroke s;
    for (const glm::vec3& p : fall.positions) s.points.emplace_back(p.x, p.y), s.depth.push_back(10.0f);
    s.weight = ridge_heights(fall);
    std::vector<Stroke> strokes{s};
    equalise_weights(strokes);
    EXPECT_FLOAT_EQ(strokes[0].weight.front(), 1.0f);  // the summit
    EXPECT_LT(strokes[0].weight.back(), 0.01f);
    double sum = 0.0, sum2 = 0.0;
    for (float x : strokes[0].weight) {
        const double width = 0.35 + 1.3 * x;
        sum += width, sum2 += width * width;
    }
    const double mean = sum / 101.0, cv = std::sqrt(sum2 / 101.0 - mean * mean) / mean;
    EXPECT_GT(cv, 0.3);
}
