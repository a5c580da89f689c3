// Finishing a drawing's strokes for export (finish_drawing.hpp).
#include "lines/finish_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "lines/chain_segments.hpp"
#include "lines/distance_thinning.hpp"
#include "lines/doubled_lines.hpp"
#include "lines/line_metrics.hpp"
#include "lines/plotter_order.hpp"
#include "lines/random_bits.hpp"
#include "lines/simplify.hpp"
#include "lines/sketchy.hpp"

namespace penink {

namespace {

float mean_depth(const Stroke& s) {
    if (s.depth.empty()) return 0.0f;
    double sum = 0.0;
    for (float d : s.depth) sum += d;
    return float(sum / double(s.depth.size()));
}

// Join, simplify, drop short strokes, and join again where drops left 2-end nodes.
std::vector<Stroke> join_and_clean(std::vector<Stroke> strokes, const FinishOptions& o, const LayerFinish& l) {
    for (Stroke& s : strokes)
        if (s.depth.size() != s.points.size()) s.depth.resize(s.points.size(), 0.0f);
    ChainParams join;
    join.tolerance = o.join_tolerance, join.occlusion = l.occlusion_joins;
    strokes = simplify_strokes(join_strokes(std::move(strokes), join), o.simplify_tolerance);
    const std::size_t before = strokes.size();
    std::erase_if(strokes, [&](const Stroke& s) { return s.points.empty() || stroke_length(s) < l.min_length; });
    if (strokes.size() != before) strokes = simplify_strokes(join_strokes(std::move(strokes), join), o.simplify_tolerance);
    return strokes;
}

void thin_by_distance(std::vector<Stroke>& strokes, const FinishOptions& o, const LayerFinish& l,
                      double max_depth) {
    if (l.keep_far >= 1.0f) return;
    const float near = float(o.near * max_depth), far = float(o.far * max_depth);
    std::erase_if(strokes, [&](const Stroke& s) {
        return !keep_stroke(mean_depth(s), near, far, l.keep_far, o.seed, stroke_geometry_id(s));
    });
}

std::vector<Stroke> sketch_all(const std::vector<Stroke>& strokes, const FinishOptions& o, const LayerFinish& l) {
    SketchParams p;
    p.amount = l.space == SketchSpace::image ? std::max(l.sketch, 0.0f) : 0.0f;
    p.overshoot = std::max(l.overshoot, 0.0f);
    p.repeat = l.space == SketchSpace::image ? std::max(l.repeat, 1) - 1 : 0;
    if (p.amount == 0.0f && p.overshoot == 0.0f && p.repeat == 0) return strokes;
    std::vector<Stroke> out;
    out.reserve(strokes.size() * std::size_t(p.repeat + 1));
    for (const Stroke& s : strokes)
        for (Stroke& c : sketch_copies(s, p, o.seed, stroke_geometry_id(s))) out.push_back(std::move(c));
    return out;
}

}  // namespace

namespace {

// Joined, cleaned and merged (yielding to `above`).
std::vector<Stroke> clean_layer(std::vector<Stroke> strokes, const FinishOptions& options, const LayerFinish& layer,
                                const std::vector<Stroke>& above, LayerFinishStats& stats) {
    stats.strokes_in = strokes.size();
    strokes = join_and_clean(std::move(strokes), options, layer);
    if (layer.merge_px > 0.0f) {
        strokes = merge_doubled(std::move(strokes), layer.merge_px, layer.merge_run_px, above);
        std::erase_if(strokes, [&](const Stroke& s) { return s.points.size() < 2 || stroke_length(s) < layer.min_length; });
    }
    std::erase_if(strokes, [&](const Stroke& s) { return is_closed(s) && stroke_extent(s) < 4.0f * layer.min_length; });
    stats.joined = strokes.size();
    return strokes;
}

// Distance thinning, metrics, sketch and plotter order of cleaned strokes.
std::vector<Stroke> finish_cleaned(std::vector<Stroke> strokes, const FinishOptions& options, const LayerFinish& layer,
                                   double max_depth, LayerFinishStats& stats) {
    thin_by_distance(strokes, options, layer, max_depth);
    if (options.measure) {
        const LineMetrics m = line_metrics(strokes);
        stats.small_loops = m.small_loops, stats.doubled_share = m.doubled_share();
    }
    strokes = sketch_all(strokes, options, layer);
    const PlotterStats ps = order_for_plotter(strokes, options.home);
    stats.strokes = strokes.size();
    stats.length = ps.length;
    stats.travel_before = ps.travel_before;
    stats.travel_after = ps.travel_after;
    return strokes;
}

}  // namespace

std::vector<Stroke> finish_strokes(std::vector<Stroke> strokes, const FinishOptions& options,
                                   const LayerFinish& layer, double max_depth, LayerFinishStats& stats) {
    return finish_cleaned(clean_layer(std::move(strokes), options, layer, {}, stats), options, layer, max_depth, stats);
}

FinishStats finish_drawing(Drawing& drawing, const FinishOptions& options) {
    double max_depth = 0.0;
    for (const Layer& l : drawing.layers)
        for (const Stroke& s : l.strokes)
            for (float d : s.depth)
                if (std::isfinite(d)) max_depth = std::max(max_depth, double(d));
    FinishStats stats;
    const std::size_t sil = static_cast<std::size_t>(LayerKind::silhouettes);
    std::vector<std::size_t> order{sil};  // the silhouettes first: creases and ridges yield to them
    for (std::size_t i = 0; i < drawing.layers.size(); ++i)
        if (i != sil) order.push_back(i);
    for (const std::size_t i : order) {
        const bool yields = i == static_cast<std::size_t>(LayerKind::creases) || i == static_cast<std::size_t>(LayerKind::ridges);
        static const std::vector<Stroke> none;
        drawing.layers[i].strokes = clean_layer(std::move(drawing.layers[i].strokes), options, options.layers[i],
                                                yields ? drawing.layers[sil].strokes : none, stats.layers[i]);
    }
    for (std::size_t i = 0; i < drawing.layers.size(); ++i) {
        Layer& l = drawing.layers[i];
        l.strokes = finish_cleaned(std::move(l.strokes), options, options.layers[i], max_depth, stats.layers[i]);
    }
    return stats;
}

std::uint64_t object_line_id(const ObjectLine& line) {
    const auto bits = float_bits;
    std::uint64_t h = splitmix64(line.points.size() ^ 0x6f626a6563740000ull);  // "object"
    if (line.points.empty()) return h;
    for (const glm::vec3& p : {line.points.front(), line.points.back()})
        h = splitmix64(splitmix64(h ^ (bits(p.x) << 32 | bits(p.y))) ^ bits(p.z));
    return h;
}

std::vector<ObjectLine> sketch_object_copies(const ObjectLine& line, float amount_px, int repeat,
                                             const Camera& camera, std::uint64_t seed) {
    std::vector<ObjectLine> out;
    const int n = std::max(repeat, 1);
    double sum = 0.0;
    for (float d : line.depth) sum += d;
    const float depth = line.depth.empty() ? 0.0f : float(sum / double(line.depth.size()));
    const float amount = amount_px > 0.0f ? amount_px * float(world_per_pixel(camera, depth)) : 0.0f;
    const std::uint64_t id = line.points.empty() ? 0 : object_line_id(line);
    for (int pass = 0; pass < n; ++pass) {
        ObjectLine c = line;
        if (amount > 0.0f && !line.points.empty())
            c.points = sketch_polyline_3d(line.points, line.normals, amount, seed, splitmix64(id + std::uint64_t(pass)));
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace penink
