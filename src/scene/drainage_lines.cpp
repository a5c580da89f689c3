#include "scene/drainage_lines.hpp"

#include <algorithm>

#include "lines/crease_scores.hpp"
#include "lines/line_strokes.hpp"
#include "lines/scored_polylines.hpp"
#include "lines/short_stroke_clusters.hpp"
#include "lines/spacing_thinning.hpp"
#include "lines/stroke_weight.hpp"

namespace penink {

float line_culling_px(const Scene& scene) {
    const double spacing = std::min(scene.lines.creases.spacing_px, scene.lines.ridges.spacing_px);
    const Style& style = scene.style.resolved;
    const double sketch = std::max(float(style.layer(LayerKind::creases).sketch), float(style.layer(LayerKind::ridges).sketch));
    const double margin = sketch > 0.0 ? 0.5 : 1.0;  // sketch offsets are sized at a line's mean depth
    return float(std::max(0.0, margin * (3.0 * spacing - 2.0 * sketch - 1.0)));
}

DrainageLines::DrainageLines(const GlApi& gl, DrainageLineData data)
    : creases_{std::move(data.creases), nullptr}, ridges_{std::move(data.ridges), nullptr} {
    for (UploadedLines* set : {&creases_, &ridges_}) set->pass = std::make_unique<DmPass>(gl, dm_input(set->lines));
}

void DrainageLines::set_lines(DrainageLineData data) {
    creases_.lines = std::move(data.creases), ridges_.lines = std::move(data.ridges);
    for (UploadedLines* set : {&creases_, &ridges_}) set->pass->set_vertices(dm_input(set->lines));
}

DrainageLines::DrainageLines(const GlApi& gl, const DrainageDb& db, const Terrain& model)
    : DrainageLines(gl, prepare_drainage_lines(db, model)) {}

void DrainageLines::draw(const Camera& camera, const Scene& scene, GLuint toward_texture,
                         float max_distance, Drawing& drawing, PassTimings& times) {
    DmFrame frame;
    frame.camera = &camera;
    frame.light = glm::vec3(light_vector(Light{scene.view.light.azimuth, scene.view.light.altitude}));
    frame.toward_texture = toward_texture;
    struct LayerLines {
        const UploadedLines& set;
        const CreaseParams& params;
        LayerKind layer;
        const char* kind;
        float sketch_px;
        int repeat;
        double& ms;
    };
    // object-space sketch and repeats of creases and ridges: the style's (Potter et al., "NPR-Style
    // 3D Line Textures", 4.3: end points moved within the surface's tangent plane)
    const LayerStyle &crease_pen = scene.style.resolved.layer(LayerKind::creases),
                     &ridge_pen = scene.style.resolved.layer(LayerKind::ridges);
    for (const LayerLines& l : {LayerLines{creases_, scene.lines.creases, LayerKind::creases, "crease",
                                           float(crease_pen.sketch), crease_pen.repeat, times.dm},
                                LayerLines{ridges_, scene.lines.ridges, LayerKind::ridges, "ridge", float(ridge_pen.sketch),
                                           ridge_pen.repeat, times.ridges}}) {
        if (!l.params.enabled) continue;
        std::vector<float> scores;
        l.ms = l.set.pass->run(frame, [&](std::span<const CreaseTerms> terms) {
            scores = crease_scores(terms, l.params, max_distance);
        });
        const ScoredLineSet& lines = l.set.lines;
        const double per_metre = max_distance > 0.0f ? l.params.distance_attenuation / double(max_distance) : 0.0;
        whole_or_nothing_by_distance(scores, lines.positions, lines.runs, camera, per_metre);
        std::vector<float> weight;  // creases by flow, ridges by height (lines/stroke_weight.hpp)
        if (l.layer == LayerKind::creases)
            for (float f : lines.flow) weight.push_back(log_flow(f));
        else weight = ridge_heights(lines);
        std::vector<Stroke>& strokes = drawing.layer(l.layer).strokes;
        strokes = thin_by_spacing(
            line_strokes(lines, scores, camera, l.kind, ObjectSketch{l.sketch_px, l.repeat, scene.style.seed}, weight),
            float(l.params.spacing_px));
        if (l.layer == LayerKind::creases)  // no stars of short stubs (lines/short_stroke_clusters.hpp)
            strokes = thin_star_clusters(std::move(strokes), float(4.0 * l.params.spacing_px), float(1.5 * l.params.spacing_px));
        equalise_weights(strokes);  // the rank among the drawn lines
    }
}

}  // namespace penink
