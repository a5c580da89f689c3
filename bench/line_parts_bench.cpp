// What building the drainage lines by parts costs against the whole build (draped_lines.hpp:
// crease_part, ridge_part, build_draped_lines), on a DEM at a given resample factor:
// - the whole build of creases and ridges;
// - what a part's build needs of the whole set, made once: the stems' sources and box, the
//   divides listed and their joins, the PN surface's normals;
// - for tiles of T x T cells (stems by their source cell), the tile at the grid's centre built
//   alone, and every tile built one after the other (the closure's repeated lines and the per-part
//   passes are the overhead over the whole build);
// - CreaseTiles (256-cell tiles): made once, a box of a tenth of the DEM's side at its centre,
//   then the whole DEM.
// Usage: line_parts_bench DEM [factor (default 1)] [tile sizes... (default 64 128 256 512)]
// Wall seconds, best of 3 for the single tile.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <glm/common.hpp>

#include "drainage/crease_tiles.hpp"
#include "drainage/dem_surface.hpp"
#include "drainage/draped_lines.hpp"
#include "drainage/drainage_build.hpp"
#include "drainage/stems.hpp"
#include "input/dem_reader.hpp"

namespace penink {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s DEM [factor] [tile sizes...]\n", argv[0]);
        return 2;
    }
    const int factor = argc > 2 ? std::atoi(argv[2]) : 1;
    std::vector<std::uint32_t> tiles;
    for (int i = 3; i < argc; ++i) tiles.push_back(std::uint32_t(std::atoi(argv[i])));
    if (tiles.empty()) tiles = {64, 128, 256, 512};
    Terrain t = read_dem(argv[1]);
    DrainageGrid g = resample_pn(t, factor);
    DrainageResult res;
    DrainageDb db = drainage_db_from_grid(g, {}, &res);  // the whole build timed again below
    std::printf("grid %dx%d (factor %d)\n", g.cols, g.rows, g.factor);

    auto t0 = std::chrono::steady_clock::now();
    build_draped_lines(g, res.dir, res.net, db);
    std::printf("whole build: %.3f s (%zu stems, %zu divides)\n", seconds_since(t0), db.creases.lines.size(),
                db.ridges.lines.size());

    t0 = std::chrono::steady_clock::now();
    const StemParts stems_of = stem_parts(g, res.dir, res.net);
    const std::vector<std::uint32_t>& sources = stems_of.sources;
    std::printf("made once: stems' sources and box %.3f s\n", seconds_since(t0));
    t0 = std::chrono::steady_clock::now();
    const DrapedLineSet listed = listed_lines(db.divide_vertices, divide_polylines(db));
    const LineJoins divide_joins = line_joins(listed);
    std::printf("made once: divides listed and their joins %.3f s\n", seconds_since(t0));
    t0 = std::chrono::steady_clock::now();
    const DemSurface surface(g);
    std::printf("made once: surface normals %.3f s\n", seconds_since(t0));

    std::vector<std::uint32_t> all_divides(listed.lines.size());
    for (std::uint32_t i = 0; i < all_divides.size(); ++i) all_divides[i] = i;
    t0 = std::chrono::steady_clock::now();
    const DrapedLineSet ridges = ridge_part(g, surface, listed, divide_joins, all_divides);
    std::printf("every divide as one part: %.3f s (%zu lines)\n", seconds_since(t0), ridges.lines.size());

    for (std::uint32_t tile : tiles) {
        const std::uint32_t tx = (std::uint32_t(g.cols) + tile - 1) / tile, ty = (std::uint32_t(g.rows) + tile - 1) / tile;
        std::vector<std::vector<std::uint32_t>> parts(std::size_t(tx) * ty);
        for (std::uint32_t s = 0; s < sources.size(); ++s) {
            const std::uint32_t c = sources[s] % std::uint32_t(g.cols), r = sources[s] / std::uint32_t(g.cols);
            parts[(r / tile) * tx + c / tile].push_back(s);
        }
        const std::size_t centre = (ty / 2) * tx + tx / 2;
        double best = 1e30;
        std::size_t lines = 0, vertices = 0;
        for (int k = 0; k < 3; ++k) {
            t0 = std::chrono::steady_clock::now();
            const DrapedLineSet part = crease_part(g, res.dir, res.net, surface, stems_of, parts[centre]);
            best = std::min(best, seconds_since(t0));
            lines = part.lines.size(), vertices = part.vertices.size();
        }
        t0 = std::chrono::steady_clock::now();
        std::size_t total_vertices = 0;
        for (const auto& ids : parts)
            if (!ids.empty())
                total_vertices += crease_part(g, res.dir, res.net, surface, stems_of, ids).vertices.size();
        std::printf("tiles of %u cells (%ux%u): centre tile %.4f s (%zu stems, %zu vertices); every tile %.3f s "
                    "(%zu vertices)\n",
                    tile, tx, ty, best, lines, vertices, seconds_since(t0), total_vertices);
    }
    // the tiles a frame needs (crease_tiles.hpp, 256-cell tiles): made once, then a box of a
    // tenth of the DEM's side at its centre, then the whole DEM
    t0 = std::chrono::steady_clock::now();
    CreaseTiles crease_tiles(g, res.dir, res.net);
    std::printf("crease tiles: made in %.3f s (%zu tiles)\n", seconds_since(t0), crease_tiles.tile_count());
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const DrapedLine& l : db.creases.lines) lo = glm::min(lo, l.lo), hi = glm::max(hi, l.hi);
    const glm::vec2 c = 0.5f * (lo + hi), half = 0.05f * (hi - lo);
    t0 = std::chrono::steady_clock::now();
    std::size_t n = crease_tiles.lines_for_box(c - half, c + half).lines.size();
    std::printf("crease tiles: a box of a tenth of the side %.3f s (%zu stems built, %zu lines)\n", seconds_since(t0),
                crease_tiles.stems_built(), n);
    t0 = std::chrono::steady_clock::now();
    n = crease_tiles.lines_for_box(lo, hi).lines.size();
    std::printf("crease tiles: then the whole DEM %.3f s (%zu stems built, %zu lines)\n", seconds_since(t0),
                crease_tiles.stems_built(), n);
    return 0;
}

}  // namespace
}  // namespace penink

int main(int argc, char** argv) { return penink::run(argc, argv); }
