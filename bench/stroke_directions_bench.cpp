// Direction measures of the creases and ridges the drainage database stores (lines/
// stroke_directions.hpp), in plan, with the build's time: for each DEM given, the database is
// built in process (build_drainage_db, the automatic resample factor; best of REPEAT builds,
// default 1) and its crease and ridge polylines measured against the DEM's fall line: share of
// length within 1 degree of the 8 grid directions, and the length-weighted median and 90th
// percentile of each segment's angle to the fall line where the slope exceeds 5 degrees.
// Usage: stroke_directions_bench DEM... (REPEAT=n in the environment; MIN_ORDER=k: only the
// stems of Strahler order k or more, what a drawing keeps of them; ENDS=n: also the measures of
// the first n vertices of each line, its last n and the rest apart).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "drainage/drainage_build.hpp"
#include "input/dem_reader.hpp"
#include "lines/stroke_directions.hpp"

using namespace penink;

namespace {

// The lines of Strahler order >= min_order (divides: all) in plan; part 0: whole lines, 1: the
// `ends` vertices at either end, 2: the rest.
std::vector<std::vector<glm::dvec2>> plan_lines(const DrapedLineSet& set, int min_order, int part = 0,
                                                std::uint32_t ends = 0) {
    std::vector<std::vector<glm::dvec2>> out;
    out.reserve(set.lines.size());
    for (const DrapedLine& l : set.lines) {
        if (l.order && l.order < min_order) continue;
        std::vector<glm::dvec2> p;
        p.reserve(l.count);
        for (std::uint32_t k = 0; k < l.count; ++k) {
            const bool near_end = part == 3 ? k < ends : part == 4 ? k + ends >= l.count : k < ends || k + ends >= l.count;
            if (part != 0 && part != 2 && !near_end) {
                if (p.size() > 1) out.push_back(std::move(p));
                p.clear();
                continue;
            }
            if (part == 2 && near_end) continue;
            const DrapedVertex& v = set.vertices[l.first + k];
            p.emplace_back(v.x, v.y);
        }
        out.push_back(std::move(p));
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: stroke_directions_bench DEM...\n");
        return 2;
    }
    const int min_order = std::getenv("MIN_ORDER") ? std::atoi(std::getenv("MIN_ORDER")) : 1;
    const int repeat = std::getenv("REPEAT") ? std::max(1, std::atoi(std::getenv("REPEAT"))) : 1;
    std::printf("%-28s %-7s %8s %10s %10s %10s %9s\n", "DEM", "layer", "lines", "grid share", "fall med", "fall p90",
                "build s");
    for (int a = 1; a < argc; ++a) {
        const Terrain t = read_dem(argv[a]);
        DrainageDb db;
        double best = 1e30;
        for (int r = 0; r < repeat; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            db = build_drainage_db(t, {});
            best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        const FallLineField field(t);
        for (const auto& [name, set] : {std::pair<const char*, const DrapedLineSet*>{"creases", &db.creases},
                                        std::pair<const char*, const DrapedLineSet*>{"ridges", &db.ridges}}) {
            const StrokeDirections d = stroke_directions(plan_lines(*set, min_order), field);
            std::printf("%-28s %-7s %8zu %10.3f %9.1f° %9.1f° %9.3f\n", argv[a], name, set->lines.size(), d.grid_share(),
                        d.fall_median_deg, d.fall_p90_deg, best);
            if (const char* e = std::getenv("ENDS")) {  // the measures near the lines' ends and elsewhere
                const std::uint32_t n = std::uint32_t(std::atoi(e));
                for (int part : {3, 4, 2}) {
                    const StrokeDirections p = stroke_directions(plan_lines(*set, min_order, part, n), field);
                    std::printf("  %s %u vertices: length share %.3f, grid share %.3f, fall median %.1f°, p90 %.1f°\n",
                                part == 3 ? "first" : part == 4 ? "last" : "beyond", n, p.length / std::max(d.length, 1e-30), p.grid_share(),
                                p.fall_median_deg, p.fall_p90_deg);
                }
            }
        }
    }
    return 0;
}
