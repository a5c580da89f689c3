#include "drainage/line_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/parallel_chunks.hpp"
#include "drainage/stored_creases.hpp"
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

// Screen-size bounds of the culling cameras (LineCulling): pixels per metre at unit distance per
// camera; an orthographic camera's are the same at every depth, so its distances count as 1.
class ScreenSize {
public:
    ScreenSize(const LineCulling& culling, double e) : culling_(culling), e_(e) {
        for (const Camera& c : culling.cameras)
            scale_.push_back(is_orthographic(c) ? 1.0 / world_per_pixel(c, 1.0) : lod_pixel_scale(c));
    }
    bool culls() const { return !culling_.cameras.empty(); }
    glm::dvec3 point(const DrapedVertex& v) const { return {v.x, v.y, e_ * double(v.z)}; }

    // Whether some camera can show vertices [a, b) of v min_px long.
    bool big_enough(const DrapedVertex* v, std::uint32_t a, std::uint32_t b) const {
        if (!culls()) return true;
        double length = 0.0;
        std::vector<double> nearest(culling_.cameras.size(), 1e300);
        for (std::uint32_t i = a; i < b; ++i) {
            const glm::dvec3 p = point(v[i]);
            if (i > a) length += glm::length(p - point(v[i - 1]));
            for (std::size_t c = 0; c < nearest.size(); ++c) nearest[c] = std::min(nearest[c], distance_to(c, p));
        }
        for (std::size_t c = 0; c < nearest.size(); ++c)
            if (length * scale_[c] >= double(culling_.min_px) * nearest[c]) return true;
        return false;
    }

    // Lines no camera can show min_px long, by their records alone (their vertices never read): a
    // line's length at exaggeration e is at most max(1, e) times its stored (unexaggerated) 3-D
    // length, and every vertex is at least its plan box's plan distance from the eye, so a piece
    // of it that big_enough would keep passes this test too.
    bool may_show(const DrapedLine& l) const {
        return may_show(l.lo, l.hi, std::max(1.0, e_) * slack * double(l.length));
    }
    // The same for a stem's bound (crease_tiles.hpp): its exaggerated length at most plan + e rise,
    // and no vertex higher than e z_top, so a camera whose eye is higher sees every vertex at least
    // that height difference below it besides the plan distance.
    bool may_show(const StemBound& b, glm::vec2 lo, glm::vec2 hi, float z_top) const {
        return may_show(lo, hi, slack * stem_bound_length(b, e_), double(z_top));
    }
    // Whether some camera can show min_px long a line of exaggerated length at most `length` (with
    // the rounding slack) in the plan box [lo, hi], its vertices no higher than e z_top.
    bool may_show(glm::vec2 lo, glm::vec2 hi, double length,
                  double z_top = std::numeric_limits<double>::infinity()) const {
        if (!culls()) return true;
        for (std::size_t c = 0; c < scale_.size(); ++c)
            if (length * scale_[c] >= double(culling_.min_px) * box_distance(c, lo, hi, z_top)) return true;
        return false;
    }

    // The spacing (metres, unexaggerated 3-D) of a line's vertices that keeps() cannot tell from
    // every vertex anywhere in the plan box [lo, hi] below e z_top: the decimation step at the
    // box's nearest point for the finest camera over max(1, e) (an exaggerated step is at most
    // max(1, e) times the unexaggerated one); 0 without decimation (CreaseTiles::LineDetail).
    double detail(glm::vec2 lo, glm::vec2 hi, double z_top) const {
        if (!culls() || culling_.decimate_px <= 0.0f) return 0.0;
        double step = 1e300;
        for (std::size_t c = 0; c < scale_.size(); ++c)
            step = std::min(step, double(culling_.decimate_px) * box_distance(c, lo, hi, z_top) / scale_[c]);
        return step / std::max(1.0, e_);
    }

    // Whether vertex p (i of a piece whose drawable part is [k, end)) is written after `last`:
    // always without decimation and at the drawable part's ends, else once it lies decimate_px
    // pixels from the last one kept for the finest camera.
    bool keeps(const glm::dvec3& p, const glm::dvec3& last, bool at_end) const {
        if (!culls() || culling_.decimate_px <= 0.0f || at_end) return true;
        double step = 1e300;  // metres that project to decimate_px for the finest camera
        for (std::size_t c = 0; c < scale_.size(); ++c)
            step = std::min(step, double(culling_.decimate_px) * distance_to(c, p) / scale_[c]);
        return glm::length(p - last) >= step;
    }

private:
    static constexpr double slack = 1.0 + 1e-5;  // float rounding of the lengths
    double distance_to(std::size_t c, const glm::dvec3& p) const {
        return is_orthographic(culling_.cameras[c]) ? 1.0 : glm::length(p - culling_.cameras[c].eye);
    }
    // The least distance_to of a point of the plan box [lo, hi] no higher than e z_top.
    double box_distance(std::size_t c, glm::vec2 lo, glm::vec2 hi, double z_top) const {
        if (is_orthographic(culling_.cameras[c])) return 1.0;
        const glm::dvec3& eye = culling_.cameras[c].eye;
        const double dx = std::max({double(lo.x) - eye.x, eye.x - double(hi.x), 0.0});
        const double dy = std::max({double(lo.y) - eye.y, eye.y - double(hi.y), 0.0});
        const double dz = std::max(0.0, eye.z - e_ * z_top);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    const LineCulling& culling_;
    double e_;
    std::vector<double> scale_;
};

// Where the pieces are: found line by line before any vertex is written.
struct PieceLayout {
    struct Piece {
        std::uint32_t line;      // index into `kept` (the lines with pieces)
        std::uint32_t from, to;  // the line's vertices [from, to) of the piece
        std::uint32_t in0, in1;  // those inside the box: [in0, in1)
        std::size_t keep;        // keep[piece.keep + (i - from)]: vertex i is written
    };
    std::vector<Piece> pieces;
    std::vector<std::uint8_t> keep;   // per candidate vertex of the pieces, in piece order
    std::vector<std::uint32_t> kept;  // j of the lines with pieces (ids[j]), ascending
    std::vector<VertexRun> runs;      // per piece, where its written vertices go
    std::uint32_t total = 0;          // vertices written
};

// Marks the vertices [a, b) of v to write: the piece's ends, the ends of its drawable part
// [k, end) and, between them, those the screen size keeps; returns how many.
std::uint32_t mark_vertices(const DrapedVertex* v, std::uint32_t a, std::uint32_t b, std::uint32_t k, std::uint32_t end,
                            const ScreenSize& size, std::vector<std::uint8_t>& keep) {
    std::uint32_t n = 0;
    glm::dvec3 last(0.0);
    for (std::uint32_t i = a; i < b; ++i) {
        const glm::dvec3 p = size.point(v[i]);
        const bool write = size.keeps(p, last, i <= k || i + 1 >= end);
        keep.push_back(write);
        if (write) last = p, ++n;
    }
    return n;
}

// The pieces of lines ids[j] (lines_in_box's cut: the runs inside the box, with one vertex beyond
// it at each cut) that the screen size keeps, batch by batch.
template <class Batches>
PieceLayout find_pieces(const std::vector<DrapedLine>& lines, const std::vector<std::uint32_t>& ids, Batches& batches,
                        const LineBox& box, const ScreenSize& size) {
    const glm::vec2 lo = box.lo, hi = box.hi;
    const double sea = box.sea_level;
    const auto inside = [&](const DrapedVertex& v) {
        return v.x >= lo.x && v.x <= hi.x && v.y >= lo.y && v.y <= hi.y && double(v.z) > sea;
    };
    PieceLayout out;
    std::vector<std::uint32_t> all;
    for (std::size_t j = 0; j < ids.size(); ++j)
        if (size.may_show(lines[ids[j]])) all.push_back(std::uint32_t(j));
    for (std::size_t i0 = 0; i0 < all.size();) {
        const std::size_t i1 = batches.fetch(all, i0);
        for (std::size_t j = i0; j < i1; ++j) {
            const std::uint32_t id = all[j];  // lines[ids[id]]
            const DrapedLine& l = lines[ids[id]];
            const DrapedVertex* v = batches.vertices(j);
            for (std::uint32_t k = 0; k < l.count;) {
                while (k < l.count && !inside(v[k])) ++k;
                if (k == l.count) break;
                std::uint32_t end = k;
                while (end < l.count && inside(v[end])) ++end;
                const std::uint32_t a = k > 0 ? k - 1 : k, b = std::min(end + 1, l.count);
                if (!size.big_enough(v, k, end)) {  // the drawable part: the vertices inside the box
                    k = end;
                    continue;
                }
                if (out.kept.empty() || out.kept.back() != id) out.kept.push_back(id);
                const std::size_t at = out.keep.size();
                const std::uint32_t n = mark_vertices(v, a, b, k, end, size, out.keep);
                out.runs.push_back({out.total, n});
                out.pieces.push_back({std::uint32_t(out.kept.size() - 1), a, b, k, end, at});
                out.total += n;
                k = end;
            }
        }
        i0 = i1;
    }
    return out;
}

// The marked vertices of the pieces, exaggerated by e, written on all cores batch by batch over
// the lines that have pieces (normal' = normalize(e nx, e ny, nz); zero beyond the box).
template <class Batches>
void write_pieces(const PieceLayout& layout, Batches& batches, double e, ScoredLineSet& out) {
    out.positions.resize(layout.total), out.normals.resize(layout.total);
    out.flow.resize(layout.total);
    std::size_t p_begin = 0;
    for (std::size_t i0 = 0; i0 < layout.kept.size();) {
        const std::size_t i1 = batches.fetch(layout.kept, i0);
        std::size_t p_end = p_begin;
        while (p_end < layout.pieces.size() && layout.pieces[p_end].line < i1) ++p_end;
        parallel_chunks(p_end - p_begin, 2048, [&](std::size_t q0, std::size_t q1) {
            for (std::size_t p = p_begin + q0; p < p_begin + q1; ++p) {
                const PieceLayout::Piece& piece = layout.pieces[p];
                const DrapedVertex* line = batches.vertices(piece.line);
                std::uint32_t at = layout.runs[p].first;
                for (std::uint32_t i = piece.from; i < piece.to; ++i) {
                    if (!layout.keep[piece.keep + (i - piece.from)]) continue;
                    const DrapedVertex& v = line[i];
                    glm::vec3 n(0.0f);  // beyond the box: off the modelled surface
                    if (i >= piece.in0 && i < piece.in1) {
                        if (e == 1.0) n = {v.nx, v.ny, v.nz};
                        else if (v.nx != 0.0f || v.ny != 0.0f || v.nz != 0.0f)
                            n = glm::normalize(glm::vec3(float(e * v.nx), float(e * v.ny), v.nz));
                    }
                    const glm::vec3 pos(v.x, v.y, e == 1.0 ? v.z : float(e * double(v.z)));
                    out.positions[at] = pos, out.normals[at] = n, out.flow[at] = v.flow;
                    ++at;
                }
            }
        });
        p_begin = p_end, i0 = i1;
    }
}

// The pieces of lines `ids` (ascending ids of lines meeting the box) laid out for a DM pass (see
// prepare_drainage_lines).
template <class Batches>
ScoredLineSet select_lines(const std::vector<DrapedLine>& lines, const std::vector<std::uint32_t>& ids,
                           Batches& batches, const LineBox& box, const LineCulling& culling) {
    const ScreenSize size(culling, box.exaggeration);
    PieceLayout layout = find_pieces(lines, ids, batches, box, size);
    ScoredLineSet out;
    write_pieces(layout, batches, box.exaggeration, out);
    out.runs = std::move(layout.runs);
    return out;
}

}  // namespace

LineBox line_box(const Terrain& model) {
    LineBox box;
    box.exaggeration = model.vertical_exaggeration;
    glm::dvec3 lo, hi;
    if (terrain_bounds(model, lo, hi)) box.lo = glm::vec2(lo), box.hi = glm::vec2(hi);
    return box;
}

namespace {

// `part`'s runs and vertices after `out`'s.
void append_lines(ScoredLineSet& out, ScoredLineSet part) {
    if (out.positions.empty() && out.runs.empty()) {
        out = std::move(part);
        return;
    }
    const auto base = std::uint32_t(out.positions.size());
    for (VertexRun r : part.runs) r.first += base, out.runs.push_back(r);
    out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
    out.normals.insert(out.normals.end(), part.normals.begin(), part.normals.end());
    out.flow.insert(out.flow.end(), part.flow.begin(), part.flow.end());
}

// Lines kept in crease tiles (StoredCreases::line_refs_by_row): records and a pointer to each
// line's vertices.
struct RefBatches {
    const CreaseTiles::LineRefs& refs;
    const std::vector<std::uint32_t>& ids;
    const std::vector<std::uint32_t>* list = nullptr;
    std::size_t fetch(const std::vector<std::uint32_t>& l, std::size_t) { return list = &l, l.size(); }
    const DrapedVertex* vertices(std::size_t i) const { return refs.vertices[ids[(*list)[i]]]; }
};

// Where the database stores the creases' source: out = the creases selected from those built
// (or read) for the box by `stored` (made here from db when none), their vertices not copied;
// false where db holds its creases.
bool select_stored_creases(const DrainageDb& db, StoredCreases* stored, const LineBox& box, const LineCulling& culling,
                           ScoredLineSet& out) {
    if (!stored && !db.has_crease_source()) return false;
    std::shared_ptr<StoredCreases> local;
    if (!stored) stored = (local = StoredCreases::of(db)).get();
    // only the stems whose bound some culling camera can show min_px long (ScreenSize::may_show
    // on the bound: a crease failing it would be culled line by line anyway)
    const ScreenSize size(culling, box.exaggeration);
    CreaseTiles::LineTest may_show;
    if (size.culls())
        may_show = [&size](const StemBound& b, glm::vec2 lo, glm::vec2 hi, float z_top) {
            return size.may_show(b, lo, hi, z_top);
        };
    CreaseTiles::LineDetail detail;  // each unit's lines as thinned as the pieces' decimation allows there
    if (size.culls())
        detail = [&size](glm::vec2 lo, glm::vec2 hi, float z_top) { return size.detail(lo, hi, double(z_top)); };
    // a row of tiles at a time, each row's pieces appended after the row before's (the stems in
    // the order one query gives them): the lines held are a row's, the pieces the frame's
    out = ScoredLineSet{};
    stored->line_refs_by_row(box.lo, box.hi, may_show, detail, [&](CreaseTiles::LineRefs refs) {
        std::vector<std::uint32_t> ids;  // those meeting the box, ascending (what lines_meeting_box gives)
        for (std::uint32_t i = 0; i < refs.lines.size(); ++i) {
            const DrapedLine& l = refs.lines[i];
            if (l.lo.x <= box.hi.x && l.hi.x >= box.lo.x && l.lo.y <= box.hi.y && l.hi.y >= box.lo.y) ids.push_back(i);
        }
        RefBatches batches{refs, ids};
        append_lines(out, select_lines(refs.lines, ids, batches, box, culling));
    });
    return true;
}

DrainageLineData prepare_from_memory(const DrainageDb& db, StoredCreases* stored, const LineBox& box,
                                     const LineCulling& culling) {
    DrainageLineData data;
    if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y)) return data;
    const bool stored_creases = select_stored_creases(db, stored, box, culling, data.creases);
    for (const auto& [set, out] : {std::pair(&db.creases, &data.creases), std::pair(&db.ridges, &data.ridges)}) {
        if (out == &data.creases && stored_creases) continue;
        const std::vector<std::uint32_t> ids = lines_meeting_box(*set, box.lo, box.hi);
        MemoryBatches batches{*set, ids};
        *out = select_lines(set->lines, ids, batches, box, culling);
    }
    return data;
}

}  // namespace

DrainageLineData prepare_drainage_lines(const DrainageDb& db, const LineBox& box, const LineCulling& culling) {
    return prepare_from_memory(db, nullptr, box, culling);
}

DrainageLineData prepare_drainage_lines(const DrainageDb& db, const Terrain& model, const LineCulling& culling) {
    return prepare_drainage_lines(db, line_box(model), culling);
}

DrainageLineData prepare_drainage_lines(const DrainageLineSource& source, const LineBox& box,
                                        const LineCulling& culling) {
    if (!source.vertices.file) return prepare_from_memory(source.db, source.creases.get(), box, culling);
    DrainageLineData data;
    if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y)) return data;
    int which = 0;
    try {
        const bool stored_creases = select_stored_creases(source.db, source.creases.get(), box, culling, data.creases);
        for (const auto& [set, out] :
             {std::pair(&source.db.creases, &data.creases), std::pair(&source.db.ridges, &data.ridges)}) {
            if (out == &data.creases && stored_creases) {
                ++which;
                continue;
            }
            const std::vector<std::uint32_t> ids = lines_meeting_box(*set, box.lo, box.hi);
            // the vertices a batch at a time (batch_bytes, or one longer line): the memory held
            // follows the lines drawn, not those meeting the box
            FileBatches batches{*set, ids, source.vertices, which,
                                std::max<std::size_t>(source.batch_bytes / sizeof(DrapedVertex), 1), {}, {}};
            *out = select_lines(set->lines, ids, batches, box, culling);
            ++which;
        }
    } catch (const DvCorrupt&) {
        if (!source.read_whole) throw;
        return prepare_drainage_lines(source.read_whole(), box, culling);
    }
    return data;
}

DrainageLineData prepare_drainage_lines(const DrainageLineSource& source, const Terrain& model,
                                        const LineCulling& culling) {
    return prepare_drainage_lines(source, line_box(model), culling);
}

}  // namespace penink
