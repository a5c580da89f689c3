#include "drainage/stems.hpp"

namespace penink {

namespace {

// Flow of an upstream branch just above its end junction: its last vertex is the shared junction
// (same flow for every branch joining there), so the one before it.
float flow_above_junction(const DrainageDb& db, const DvBranch& up) {
    const std::uint32_t k = up.count >= 2 ? up.count - 2 : 0;
    return db.vertices[up.first + k].flow;
}

// The upstream branch a branch continues: highest order, then larger flow above the junction.
std::vector<std::int32_t> main_upstream(const DrainageDb& db) {
    std::vector<std::int32_t> main(db.branches.size(), -1);
    for (std::size_t b = 0; b < db.branches.size(); ++b) {
        const DvBranch& br = db.branches[b];
        float best_flow = -1.0f;
        int best_order = -1;
        for (std::uint32_t k = 0; k < br.up_count; ++k) {
            const std::uint32_t u = db.upstream[br.up_first + k];
            const DvBranch& up = db.branches[u];
            const float flow = flow_above_junction(db, up);
            if (up.order > best_order || (up.order == best_order && flow > best_flow)) {
                best_order = up.order, best_flow = flow, main[b] = std::int32_t(u);
            }
        }
    }
    return main;
}

void append_branch(const DrainageDb& db, std::uint32_t b, std::vector<std::uint32_t>& stem) {
    const DvBranch& br = db.branches[b];
    for (std::uint32_t i = br.first; i < br.first + br.count; ++i) {
        if (!stem.empty()) {
            const DvVertex &last = db.vertices[stem.back()], &v = db.vertices[i];
            if (last.x == v.x && last.y == v.y) continue;  // the shared junction vertex
        }
        stem.push_back(i);
    }
}

}  // namespace

std::vector<std::vector<std::uint32_t>> drainage_stems(const DrainageDb& db) {
    const std::vector<std::int32_t> main = main_upstream(db);
    std::vector<std::vector<std::uint32_t>> stems;
    for (std::uint32_t b = 0; b < db.branches.size(); ++b) {
        if (db.branches[b].up_count != 0) continue;  // stems start at sources
        std::vector<std::uint32_t> stem;
        std::uint32_t cur = b;
        append_branch(db, cur, stem);
        for (std::int32_t d = db.branches[cur].downstream; d >= 0 && main[std::size_t(d)] == std::int32_t(cur);
             d = db.branches[cur].downstream) {
            cur = std::uint32_t(d);
            append_branch(db, cur, stem);
        }
        stems.push_back(std::move(stem));
    }
    return stems;
}

std::vector<std::vector<std::uint32_t>> divide_polylines(const DrainageDb& db) {
    const std::vector<DvPolyline>& lines = db.divides;
    std::vector<std::vector<std::uint32_t>> out;
    for (const DvPolyline& l : lines) {
        out.emplace_back(l.count);
        for (std::uint32_t k = 0; k < l.count; ++k) out.back()[k] = l.first + k;
    }
    return out;
}

std::vector<std::vector<std::uint32_t>> lines_in_box(const std::vector<std::vector<std::uint32_t>>& lines,
                                                     const DvVertices& v, glm::vec2 lo, glm::vec2 hi) {
    std::vector<std::vector<std::uint32_t>> out;
    const auto inside = [&](std::uint32_t i) {
        return v[i].x >= lo.x && v[i].x <= hi.x && v[i].y >= lo.y && v[i].y <= hi.y;
    };
    for (const auto& line : lines) {
        std::size_t k = 0;
        while (k < line.size()) {
            while (k < line.size() && !inside(line[k])) ++k;
            if (k == line.size()) break;
            std::size_t end = k;
            while (end < line.size() && inside(line[end])) ++end;
            const std::size_t a = k > 0 ? k - 1 : k, b = std::min(end + 1, line.size());
            out.emplace_back(line.begin() + std::ptrdiff_t(a), line.begin() + std::ptrdiff_t(b));
            k = end;
        }
    }
    return out;
}

}  // namespace penink
