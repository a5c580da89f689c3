// The outline of a variable-width stroke (export/stroke_outline.hpp) against the exact swept
// shape: the union of the discs of radius r(s) about the centre line's point c(s), r linear in
// arc length between points. Its boundary is where the signed distance
// f(q) = min over s of |q - c(s)| - r(s) is 0 (here s sampled every 0.01 px).
#include "export/stroke_outline.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/polyline_simplify.hpp"

using namespace penink;

namespace {

double swept_distance(glm::dvec2 q, const std::vector<glm::vec2>& pts, const std::vector<double>& widths) {
    double best = 1e9;
    for (std::size_t i = 1; i < pts.size(); ++i) {
        const glm::dvec2 a(pts[i - 1]), b(pts[i]);
        const double len = glm::length(b - a);
        const int n = std::max(1, int(std::ceil(len / 0.01)));
        for (int k = 0; k <= n; ++k) {
            const double f = double(k) / n;
            best = std::min(best, glm::length(q - (a + (b - a) * f)) - 0.5 * (widths[i - 1] + (widths[i] - widths[i - 1]) * f));
        }
    }
    return best;
}

// A bent stroke tapering from 0.3 px to 3 px and back over 8 points, as the writers fill it.
struct Sample {
    std::vector<glm::vec2> pts{{10, 10}, {14, 11}, {18, 13}, {22, 17}, {24, 22}, {25, 28}, {30, 30}, {36, 30}};
    std::vector<double> widths{0.3, 1.2, 2.4, 3.0, 3.0, 2.2, 1.0, 0.3};
};

}  // namespace

// Every vertex of the outline lies within 0.1 px of the swept shape's boundary (arcs as chords
// within 0.05 px, then Douglas-Peucker at 0.05 px), and so does the middle of every edge
// (a chord cuts inside by at most the same); every boundary point (sampled round the discs
// at the centre-line points, where it is not inside the shape) lies within 0.1 px of the
// outline. Fewer points than the round outline would need at 0.05 px alone.
TEST(StrokeOutline, WithinItsToleranceOfTheSweptShape) {
    const Sample s;
    const std::vector<glm::vec2> outline = stroke_outline(s.pts, s.widths);
    ASSERT_GE(outline.size(), 16u);
    EXPECT_LE(outline.size(), 60u);
    const double tol = 0.1 + 1e-3;
    for (std::size_t i = 0; i < outline.size(); ++i) {
        const glm::vec2 a = outline[i], b = outline[(i + 1) % outline.size()];
        EXPECT_LE(std::abs(swept_distance(glm::dvec2(a), s.pts, s.widths)), tol) << i;
        EXPECT_LE(std::abs(swept_distance(0.5 * (glm::dvec2(a) + glm::dvec2(b)), s.pts, s.widths)), tol) << i;
    }
    for (std::size_t i = 0; i < s.pts.size(); ++i)
        for (int k = 0; k < 72; ++k) {
            const double a = k * M_PI / 36.0, r = 0.5 * s.widths[i];
            const glm::dvec2 q = glm::dvec2(s.pts[i]) + r * glm::dvec2(std::cos(a), std::sin(a));
            if (swept_distance(q, s.pts, s.widths) < -1e-3) continue;  // inside: not on the boundary
            double best = 1e9;
            for (std::size_t j = 0; j < outline.size(); ++j)
                best = std::min(best, double(point_segment_distance(glm::vec2(q), outline[j], outline[(j + 1) % outline.size()])));
            EXPECT_LE(best, tol) << i << " " << k;
        }
}

// A straight stroke of one width: its two sides and two round caps; the points along the
// straight sides, one per centre-line point, all left out.
TEST(StrokeOutline, StraightSidesKeepOnlyTheirEnds) {
    std::vector<glm::vec2> pts;
    std::vector<double> widths;
    for (int i = 0; i <= 20; ++i) pts.push_back({float(i), 0.0f}), widths.push_back(2.0);
    const std::vector<glm::vec2> outline = stroke_outline(pts, widths);
    std::size_t sides = 0;
    for (const glm::vec2& p : outline) sides += std::abs(std::abs(p.y) - 1.0f) < 1e-4f && p.x > 0.5f && p.x < 19.5f;
    EXPECT_EQ(sides, 0u);
    for (const glm::vec2& p : outline) EXPECT_NEAR(std::abs(swept_distance(glm::dvec2(p), pts, widths)), 0.0, 0.1 + 1e-3);
    EXPECT_LE(outline.size(), 20u);  // two caps of radius 1 (chords within 0.05 px) and the corners
}
