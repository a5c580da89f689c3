// The hachures layer of a terrain frame (lines/hachures.hpp): the scene's [hachures] table read
// and checked, and one frame's hachures traced on the modelled nodes after its creases, ridges
// and silhouettes (which the hachures yield to), against the frame's nearest-surface depth.
#pragma once
#include <string>
#include <vector>

#include "core/drawing.hpp"
#include "core/pixel_mask.hpp"
#include "export/style.hpp"
#include "lines/hachures.hpp"
#include "scene/terrain_view.hpp"

namespace penink {

// The keys [hachures] takes (read by the scene file's reader, scene_file.cpp): enabled, tone,
// blend, contrast, gamma, min_slope_deg, spacing_min_px, spacing_max_px, width_px, d_test,
// yield_px, max_turn_deg, aerial, min_length_px.
const std::vector<std::string>& hachure_keys();
// The number that [hachures] `key` sets in `p`; nullptr for enabled, tone and any other name.
double* hachure_number(HachureParams& p, const std::string& key);
// The scene's hachure settings with the style's pen (style resolved by load_scene): width_px, when
// the scene gives none, from the hachures layer's width (millimetres at 96 dpi), since the
// spacing is computed for the pen that draws them, and the weight range its width takes with
// the tone (the layer's weight_min, weight_max).
HachureParams hachure_pen(HachureParams params, const Style& style);

// One-line range errors ("[hachures] KEY must be between LO and HI (got V)").
void validate_hachures(const HachureParams& p, const std::string& file);

// The step between the nodes the hachures work from: the largest power of two (at most
// hachure_max_node_step) at which a cell of the window still spans at most hachure_node_px on the
// image, its image size the largest of max(|node(c+1, r) - node(c, r)|, |node(c, r+1) - node(c, r)|)
// (pixels) over a 16 x 16 lattice of the window's nodes (its edges included) that project into the
// image. 1 (every node) wherever the nodes are not finer than that, as on every DEM a frame shows
// at a few pixels or more a cell; a whole view of a DEM of many nodes to the pixel gets 2, 4, ...
// A pixel: the gradients' stencil spans about 1.5 px of ground whatever the step (hachures.hpp),
// so the field has no detail finer than the sampled cells (jacksboro refined 29 times, whole view:
// the same tone as with every node, docs/timings.md "Scale"; the hachures 3x faster than at
// half a pixel, whose 4x the nodes overflowed the tiles held).
inline constexpr double hachure_node_px = 1.0;
inline constexpr int hachure_max_node_step = 64;
int hachure_node_step(const GridNodes& nodes, GridWindow window, const Camera& camera);

// The nodes a frame's hachures are traced on: every hachure_node_step-th node of the frame's
// window in each direction (sampled.step), counted from the grid's node (0, 0) (the window's first
// row and column rounded down to a multiple of the step): the same nodes for every view at that
// step, so a pan or a flight does not shift them, and those a terrain cache keeps as its coarse
// nodes (GridNodes::coarse_step) at a step of 4 or more. At step 1 the window's nodes, made readable in place
// (GridNodes::need) here; past it the sampled nodes are read by the hachures as they trace, a
// tile at a time through a cache of NodeTiles::default_budget bytes (read_sampled: only their
// rows are read, none kept in place), so their memory is bounded whatever the window. Depends on
// the terrain's nodes and window and the camera alone, so a frame finds them while its other
// lines are still being prepared.
struct HachureNodes {
    SampledWindow sampled;
};
HachureNodes hachure_nodes(const FrameTerrain& terrain, const Camera& camera);

// The frame's hachures into drawing's hachures layer (nothing when disabled), traced on
// hachure_nodes, so a frame of a fine DEM reads a share of its nodes that follows the image.
// params.width_px is the pen width the spacing is computed for (0: default_hachure_width_px).
void add_hachures(const FrameTerrain& terrain, const Camera& camera, const DepthImage& toward,
                  const glm::dvec3& light, const HachureParams& params, Drawing& drawing);
// The same on nodes read beforehand (hachure_nodes of this terrain and camera); `tiles`, when
// given, gets what the cache of the sampled nodes' tiles did (step > 1).
void add_hachures(const FrameTerrain& terrain, const HachureNodes& nodes, const Camera& camera,
                  const DepthImage& toward, const glm::dvec3& light, const HachureParams& params, Drawing& drawing,
                  NodeTileCounts* tiles = nullptr);

// The -v line of the sampled nodes' tiles: "hachures: every 4 nodes (2922 x 2494 sampled), 468
// reads of 468 tiles of 256 x 64, 64 MiB held at most".
std::string hachure_tiles_line(const SampledWindow& sampled, const NodeTileCounts& tiles);

}  // namespace penink
