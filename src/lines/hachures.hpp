// Hachures: slope lines whose spacing on the image draws a target tone (Buchin, Sousa, Döllner,
// Samavati & Walther 2004, "Illustrating terrains using direction of slope and lighting"; Imhof's
// and Lehmann's hachure rules; Mower 2009, "Automating landscape illustration with pen and ink
// style rendering"), placed as evenly spaced streamlines (Jobard & Lefer 1997, "Creating
// evenly-spaced streamlines of arbitrary density") with hachure-builder's minimum and maximum
// distance and turning limit (tsamsonov/hachure-builder).
//
// Surface: a DEM's grid of nodes (local metres, x east, y north, z up as drawn; row 0 north, the
// grid may be curvilinear), positions bilinear in the grid parameters (c, r) inside a cell whose
// four nodes are valid. The slope field is continuous: the world gradient (dz/dx, dz/dy) at each
// node from central differences of its neighbours (one-sided at the grid's edge or beside nodata),
// interpolated bilinearly between nodes. Lines are traced in object space along that field (the
// fall line, both ways from a seed: down along -grad z, up along +grad z) with a midpoint (RK2)
// step whose image length is about 2 px, each point projected by the camera (core/camera.hpp):
// a step's chord departs from the traced curve by L theta / 8 (L = 2 px, theta its turn), under
// 0.05 px where fall lines turn less than 5 deg/px and 0.22 px at max_turn_deg, about the 0.2 px
// the strokes are simplified by.
//
// Tone at a point: "light" T = 1 - max(0, n . l) (n the unit normal of the interpolated gradient,
// l the unit vector towards the light); "slope" T = min(1, slope / 45 deg) (Lehmann: steeper is
// darker); "blend" (1 - b) light + b slope. Drawn tone t = clamp(0.5 + contrast (T - 0.5), 0, 1)^gamma
// (contrast about mid-grey: flats under a 45 deg sun, T = 0.29, fall to white first), times
// (1 - aerial * ((d - d0) / (D - d0))^2) in perspective (d the point's eye distance, D the frame's
// largest, d0 its nearest, or with a sea the nearest land node's; Bratkova, Shirley & Thompson
// 2009: contrast falls with distance). The pen for tone t is w(t) = w (weight_min + (weight_max -
// weight_min) t^1.5) (hachure_pen_width: Lehmann's light tones in thin, sparse strokes, dark tones
// in heavy, close ones). Parallel lines of width w(t) px at spacing s px cover w(t) / s of the
// paper, so the separation is s = w(t) / t on the image, clamped below at spacing_min_px; where
// w(t) / t exceeds spacing_max_px, or the slope is under min_slope_deg, no line is drawn (lit
// slopes and flats stay white).
//
// Width: each point of a line carries a weight u in [0, 1] (Stroke::weight) that the style maps to
// a width between weight_min and weight_max times w: the width w' = t (g_l + g_r) / 2 that makes
// the ink between the line and its neighbours the tone, g_l and g_r the gaps across the line to
// the nearest other hachure or obstacle point on each side (within 45 deg of the normal, at most
// 2 s; a side with none within 2 s counts s), u = (w' - weight_min w) / ((weight_max - weight_min) w)
// clamped and averaged over 5 points (about 10 px): w(t) where the lines lie w(t) / t apart. So the
// dark tones that spacing_min_px stops, and the gaps
// where lines end, are drawn by wider lines, crowded lines by thinner ones. With weight_min ==
// weight_max (the plotter style) no weights: tone by spacing alone.
//
// Coverage feedback (Winkenbach & Salesin 1994: strokes until the tone is reached; lines/
// hachure_coverage.hpp), on 8 px image cells: the drawn tone is sampled at every lattice seed
// (flats under min_slope_deg and water at the sea level aim at white), the ink is each line's
// length x width with the style's taper (a side's share no wider than the gap there: overlapping
// ink is paper already black) plus the lines yielded to, drawn with their own pens. (1) Where even
// the heaviest pen leaves a cell lighter than its target by 5 %, its lattice seeds are tried again
// with the separation tightened by the shortfall, down to 0.35 s (the holes between line ends on
// rough ground). (2) Each point's width is multiplied by the gain target / ink of its cells
// (3 x 3 box, bilinear), clamped to the pen; then points wanting less than the
// lightest pen (cells the creases or silhouettes already darken) are cut out, pieces shorter
// than min_length_px dropped, and a last round sets the widths.
//
// Placement, all in image pixels on an occupancy grid (a spatial hash of 3 px cells): a line grows
// from its seed while each new point is on a valid cell, in the image, visible against the frame's
// depth image (lines/mesh_visibility.hpp point_visible: the depth test of the outline and creases),
// facing the viewer (a silhouette ends it), dark enough, turning less than max_turn_deg per pixel
// (where fall lines converge or diverge: valleys and ridges), and no point of another hachure lies
// within d_test * s (s the local separation), nor a point of an obstacle (creases, ridges,
// silhouettes drawn before) within yield_px. Lines shorter than min_length_px are
// dropped. Seeds are tried beside each accepted line, at s to either side along the contour
// direction, every s / 2 along it (a seed needs its whole separation free: 0.95 s), then on a
// lattice of the grid's cells (north to south, west to east) about one per (2 spacing_min_px)^2 of
// image, a block wider than 9 px on the image split into up to 16 x 16 seeds. Node gradients use
// differences over +-k nodes, k about 1.5 px of ground at the median cell size. No random numbers and no hash or thread order: the same input gives the same strokes.
// Cost: O(drawn length + lattice seeds + image cells). Nodes read on demand (HachureGrid::read)
// hold at most the cache's bytes; the lines then read the tiles they walk, again where they come
// back to a tile dropped meanwhile (lines/node_tiles.hpp).
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"
#include "lines/hachure_params.hpp"
#include "lines/node_tiles.hpp"

namespace penink {

// Width the spacing is computed for when neither the scene nor the style gives one (pixels).
inline constexpr double default_hachure_width_px = 1.0;

// A read-only grid of nodes (the hachures' view of a DEM's nodes; the scene fills it from its
// GridNodes): cols x rows, row-major, row 0 north; z drawn as max(z * z_scale, floor_z) (the
// vertical exaggeration and a sea level, as GridNodes::at draws it); [c0, c1) x [r0, r1) the nodes
// the lines may use. The nodes are in memory (pos, valid), or, with pos null, read through `read`
// on demand in tiles of tile_cols x tile_rows nodes, at most cache_bytes of them held (NodeTiles,
// lines/node_tiles.hpp: the same nodes, so the same lines; `counts`, when given, gets what the
// cache did).
struct HachureGrid {
    int cols = 0, rows = 0;
    const glm::vec3* pos = nullptr;
    const std::uint8_t* valid = nullptr;
    NodeReader read;
    std::size_t cache_bytes = NodeTiles::default_budget;
    int tile_cols = NodeTiles::default_tile_cols, tile_rows = NodeTiles::default_tile_rows;
    NodeTileCounts* counts = nullptr;
    double z_scale = 1.0;
    float floor_z = -std::numeric_limits<float>::infinity();
    int c0 = 0, r0 = 0, c1 = 0, r1 = 0;
};

struct HachureFrame {
    const Camera* camera = nullptr;
    const DepthImage* toward = nullptr;  // the frame's nearest-surface depth; empty: no occlusion
    glm::dvec3 light{0.0, 0.0, 1.0};     // unit, towards the light
    double max_distance = 0.0;           // D: the largest visible eye distance (0: no aerial fade)
    double width_px = default_hachure_width_px;
    std::vector<const std::vector<Stroke>*> obstacles;  // strokes the hachures yield to
    std::vector<HachurePen> obstacle_pens;              // the pen of each (missing: a HachurePen{})
};

// The pen's width for drawn tone t in [0, 1], px: width x lerp(weight_min, weight_max, t^p) with
// p = hachure_width_exponent (the lightest tones thin, the darkest heaviest, the middle tones
// nearer the thin end); the spacing w / t makes up the rest of the tone. Equal weights: one width.
inline constexpr double hachure_width_exponent = 1.5;
double hachure_pen_width(double tone, double width, double weight_min, double weight_max);

// The target tone T of a unit normal (before contrast, gamma and distance), in [0, 1].
double hachure_tone(HachureTone tone, double blend, const glm::dvec3& normal, const glm::dvec3& light);

// The hachures of one frame: strokes of kind "hachure" (image pixels, eye distance per point),
// strength = the mean drawn tone along the line.
std::vector<Stroke> trace_hachures(const HachureGrid& grid, const HachureFrame& frame, const HachureParams& params);

}  // namespace penink
