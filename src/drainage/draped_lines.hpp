// Building the creases and ridges the drainage database stores for drawing (line_set.hpp; Mower,
// "Concurrent Drainage Network Rendering": drainage vertices draped on the PN surface):
// 1. lines: the drainage stems (stems.hpp: drainage_stems, walked here on the network's cells,
//    the same vertices) and the basin divides (divide_polylines), vertices as the DrainageDb
//    holds them (x, y, z of the drainage point, normalised flow);
// 2. smoothing: the stems traced along the surface's fall line within a corridor of their cells
//    (fall_line_stems.hpp), the divides smoothed by a Gaussian along each line
//    (polyline_smoothing.hpp: gaussian_smooth) of three DEM cells; then each line end that sat on
//    another line's interior vertex (a tributary's junction; the same x, y bit for bit before
//    smoothing) is brought back to that vertex over the vertices next to it, over all the lines
//    of a set at once (a stem instead ends where its trace first comes within
//    FallLineOptions::meet of the line it joins, or where its trace ends: fall_line_stems.hpp),
//    and every vertex clamped to the plan box the set's vertices spanned before (the DEM's);
// 3. the divides moved across onto the PN surface's crest (ridge_crests.hpp) once the surface
//    below is made, their ends fixed;
// 4. draping: each vertex's z and unit normal from the PN surface of the full-resolution DEM
//    (dem_surface.hpp, no mesh of it; TerrainLocator's lookup on mesh_from_terrain bit for bit);
//    a vertex off the surface keeps its z and gets a zero normal; the creases on their lattice
//    (crease_lattice: each vertex's x, y snapped before it is draped, within the box step 2
//    clamps to, the rest once draped), so
//    their tile files code them in a few bytes a vertex and read back the same floats;
// 5. each line's plan box and length, and the set's spatial index (index_lines).
// Memory beyond the result (28 B a vertex, 28 B a line): while smoothing, the ends of the lines in
// a hash table with a bitmap of their hashes (19 B an end), and for the stems each vertex's grid
// cell and line (8 B a vertex); while the stems are walked, one block of 65536 stems' vertices
// in the threads' buffers; while draping, the DEM's node normals (12 B a node, dem_surface.hpp);
// never both at once.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "drainage/dem_surface.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/drainage_grid.hpp"
#include "drainage/fall_line_stems.hpp"
#include "drainage/flow_network.hpp"
#include "drainage/line_lattice.hpp"

namespace penink {

// Called with the fraction of a set's smoothing and draping done, in [0, 1] (from the calling
// thread).
using LineProgress = std::function<void(double fraction)>;

// Step 1 for the stems of a network: its drainage_stems, each vertex as build_branches would store
// it (x, y from grid_xy, z from g.z, normalised flow); each line's order is the Strahler order at
// its end (that of the branch the stem last runs through). Normals, boxes and index unset.
// `cells`, when given, gets each vertex's grid cell (index into g).
DrapedLineSet network_stems(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                            std::vector<std::uint32_t>* cells = nullptr);

// Step 1 for lines given as index lists into `vertices` (drainage_stems(db) and db.vertices,
// divide_polylines(db) and db.divide_vertices); orders 0.
DrapedLineSet listed_lines(const DvVertices& vertices, const std::vector<std::vector<std::uint32_t>>& lines);

// Step 2 for lines without grid cells (the divides; listed_lines): Gaussian smoothing of `sigma`
// vertices, then the ends joined.
void smooth_lines(DrapedLineSet& set, double sigma = 2.0);
// Step 2 for stems (network_stems with its cells): trace_fall_lines, then each stem ending at a
// junction ends where its trace first comes within options.meet cells of the line it joins (among
// its last 4 options.corridor vertices), else where its trace ends.
void smooth_stems(DrapedLineSet& set, const std::vector<std::uint32_t>& cells, const DrainageGrid& g,
                  const FallLineOptions& options);
// A lattice to drape on and the box the set was clamped to while smoothed (its vertices' box
// before smoothing), which its snapped vertices keep to.
struct DrapeLattice {
    LineLattice lattice;
    glm::vec2 lo, hi;
};
// Steps 4 and 5 on a smoothed set; with a lattice, each vertex snapped to it (snapped_vertex, in
// the box) before it is located (draped at the x, y it keeps) and again once draped.
void drape_lines(DrapedLineSet& set, const DemSurface& surface, const LineProgress& progress = {},
                 const DrapeLattice* lattice = nullptr);
// smooth_lines, then steps 4 and 5, on a set made by step 1.
void smooth_and_drape(DrapedLineSet& set, const DemSurface& surface, const LineProgress& progress = {});

// Whether the DEM's valid nodes differ in height (its own nodes: g's coarse nodes at factor > 1);
// false for a plane (every valid height equal) or no valid node.
bool has_relief(const DrainageGrid& g);

// Lines built for part of the DEM with the same per-line results as the whole set's build
// (build_draped_lines): a line's smoothing reads, besides its own vertices, those of the lines its
// ends join (step 2: the end matches) and the box of the whole set's vertices, so a part is built
// on the closure of its lines under "joins" (stems: one level, a stem ends against its trunk's
// trace; divides: four, the three rounds of join_ends and the final snap each read the joined
// line as the round before left it), the box taken from the whole set unsmoothed.
// One end's match: line `line`'s first (last = 0) or last (last = 1) vertex follows vertex
// `offset` of line `into` (end_matches on the whole set).
struct LineJoin {
    std::uint32_t line, last, into, offset;
    bool operator==(const LineJoin&) const = default;
};
// The whole set's joins, by line (CSR: line l's are joins[start[l], start[l + 1]), its first end's
// before its last), and the plan box of its vertices before smoothing (what clamping keeps to).
struct LineJoins {
    std::vector<std::uint32_t> start{0};
    std::vector<LineJoin> joins;
    glm::vec2 lo{0.0f}, hi{-1.0f};
    bool operator==(const LineJoins&) const = default;
};
// The joins of a set made by step 1 (network_stems, listed_lines), before smoothing.
LineJoins line_joins(const DrapedLineSet& set);
// `ids` (line ids, no repeats) followed by every line they reach through up to `depth` joins,
// each once, the added ones ascending.
std::vector<std::uint32_t> join_closure(const LineJoins& joins, const std::vector<std::uint32_t>& ids, int depth);

// What a part's stems need of the whole network, made in one pass over its cells: the stems'
// sources in cell order (stem s starts at cell sources[s]: network_stems' line order) and the box
// of all stems' vertices (every valid cell's drainage vertex), which the whole build clamps to.
struct StemParts {
    std::vector<std::uint32_t> sources;
    glm::vec2 lo{0.0f}, hi{-1.0f};
};
StemParts stem_parts(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net);
// FlowNetwork::mains of the network: for every junction (a cell two or more valid cells drain
// into), the bit of its main upstream cell (network_stems' rule: highest order, then larger flow
// just above the junction, then the branch with the least head), in mains_words(g.size()) words.
// The walks of for_each_stem_cells and crease_part read it instead of comparing the junction's
// inflows at every arrival.
std::vector<std::uint64_t> main_upstream_bits(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                                              const FlowNetwork& net);
inline std::size_t mains_words(std::size_t cells) { return (cells + 63) / 64; }
// Calls f(chunk, s, cells, xy, n) for each stem s of network_stems(g, dir, net) (parts.sources)
// with its n grid cells in stem order and their drainage vertices' x, y (the walk's: grid_xy
// rounded to floats), on all cores (f must be safe to call from several threads at
// once): the stems in consecutive chunks, chunk c (0, 1, ... in stem order, fewer than
// stem_chunks_most) visited in stem order on one thread. No stem's vertices are kept.
inline constexpr std::size_t stem_chunks_most = 17;
// With `cuts` (ascending stem ids), the stems [cuts[k], cuts[k + 1]) alone, range after range on
// one set-up walk (the junctions' mains found once), each range's chunks counted from its first
// stem and done(k) called once its stems are all visited.
void for_each_stem_cells(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                         const StemParts& parts,
                         const std::function<void(std::size_t, std::uint32_t, const std::uint32_t*, const glm::vec2*, std::uint32_t)>& f,
                         const std::vector<std::size_t>& cuts = {}, const std::function<void(std::size_t)>& done = {});
// The lattice the creases' vertices are draped on (line_lattice.hpp), by g's smaller cell side.
LineLattice crease_lattice(const DrainageGrid& g);
// Steps 1 to 5 for stems `ids` of network_stems(g, dir, net): the lines build_draped_lines stores
// for them in db.creases (vertices, order, box, length equal bit for bit), in the order of `ids`,
// indexed. A stem's join is found on the network: the stem it joins is the one through its end
// junction (up the junction's main upstream cells to their source), its vertex the junction's
// (end_matches' x, y match, where every cell has its own x, y). On a DEM without relief
// (has_relief) the whole build keeps no lines: ask for none there. Draped on crease_lattice(g),
// as build_draped_lines drapes db.creases.
DrapedLineSet crease_part(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                          const DemSurface& surface, const StemParts& parts, const std::vector<std::uint32_t>& ids);
// The same for divides `ids` of `listed` (listed_lines of the database's divides, unsmoothed;
// joins: line_joins(listed)): the lines build_draped_lines stores for them in db.ridges.
DrapedLineSet ridge_part(const DrainageGrid& g, const DemSurface& surface, const DrapedLineSet& listed,
                         const LineJoins& joins, const std::vector<std::uint32_t>& ids);

// Both sets of a built network into db.creases and db.ridges (the divides from db.divides and
// db.divide_vertices), on the DEM of `g` (DemSurface(g): g.z must hold the original elevations).
// On a DEM without relief (has_relief) both sets are empty: a plane has no creases nor ridges.
// `progress` gets the fraction of the two sets done.
void build_draped_lines(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net,
                        DrainageDb& db, const LineProgress& progress = {});
// The ridges alone (db.ridges as build_draped_lines gives them), for a database whose creases are
// built where a frame needs them (crease_source.hpp). `surface`: DemSurface(g) made before (none:
// made here).
void build_draped_ridges(const DrainageGrid& g, DrainageDb& db, const LineProgress& progress = {},
                         const DemSurface* surface = nullptr);

}  // namespace penink
