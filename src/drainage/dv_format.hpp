// The DV file layout shared by its writer (dv_writer.cpp) and reader (dv_reader.cpp); the layout
// itself is set out at the top of drainage_db.cpp. Internal to src/drainage.
#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "drainage/drainage_db.hpp"

namespace penink::dv {

inline constexpr char magic[8] = {'P', 'N', 'K', 'D', 'V', 0, 0, 0};
inline constexpr std::size_t prefix_bytes = 8 + 4 + 4 + 8;  // magic, version, reserved, total length

// Bytes of a LEB128 varint.
inline std::size_t varint_size(std::uint64_t v) { return (std::size_t(std::bit_width(v | 1)) + 6) / 7; }

// How vertex positions are stored (the byte after the CRS): x, y per vertex, or grid cells on an
// affine grid (then f64 gt[6], f64 unit, i32 col0, row0 follow).
inline constexpr std::uint8_t positions_explicit = 0, positions_grid = 1;
inline std::size_t positions_bytes(bool grid) { return 1 + (grid ? 6 * 8 + 8 + 8 : 0); }

// Bytes up to the positions byte: prefix, fingerprint, grid, origin, CRS.
inline std::size_t header_bytes(const DrainageDb& db) { return prefix_bytes + 36 + 12 + 16 + 4 + db.crs_wkt.size(); }

// Accumulation at the outlet of basin b at total[b - 1], from the basin's outlet branch. False
// unless every basin id is in 1..outlet branches, each outlet branch has its own and its total
// is at least one point.
bool basin_totals(const DrainageDb& db, std::vector<double>& total);

// Normalised flow at vertex k of branch b (as the builder's normalised_flow gives it).
inline float branch_flow(const DvBranch& b, std::uint32_t k, const std::vector<double>& total) {
    return float(double(std::uint64_t(b.head_acc) + k) / total[b.basin - 1]);
}

// What the layout relies on and the encoder checks (drainage_db.cpp): vertex ranges of branches
// and divides consecutive, downstream links in range and never to the branch itself, basin ids.
bool layout_ok(const DrainageDb& db);

}  // namespace penink::dv
