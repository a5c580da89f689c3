// Polyline chaining on a real render (volcano, 400x300, in process): the finished drawing has
// far fewer paths than the traced pixel chains and their segments, and no two open path ends of
// the same layer and kind are left within the join tolerance unless they meet at a junction of
// >= 3 ends. Prints the measured ratios.
#include <gtest/gtest.h>

#include <cstdio>
#include <numeric>

#include <glm/geometric.hpp>

#include "scene/frame_source.hpp"
#include "lines/finish_drawing.hpp"

using namespace penink;

namespace {

struct Counts {
    size_t strokes = 0, segments = 0;
};

Counts count(const Drawing& d) {
    Counts c;
    for (const Layer& l : d.layers)
        for (const Stroke& s : l.strokes) ++c.strokes, c.segments += s.points.size() - 1;
    return c;
}

int find(std::vector<int>& parent, int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// Pairs of open-stroke ends (same kind) closer than tol whose cluster has fewer than 3 ends.
size_t unjoined_pairs(const std::vector<Stroke>& strokes, float tol) {
    std::vector<glm::vec2> ends;
    std::vector<const std::string*> kinds;
    for (const Stroke& s : strokes) {
        if (s.points.size() < 2 || s.points.front() == s.points.back()) continue;
        for (glm::vec2 p : {s.points.front(), s.points.back()}) ends.push_back(p), kinds.push_back(&s.kind);
    }
    std::vector<int> parent(ends.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<std::pair<int, int>> close;
    for (size_t i = 0; i < ends.size(); ++i)
        for (size_t j = i + 1; j < ends.size(); ++j)
            if (*kinds[i] == *kinds[j] && glm::length(ends[i] - ends[j]) < tol) {
                close.emplace_back(int(i), int(j));
                parent[find(parent, int(i))] = find(parent, int(j));
            }
    std::vector<int> size(ends.size(), 0);
    for (size_t i = 0; i < ends.size(); ++i) ++size[find(parent, int(i))];
    size_t bad = 0;
    for (auto [i, j] : close) bad += size[find(parent, i)] < 3;
    return bad;
}

}  // namespace

TEST(GoldenChaining, VolcanoHasFewLongPathsAndNoUnjoinedEnds) {
    Scene scene = load_scene(PENINK_SOURCE_DIR "/examples/volcano.asc");
    scene.view.camera.width = 400, scene.view.camera.height = 300;
    validate_scene(scene);
    const auto context = make_gl_context(GlBackend::osmesa);
    Drawing d = draw_scene(scene, *context, Log{}).drawing;
    const Counts raw = count(d);
    FinishOptions options;
    options.seed = scene.style.seed;
    const FinishStats stats = finish_drawing(d, options);
    const Counts done = count(d);
    std::printf("volcano 400x300: %zu traced chains (%zu segments) -> %zu paths; paths/chains %.3f, "
                "paths/segments %.4f\n",
                raw.strokes, raw.segments, done.strokes, double(done.strokes) / raw.strokes,
                double(done.strokes) / raw.segments);
    for (LayerKind k : all_layers) {
        const LayerFinishStats& s = stats.layers[size_t(k)];
        if (s.strokes_in)
            std::printf("  %s: %zu -> %zu lines, %.0f px, pen-up %.0f -> %.0f px\n", layer_name(k).data(),
                        s.strokes_in, s.strokes, s.length, s.travel_before, s.travel_after);
        EXPECT_LE(s.travel_after, s.travel_before + 1e-6) << layer_name(k);
        EXPECT_EQ(unjoined_pairs(d.layer(k).strokes, options.join_tolerance), 0u) << layer_name(k);
    }
    ASSERT_GT(raw.segments, 200u);
    EXPECT_LT(done.strokes * 10, raw.segments);
    EXPECT_LE(done.strokes, raw.strokes);
}
