// Line accuracy metric on hand cases with exact answers: precision/recall at 1 and 2 px, mean
// distances both ways, empty inputs, per-layer scores, and the 1-px polyline rasteriser.
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "lines/line_accuracy.hpp"

using namespace penink;

namespace {

PixelMask mask(int w, int h) {
    PixelMask m;
    m.width = w, m.height = h;
    m.on.assign(std::size_t(w) * h, 0);
    return m;
}

void set(PixelMask& m, int x, int y) { m.on[std::size_t(y) * m.width + x] = 1; }

// Per layer of a drawing: its strokes rasterised at 1 px against that layer's reference; layers
// without a reference entry are skipped.
std::map<LayerKind, LineAccuracy> drawing_accuracy(const Drawing& drawing,
                                                   const std::map<LayerKind, std::vector<ImagePolyline>>& reference) {
    std::map<LayerKind, LineAccuracy> out;
    for (const auto& [kind, ref] : reference)
        out[kind] = line_accuracy(rasterize_strokes(drawing.layer(kind).strokes, drawing.width, drawing.height), ref);
    return out;
}

}  // namespace

TEST(AccuracyMetric, PixelsOnTheReferenceScorePerfectly) {
    PixelMask m = mask(12, 10);
    for (int x = 0; x < 10; ++x) set(m, x, 5);
    const LineAccuracy a = line_accuracy(m, {{{0.0f, 5.5f}, {10.0f, 5.5f}}});
    EXPECT_EQ(a.drawn_pixels, 10u);
    EXPECT_NEAR(a.reference_length, 10.0, 1e-9);
    EXPECT_DOUBLE_EQ(a.at(1.0).precision, 1.0);
    EXPECT_DOUBLE_EQ(a.at(1.0).recall, 1.0);
    EXPECT_DOUBLE_EQ(a.at(2.0).recall, 1.0);
    EXPECT_NEAR(a.mean_drawn_to_reference, 0.0, 1e-12);
    EXPECT_NEAR(a.mean_reference_to_drawn, 0.25, 1e-9);  // mean of |x - nearest centre|
}

TEST(AccuracyMetric, StrayPixelLowersPrecisionAndMissingPixelsLowerRecall) {
    PixelMask m = mask(22, 10);
    for (int x = 0; x < 10; ++x) set(m, x, 5);
    set(m, 3, 8);  // centre (3.5, 8.5): 3 px off the line
    const LineAccuracy a = line_accuracy(m, {{{0.0f, 5.5f}, {20.0f, 5.5f}}}, {1.0, 2.0, 3.0});
    EXPECT_NEAR(a.at(1.0).precision, 10.0 / 11.0, 1e-12);
    EXPECT_NEAR(a.at(2.0).precision, 10.0 / 11.0, 1e-12);
    EXPECT_NEAR(a.at(3.0).precision, 1.0, 1e-12);
    EXPECT_NEAR(a.mean_drawn_to_reference, 3.0 / 11.0, 1e-12);
    // Reference within 1 px of a centre up to x = 10.5, within 2 px up to 11.5 (of 20).
    EXPECT_NEAR(a.at(1.0).recall, 10.5 / 20.0, 1e-9);
    EXPECT_NEAR(a.at(2.0).recall, 11.5 / 20.0, 1e-9);
    // Integral of the distance: 0.125 + 9 * 0.25 on [0, 9.5], 10.5^2 / 2 beyond; over 20 px.
    EXPECT_NEAR(a.mean_reference_to_drawn, (2.375 + 55.125) / 20.0, 1e-9);
}

TEST(AccuracyMetric, EmptyInputs) {
    PixelMask none = mask(8, 8);
    const LineAccuracy a = line_accuracy(none, {{{1.0f, 1.0f}, {5.0f, 1.0f}}});
    EXPECT_DOUBLE_EQ(a.at(1.0).precision, 1.0);
    EXPECT_DOUBLE_EQ(a.at(1.0).recall, 0.0);
    EXPECT_TRUE(std::isinf(a.mean_reference_to_drawn));
    PixelMask one = mask(8, 8);
    set(one, 2, 2);
    const LineAccuracy b = line_accuracy(one, {});
    EXPECT_DOUBLE_EQ(b.at(2.0).precision, 0.0);
    EXPECT_DOUBLE_EQ(b.at(2.0).recall, 1.0);
    EXPECT_TRUE(std::isinf(b.mean_drawn_to_reference));
    const LineAccuracy c = line_accuracy(none, {});
    EXPECT_DOUBLE_EQ(c.at(1.0).precision, 1.0);
    EXPECT_DOUBLE_EQ(c.at(1.0).recall, 1.0);
    EXPECT_DOUBLE_EQ(c.mean_reference_to_drawn, 0.0);
    try {
        (void)c.at(1.5);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "penink: lines: no accuracy score at tolerance 1.500000 px");
    }
}

TEST(AccuracyMetric, FarReferenceFoundOutsideTheImage) {
    PixelMask m = mask(10, 10);
    set(m, 9, 9);
    const LineAccuracy a = line_accuracy(m, {{{-30.0f, 9.5f}, {-20.0f, 9.5f}}});
    EXPECT_NEAR(a.mean_drawn_to_reference, 29.5, 1e-9);
    EXPECT_NEAR(a.mean_reference_to_drawn, 34.5, 1e-9);  // mean of 29.5..39.5
}

TEST(AccuracyMetric, RasterisedDiagonalAndPerLayerScores) {
    const PixelMask r = rasterize_polylines({{{0.5f, 0.5f}, {3.5f, 3.5f}}}, 5, 5);
    std::size_t on = 0;
    for (auto v : r.on) on += v != 0;
    EXPECT_EQ(on, 4u);
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(r.on[std::size_t(i) * 5 + i]);
    Drawing d;
    d.width = 20, d.height = 10;
    Stroke s;
    s.points = {{2.0f, 4.5f}, {12.0f, 4.5f}};
    s.depth = {1.0f, 1.0f};
    d.layer(LayerKind::silhouettes).strokes.push_back(s);
    const auto acc = drawing_accuracy(d, {{LayerKind::silhouettes, {{{2.0f, 4.5f}, {12.0f, 4.5f}}}},
                                          {LayerKind::creases, {{{2.0f, 8.5f}, {4.0f, 8.5f}}}}});
    ASSERT_EQ(acc.size(), 2u);
    EXPECT_EQ(acc.at(LayerKind::silhouettes).drawn_pixels, 11u);  // x = 2..12 (12.0 is pixel 12)
    EXPECT_DOUBLE_EQ(acc.at(LayerKind::silhouettes).at(1.0).recall, 1.0);
    EXPECT_DOUBLE_EQ(acc.at(LayerKind::silhouettes).at(1.0).precision, 1.0);
    EXPECT_EQ(acc.at(LayerKind::creases).drawn_pixels, 0u);
    EXPECT_DOUBLE_EQ(acc.at(LayerKind::creases).at(2.0).recall, 0.0);
}
