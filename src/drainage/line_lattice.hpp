// The lattice the crease lines' vertices are made on (draped_lines.hpp: crease_part and
// build_draped_lines drape each vertex at its x, y snapped to it, kept in the box the creases are
// clamped to, then snap the rest), so that a tile file codes each vertex as a few small integers
// (line_tile_files.hpp) and a line read from a file is bit for bit the line the building process
// drew from memory.
// - x, y: integer multiples of 2^plan_exp metres, the largest power of two at most 1/64 of the
//   drainage grid's smaller cell side (a vertex moves by at most 1/128 of a cell in each of x, y,
//   1/64 where the box's edge turns it back: 0.016 px where a cell is drawn a pixel wide, half a
//   pixel only where a cell spans 32 or more);
// - z: integer multiples of 2^z_exp = 2^plan_exp / 2 metres (at most 1/256 of a cell, so at the
//   exaggeration 2 it moves as little as x and y);
// - the unit normal (upward: nz >= 0): the hemisphere's octahedral map (Cigolle et al., "A Survey
//   of Efficient Representations for Independent Unit Vectors", JCGT 2014, sec. 3.2, its square
//   turned by 45 degrees so the upper hemisphere fills it): a = u + v, b = u - v with
//   u = nx / (|nx| + |ny| + nz), v = ny / (...), each of [-1, 1] in normal_levels = 254 steps
//   (8 bits each, 0 exactly a level: a level surface's normal is exact), at most 0.553 degrees off
//   (sqrt(6) / 254 radians); a zero normal (off the surface) its own code, 255;
// - the flow (normalised, in [0, 1]; its users weigh it by the rank of log10 flow and linearly
//   in the crease score: stroke_weight.hpp, shaders/dm.comp.glsl) rounded to flow_bits = 6 bits
//   of mantissa (within 2^-7 = 0.8 % of itself).
// The steps are chosen by the tile files' size on /tmp/j5.tif (line_tile_files.hpp): the normal
// at 10 bits a component took 0.22 B a vertex more, the flow at 8 bits 0.11, z at 1/512 of a cell
// 0.11.
// Each code decodes by one function (lattice_vertex), which snapping also applies, so the floats
// are the same whichever side made them (no fused multiply-adds: the build targets plain x86-64).
#pragma once
#include <cstdint>
#include <limits>

#include <glm/vec2.hpp>

#include "drainage/line_set.hpp"

namespace penink {

struct LineLattice {
    int plan_exp = 0, z_exp = 0;  // steps 2^plan_exp, 2^z_exp metres
    bool operator==(const LineLattice&) const = default;
};

// Normal components' steps over [-1, 1] (codes 0 .. normal_levels; normal_levels + 1: zero normal),
// and the flow's mantissa bits kept.
inline constexpr std::uint32_t normal_levels = 254;
inline constexpr int flow_bits = 6;

// The lattice for a drainage grid of cells `cell` metres on their smaller side (> 0).
LineLattice line_lattice(double cell);

// A vertex's integer code: x, y, z in lattice steps, the normal's a and b, the flow's bits
// shifted down to its kept ones.
struct VertexCode {
    std::int32_t x = 0, y = 0, z = 0;
    std::uint32_t a = 0, b = 0, flow = 0;
};

// The vertex of a code (the code's floats, rounded once from double).
DrapedVertex lattice_vertex(const VertexCode& code, const LineLattice& lattice);
// The same for n codes (lattice_vertex of each, in one loop).
void lattice_vertices(const VertexCode* codes, std::size_t n, const LineLattice& lattice, DrapedVertex* out);
// The code of a vertex on the lattice; false when v is not one lattice_vertex gives (bit for bit:
// a vertex not snapped, or beyond the codes' range).
bool vertex_code(const DrapedVertex& v, const LineLattice& lattice, VertexCode& code);
// The lattice vertex nearest v (x, y, z, flow rounded to nearest, the normal's a and b too), its
// x and y a step back inside [lo, hi] where rounding took them out (the box the build clamps the
// creases to: a snapped crease stays in it; [lo, hi] wider than a step); v as it is when it has
// no code (a coordinate beyond 2^31 steps or not finite).
DrapedVertex snapped_vertex(const DrapedVertex& v, const LineLattice& lattice,
                            glm::vec2 lo = glm::vec2(-std::numeric_limits<float>::infinity()),
                            glm::vec2 hi = glm::vec2(std::numeric_limits<float>::infinity()));
}  // namespace penink
