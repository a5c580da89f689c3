#include "scene/drainage_lines.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/parallel_chunks.hpp"
#include "lines/finish_drawing.hpp"
#include "lines/rank_scores.hpp"
#include "lines/spacing_thinning.hpp"
#include "lines/stroke_weight.hpp"
#include "surface/terrain_lod.hpp"

namespace penink {

namespace {

// Vertices of the lines a selection looks at, in batches: fetch(list, from) makes those of lines
// ids[list[i]] available for i in [from, end) and returns end (from < end <= list.size());
// vertices(i) then points at those of line ids[list[i]].
// In memory: one batch of everything.
struct MemoryBatches {
    const DrapedLineSet& set;
    const std::vector<std::uint32_t>& ids;
    const std::vector<std::uint32_t>* list = nullptr;
    std::size_t fetch(const std::vector<std::uint32_t>& l, std::size_t) { return list = &l, l.size(); }
    const DrapedVertex* vertices(std::size_t i) const { return set.vertices.data() + set.lines[ids[(*list)[i]]].first; }
};

// From the file (DvLineVertices): batches of about batch_vertices (or one longer line) read into one
// buffer, one read for each run of consecutive line ids.
struct FileBatches {
    const DrapedLineSet& set;
    const std::vector<std::uint32_t>& ids;
    const DvLineVertices& file;
    int which;
    std::size_t batch_vertices;
    DrapedVertices buffer;
    std::vector<std::size_t> at;  // where line ids[list[from + k]] starts in `buffer`
    std::size_t from = 0;
    std::size_t fetch(const std::vector<std::uint32_t>& list, std::size_t f) {
        from = f;
        at.assign(1, 0);
        std::size_t end = f;
        const auto count = [&](std::size_t i) { return set.lines[ids[list[i]]].count; };
        while (end < list.size() && (end == f || at.back() + count(end) <= batch_vertices))
            at.push_back(at.back() + count(end++));
        if (buffer.size() < at.back()) buffer.resize(at.back());
        for (std::size_t i = f; i < end;) {
            std::size_t k = i + 1;
            while (k < end && ids[list[k]] == ids[list[k - 1]] + 1) ++k;
            file.read(which, set.lines[ids[list[i]]].first, at[k - f] - at[i - f], buffer.data() + at[i - f]);
            i = k;
        }
        return end;
    }
    const DrapedVertex* vertices(std::size_t i) const { return buffer.data() + at[i - from]; }
};

// The pieces of lines `ids` (ascending ids of lines meeting [lo, hi]) laid out for a DM pass (see
// prepare_drainage_lines): the pieces found line by line, batch by batch; then the output sized
// once and the vertices of the pieces written on all cores, batch by batch over the lines that
// have pieces.
template <class Batches>
ScoredLineSet select_lines(const std::vector<DrapedLine>& lines, const std::vector<std::uint32_t>& ids,
                           Batches& batches, const LineBox& box, const LineCulling& culling) {
    const glm::vec2 lo = box.lo, hi = box.hi;
    const double e = box.exaggeration, sea = box.sea_level;
    struct Piece {
        std::uint32_t line;          // index into `kept` (the lines with pieces)
        std::uint32_t from, to;      // the line's vertices [from, to) of the piece
        std::uint32_t in0, in1;      // those inside the box: [in0, in1)
        std::size_t keep;            // keep[piece.keep + (i - from)]: vertex i is written
    };
    const auto inside = [&](const DrapedVertex& v) {
        return v.x >= lo.x && v.x <= hi.x && v.y >= lo.y && v.y <= hi.y && double(v.z) > sea;
    };
    std::vector<Piece> pieces;
    std::vector<std::uint8_t> keep;   // per candidate vertex of the pieces, in piece order
    std::vector<std::uint32_t> kept;  // j of the lines with pieces (ids[j]), ascending
    ScoredLineSet out;
    // Pixels per metre at unit distance, per camera; an orthographic camera's are the same at
    // every depth, so its distances count as 1 (distance_to).
    std::vector<double> scale;
    for (const Camera& c : culling.cameras) scale.push_back(is_orthographic(c) ? 1.0 / world_per_pixel(c, 1.0) : lod_pixel_scale(c));
    const auto distance_to = [&](std::size_t c, const glm::dvec3& p) {
        return is_orthographic(culling.cameras[c]) ? 1.0 : glm::length(p - culling.cameras[c].eye);
    };
    // Whether some camera can show vertices [a, b) of v min_px long.
    const auto big_enough = [&](const DrapedVertex* v, std::uint32_t a, std::uint32_t b) {
        if (culling.cameras.empty()) return true;
        double length = 0.0;
        std::vector<double> nearest(culling.cameras.size(), 1e300);
        for (std::uint32_t i = a; i < b; ++i) {
            const glm::dvec3 p(v[i].x, v[i].y, e * double(v[i].z));
            if (i > a) length += glm::length(p - glm::dvec3(v[i - 1].x, v[i - 1].y, e * double(v[i - 1].z)));
            for (std::size_t c = 0; c < nearest.size(); ++c)
                nearest[c] = std::min(nearest[c], distance_to(c, p));
        }
        for (std::size_t c = 0; c < nearest.size(); ++c)
            if (length * scale[c] >= double(culling.min_px) * nearest[c]) return true;
        return false;
    };
    // Marks the vertices [a, b) of v to write: the piece's ends, the ends of its drawable part
    // [k, end) and, between them, a vertex only once it lies decimate_px pixels (as big_enough
    // measures) from the last one kept; returns how many.
    const auto mark = [&](const DrapedVertex* v, std::uint32_t a, std::uint32_t b, std::uint32_t k,
                          std::uint32_t end) {
        std::uint32_t n = 0;
        glm::dvec3 last(0.0);
        for (std::uint32_t i = a; i < b; ++i) {
            const glm::dvec3 p(v[i].x, v[i].y, e * double(v[i].z));
            bool write = culling.cameras.empty() || culling.decimate_px <= 0.0f || i <= k || i + 1 >= end;
            if (!write) {
                double step = 1e300;  // metres that project to decimate_px for the finest camera
                for (std::size_t c = 0; c < scale.size(); ++c)
                    step = std::min(step, double(culling.decimate_px) * distance_to(c, p) / scale[c]);
                write = glm::length(p - last) >= step;
            }
            keep.push_back(write);
            if (write) last = p, ++n;
        }
        return n;
    };
    // Lines no camera can show min_px long, by their records alone (their vertices never read): a
    // line's length at exaggeration e is at most max(1, e) times its stored (unexaggerated) 3-D
    // length, and every vertex is at least its plan box's plan distance from the eye, so a piece
    // of it that big_enough would keep passes this test too.
    const double stretch = std::max(1.0, e) * (1.0 + 1e-5);
    const auto may_show = [&](const DrapedLine& l) {
        if (culling.cameras.empty()) return true;
        for (std::size_t c = 0; c < scale.size(); ++c) {
            const glm::dvec3& eye = culling.cameras[c].eye;
            const double dx = std::max({double(l.lo.x) - eye.x, eye.x - double(l.hi.x), 0.0});
            const double dy = std::max({double(l.lo.y) - eye.y, eye.y - double(l.hi.y), 0.0});
            const double plan = is_orthographic(culling.cameras[c]) ? 1.0 : std::sqrt(dx * dx + dy * dy);
            if (stretch * double(l.length) * scale[c] >= double(culling.min_px) * plan) return true;
        }
        return false;
    };
    std::vector<std::uint32_t> all;
    for (std::size_t j = 0; j < ids.size(); ++j)
        if (may_show(lines[ids[j]])) all.push_back(std::uint32_t(j));
    std::uint32_t total = 0;
    for (std::size_t i0 = 0; i0 < all.size();) {
        const std::size_t i1 = batches.fetch(all, i0);
        for (std::size_t j = i0; j < i1; ++j) {
            const std::uint32_t id = all[j];  // lines[ids[id]]
            const DrapedLine& l = lines[ids[id]];
            const DrapedVertex* v = batches.vertices(j);
            for (std::uint32_t k = 0; k < l.count;) {  // lines_in_box's cut
                while (k < l.count && !inside(v[k])) ++k;
                if (k == l.count) break;
                std::uint32_t end = k;
                while (end < l.count && inside(v[end])) ++end;
                const std::uint32_t a = k > 0 ? k - 1 : k, b = std::min(end + 1, l.count);
                if (!big_enough(v, k, end)) {  // the drawable part: the vertices inside the box
                    k = end;
                    continue;
                }
                if (kept.empty() || kept.back() != id) kept.push_back(id);
                const std::size_t at = keep.size();
                const std::uint32_t n = mark(v, a, b, k, end);
                out.runs.push_back({total, n});
                pieces.push_back({std::uint32_t(kept.size() - 1), a, b, k, end, at});
                total += n;
                k = end;
            }
        }
        i0 = i1;
    }
    all = {};
    out.positions.resize(total), out.normals.resize(total), out.upload.resize(total), out.flow.resize(total);
    std::size_t p_begin = 0;
    for (std::size_t i0 = 0; i0 < kept.size();) {
        const std::size_t i1 = batches.fetch(kept, i0);
        std::size_t p_end = p_begin;
        while (p_end < pieces.size() && pieces[p_end].line < i1) ++p_end;
        parallel_chunks(p_end - p_begin, 2048, [&](std::size_t q0, std::size_t q1) {
            for (std::size_t p = p_begin + q0; p < p_begin + q1; ++p) {
                const Piece& piece = pieces[p];
                const DrapedVertex* line = batches.vertices(piece.line);
                std::uint32_t at = out.runs[p].first;
                for (std::uint32_t i = piece.from; i < piece.to; ++i) {
                    if (!keep[piece.keep + (i - piece.from)]) continue;
                    const DrapedVertex& v = line[i];
                    glm::vec3 n(0.0f);  // beyond the box: off the modelled surface
                    if (i >= piece.in0 && i < piece.in1) {
                        if (e == 1.0) n = {v.nx, v.ny, v.nz};
                        else if (v.nx != 0.0f || v.ny != 0.0f || v.nz != 0.0f)
                            n = glm::normalize(glm::vec3(float(e * v.nx), float(e * v.ny), v.nz));
                    }
                    const glm::vec3 pos(v.x, v.y, e == 1.0 ? v.z : float(e * double(v.z)));
                    out.positions[at] = pos, out.normals[at] = n;
                    DmVertex& dm = out.upload[at];
                    dm.position = pos, dm.flow = v.flow, dm.normal = n, dm.unused = 0.0f;
                    out.flow[at] = v.flow;
                    ++at;
                }
            }
        });
        p_begin = p_end, i0 = i1;
    }
    return out;
}

// Visible, scored runs of a line set as image strokes; with sketchiness, each run is perturbed
// within the surface's tangent planes (and repeated) before it is projected.
std::vector<Stroke> line_strokes(const ScoredLineSet& set, const std::vector<float>& scores,
                                 const Camera& camera, const std::string& kind, float sketch_px,
                                 int repeat, std::uint64_t seed, const std::vector<float>& weight) {
    if (sketch_px <= 0.0f && repeat <= 1)
        return scored_runs_to_strokes(set.positions, scores, set.runs, camera, kind, weight);
    std::vector<Stroke> out;
    for (const DrawnRun& run : drawn_runs(set.positions, scores, set.runs, camera)) {
        ObjectLine line;
        line.points = drawn_points(run, set.positions);
        const std::uint32_t first = run.run.first, last = run.run.first + run.run.count - 1;
        if (run.has_head) line.normals.push_back(set.normals[first]);
        for (std::uint32_t i = first; i <= last; ++i) line.normals.push_back(set.normals[i]);
        if (run.has_tail) line.normals.push_back(set.normals[last]);
        for (const glm::vec3& p : line.points) line.depth.push_back(float(eye_depth(camera, glm::dvec3(p))));
        const float strength = mean_score(scores, run.run);
        for (const ObjectLine& copy : sketch_object_copies(line, sketch_px, std::max(repeat, 1), camera, seed))
            out.push_back(project_stroke(copy.points, camera, strength, kind, drawn_values(run, weight)));
    }
    return out;
}

}  // namespace

float max_visible_distance(const DepthImage& toward) {
    float d = 0.0f;
    for (float t : toward.depth)
        if (std::isfinite(t)) d = std::max(d, t);
    return d;
}

LineBox line_box(const Terrain& model) {
    LineBox box;
    box.exaggeration = model.vertical_exaggeration;
    glm::dvec3 lo, hi;
    if (terrain_bounds(model, lo, hi)) box.lo = glm::vec2(lo), box.hi = glm::vec2(hi);
    return box;
}

DrainageLineData prepare_drainage_lines(const DrainageDb& db, const LineBox& box, const LineCulling& culling) {
    DrainageLineData data;
    if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y)) return data;
    for (const auto& [set, out] : {std::pair(&db.creases, &data.creases), std::pair(&db.ridges, &data.ridges)}) {
        const std::vector<std::uint32_t> ids = lines_meeting_box(*set, box.lo, box.hi);
        MemoryBatches batches{*set, ids};
        *out = select_lines(set->lines, ids, batches, box, culling);
    }
    return data;
}

DrainageLineData prepare_drainage_lines(const DrainageDb& db, const Terrain& model, const LineCulling& culling) {
    return prepare_drainage_lines(db, line_box(model), culling);
}

DrainageLineData prepare_drainage_lines(const DrainageLineSource& source, const LineBox& box,
                                        const LineCulling& culling) {
    if (!source.vertices.file) return prepare_drainage_lines(source.db, box, culling);
    DrainageLineData data;
    if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y)) return data;
    int which = 0;
    for (const auto& [set, out] :
         {std::pair(&source.db.creases, &data.creases), std::pair(&source.db.ridges, &data.ridges)}) {
        const std::vector<std::uint32_t> ids = lines_meeting_box(*set, box.lo, box.hi);
        // the vertices a batch at a time (batch_bytes, or one longer line): the memory held
        // follows the lines drawn, not those meeting the box
        FileBatches batches{*set, ids, source.vertices, which,
                            std::max<std::size_t>(source.batch_bytes / sizeof(DrapedVertex), 1), {}, {}};
        *out = select_lines(set->lines, ids, batches, box, culling);
        ++which;
    }
    return data;
}

DrainageLineData prepare_drainage_lines(const DrainageLineSource& source, const Terrain& model,
                                        const LineCulling& culling) {
    return prepare_drainage_lines(source, line_box(model), culling);
}

float line_culling_px(const Scene& scene) {
    const double spacing = std::min(scene.creases.spacing_px, scene.ridges.spacing_px);
    const double sketch = std::max(scene.crease_sketch_px, scene.ridge_sketch_px);
    const double margin = sketch > 0.0 ? 0.5 : 1.0;  // sketch offsets are sized at a line's mean depth
    return float(std::max(0.0, margin * (3.0 * spacing - 2.0 * sketch - 1.0)));
}

DrainageLines::DrainageLines(const GlApi& gl, DrainageLineData data)
    : creases_(std::move(data.creases)), ridges_(std::move(data.ridges)) {
    for (ScoredLineSet* set : {&creases_, &ridges_}) {
        set->pass = std::make_unique<DmPass>(gl, set->upload);
        set->upload = {};
    }
}

DrainageLines::DrainageLines(const GlApi& gl, const DrainageDb& db, const Terrain& model)
    : DrainageLines(gl, prepare_drainage_lines(db, model)) {}

namespace {

// The DM pass's scores under `p`; for "rank" the pass gives each weighted term alone (its weight 1,
// the others 0, no threshold) and -rs_min(d) (every weight 0), ranked on the CPU (lines/rank_scores.hpp).
double score_vertices(DmPass& pass, const DmFrame& frame, const CreaseParams& p, std::vector<float>& scores) {
    if (p.normalisation != ScoreNormalisation::rank) return pass.run(frame, p, scores);
    CreaseParams single = p;
    single.normalisation = ScoreNormalisation::paper;
    single.min_score = 0.0, single.distance_attenuation = 0.0;
    const std::array<double, 3> weights{p.slope_weight, p.illumination_weight, p.flow_weight};
    std::array<std::vector<float>, 3> terms;  // empty where the weight is 0 (not ranked)
    double ms = 0.0;
    for (int k = 0; k < 3; ++k) {
        if (weights[k] == 0.0) continue;
        single.slope_weight = k == 0, single.illumination_weight = k == 1, single.flow_weight = k == 2;
        ms += pass.run(frame, single, terms[k]);
    }
    CreaseParams threshold = p;
    threshold.normalisation = ScoreNormalisation::paper;
    threshold.slope_weight = threshold.illumination_weight = threshold.flow_weight = 0.0;
    std::vector<float> minus_rs_min;
    ms += pass.run(frame, threshold, minus_rs_min);
    scores = rank_scores(terms, minus_rs_min, weights, dm_hidden);
    return ms;
}

}  // namespace

void DrainageLines::draw(const Camera& camera, const Scene& scene, GLuint toward_texture,
                         float max_distance, Drawing& drawing, PassTimings& times) {
    DmFrame frame;
    frame.camera = &camera;
    frame.light = glm::vec3(light_vector(Light{scene.light.azimuth, scene.light.altitude}));
    frame.max_distance = max_distance;
    frame.toward_texture = toward_texture;
    struct LayerLines {
        const ScoredLineSet& set;
        const CreaseParams& params;
        LayerKind layer;
        const char* kind;
        float sketch_px;
        int repeat;
        double& ms;
    };
    for (const LayerLines& l : {LayerLines{creases_, scene.creases, LayerKind::creases, "crease", scene.crease_sketch_px,
                                           scene.crease_repeat, times.dm},
                                LayerLines{ridges_, scene.ridges, LayerKind::ridges, "ridge", scene.ridge_sketch_px,
                                           scene.ridge_repeat, times.ridges}}) {
        if (!l.params.enabled) continue;
        std::vector<float> scores;
        l.ms = score_vertices(*l.set.pass, frame, l.params, scores);
        const double per_metre = max_distance > 0.0f ? l.params.distance_attenuation / double(max_distance) : 0.0;
        whole_or_nothing_by_distance(scores, l.set.positions, l.set.runs, camera, per_metre);
        std::vector<float> weight;  // creases by flow (lines/stroke_weight.hpp)
        if (l.layer == LayerKind::creases)
            for (float f : l.set.flow) weight.push_back(flow_weight(f));
        drawing.layer(l.layer).strokes = thin_by_spacing(
            line_strokes(l.set, scores, camera, l.kind, l.sketch_px, l.repeat, scene.seed, weight),
            float(l.params.spacing_px));
    }
}

}  // namespace penink
