// Thinning of a binary pixel mask (1-2 px wide line pixels) to an 8-connected one-pixel-wide
// skeleton: Zhang & Suen (CACM 27(3), 1984) sub-iterations whose deletions are re-checked one
// by one against Yokoi's 8-connectivity number (topology kept, end points never deleted), then
// a clean-up pass that removes the remaining redundant staircase/corner pixels.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/pixel_mask.hpp"

namespace penink {

// Neighbour order used for the 8-bit neighbourhood codes: N, NE, E, SE, S, SW, W, NW
// (image frame, y down: N is the row above).
inline constexpr std::array<int, 8> neighbour_dx = {0, 1, 1, 1, 0, -1, -1, -1};
inline constexpr std::array<int, 8> neighbour_dy = {-1, -1, 0, 1, 1, 1, 0, -1};

// Number of set neighbours of an 8-bit neighbourhood code (bit k = neighbour k above).
int neighbour_count(std::uint8_t code);
// Yokoi's 8-connectivity number: 1 <=> deleting the centre changes no connectivity
// (for a centre with >= 1 neighbour).
int connectivity_number(std::uint8_t code);

// Skeleton of the mask (same size; on = 1 for skeleton pixels). Throws penink::Error on a
// malformed mask. Works on the list of set pixels only: cost ~ number of set pixels.
PixelMask thin_mask(const PixelMask& mask);

// Prunes branches of at most max_len pixels that run from an end point to a junction
// (a pixel with >= 3 neighbours); max_len <= 0 leaves the skeleton unchanged.
void prune_spurs(PixelMask& skeleton, int max_len);

}  // namespace penink
