#include "scene/flight_coherence.hpp"

#include <iomanip>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "core/progress_bar.hpp"
#include "lines/line_accuracy.hpp"
#include "scene/flight_frames.hpp"
#include "scene/terrain_frames.hpp"

namespace penink {

std::vector<std::vector<glm::vec2>> carry_strokes(const std::vector<Stroke>& strokes, const Camera& from,
                                                  const Camera& to) {
    const glm::dmat4 inv = glm::inverse(view_projection(from));
    std::vector<std::vector<glm::vec2>> out;
    for (const Stroke& s : strokes) {
        std::vector<glm::vec2> run;
        for (std::size_t i = 0; i < s.points.size(); ++i) {
            glm::dvec2 px;
            double depth = 0;
            bool ok = i < s.depth.size() && s.depth[i] > 0.0f;
            if (ok) {
                const glm::dvec2 p(s.points[i]);
                const glm::dvec4 q = inv * glm::dvec4(2.0 * p.x / from.width - 1.0, 1.0 - 2.0 * p.y / from.height, 1.0, 1.0);
                const glm::dvec3 world = from.eye + glm::normalize(glm::dvec3(q) / q.w - from.eye) * double(s.depth[i]);
                ok = project_to_pixel(to, world, px, depth);
            }
            if (!ok) {
                if (run.size() >= 2) out.push_back(run);
                run.clear();
                continue;
            }
            run.push_back(glm::vec2(px));
        }
        if (run.size() >= 2) out.push_back(std::move(run));
    }
    return out;
}

std::vector<CoherenceRow> flight_coherence(const Scene& flight_scene, const std::string& flight_csv, GlContext& context,
                                           double tolerance_px, const Log& log) {
    Scene scene = flight_scene;  // its vertical exaggeration resolved by plan_flight
    Flight f = plan_flight(scene, flight_csv, false, log);
    const int w = scene.view.camera.width, h = scene.view.camera.height;
    TerrainFrames frames(context, scene_drainage(scene, f.dem, log), std::move(f.model), w, h, log,
                         LineCulling{f.cameras, line_culling_px(scene)});
    std::vector<CoherenceRow> rows;
    ProgressBar bar(std::cerr, log.progress, "coherence", int(f.records.size()));
    Drawing previous;
    for (std::size_t i = 0; i < f.records.size(); ++i) {
        const Drawing d = frames.draw(f.cameras[i], frame_scene(scene, f.records[i])).drawing;
        if (i > 0) {
            CoherenceRow row;
            row.frame = int(i);
            const auto share = [&](LayerKind kind, double& length) {
                const std::vector<Stroke>& before = previous.layer(kind).strokes;
                const LineAccuracy a = line_accuracy(rasterize_strokes(d.layer(kind).strokes, w, h),
                                                     carry_strokes(before, f.cameras[i - 1], f.cameras[i]), {tolerance_px});
                length = 0;
                for (const Stroke& s : before)
                    for (std::size_t k = 1; k < s.points.size(); ++k) length += glm::length(s.points[k] - s.points[k - 1]);
                return a.reference_length > 0 ? a.at(tolerance_px).recall : 0.0;
            };
            row.silhouettes = share(LayerKind::silhouettes, row.silhouette_px);
            row.creases = share(LayerKind::creases, row.crease_px);
            rows.push_back(row);
        }
        previous = d;
        bar.step("frame " + std::to_string(i + 1), 0.0);
    }
    bar.finish();
    return rows;
}

std::string coherence_csv(const std::vector<CoherenceRow>& rows) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3) << "frame,silhouettes,creases,silhouette_px,crease_px\n";
    double sil = 0, cre = 0, sil_px = 0, cre_px = 0;
    for (const CoherenceRow& r : rows) {
        s << r.frame << "," << r.silhouettes << "," << r.creases << "," << r.silhouette_px << "," << r.crease_px << "\n";
        sil += r.silhouettes * r.silhouette_px, cre += r.creases * r.crease_px;
        sil_px += r.silhouette_px, cre_px += r.crease_px;
    }
    s << "mean," << (sil_px > 0 ? sil / sil_px : 0.0) << "," << (cre_px > 0 ? cre / cre_px : 0.0) << "," << sil_px << ","
      << cre_px << "\n";
    return s.str();
}

}  // namespace penink
