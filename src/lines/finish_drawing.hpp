// Finishing a Drawing for export (Potter et al., "NPR-Style 3D Line Textures", 4.3 for the sketchy part): per layer, strokes
// (image pixels, origin top-left, y down; depth = eye distance in metres / world units) are
// joined end to end, simplified (Douglas-Peucker, px), stripped of tiny strokes, thinned by
// distance, perturbed / overshot / repeated, and put in pen-plotter order (greedy nearest end).
//
// Which layers are perturbed where:
//  - image space (LayerFinish::space == SketchSpace::image, the default for every layer:
//    silhouettes, outlines, PELs, textures, feature edges): finish_drawing moves the end points
//    of each finished stroke in the image plane (sketch_copies), extends open ends by the
//    overshoot and adds repeat-1 extra strokes, each perturbed on its own.
//  - object space (SketchSpace::object; meant for the terrain's ridges and creases, which live on
//    the surface): the caller perturbs each 3D polyline within the local surface plane BEFORE
//    projecting it, with sketch_object_copies() below (one copy per repeat), and marks the layer
//    object. finish_drawing then neither perturbs nor repeats it (it still joins, simplifies,
//    drops, thins, overshoots in the image and orders it).
// Overshoot, repeat and distance thinning are applied here, exactly once (export's
// style_drawing() only colours, sizes and groups). Every random number derives from (seed, stroke_geometry_id,
// k) (splitmix64), so the same seed gives the same drawing whatever the processing order.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera.hpp"
#include "core/drawing.hpp"

namespace penink {

enum class SketchSpace { image, object };

struct LayerFinish {
    float sketch = 0.0f;     // end point perturbation radius, px (0 = none)
    float overshoot = 0.0f;  // extension of both ends of open strokes, px
    int repeat = 1;          // times each stroke is drawn (>= 1), each perturbed on its own
    float keep_far = 1.0f;   // share of strokes kept at the far distance (1 = no thinning)
    float min_length = 2.0f; // px: shorter strokes (pen-down length) are dropped, and closed ones
                             // less than 4 min_length across (specks, slivers); 0 keeps both
    SketchSpace space = SketchSpace::image;
    // Joins that know occlusion (ChainParams::occlusion): contours whose depth is the occluding
    // surface's; finish_options sets it for the silhouettes.
    bool occlusion_joins = false;
    // Doubled lines (merge_doubled): a stretch running within merge_px of a stronger stroke for
    // merge_run_px or more is cut out; in finish_drawing creases and ridges also yield to the
    // silhouettes. 0: no merging (finish_options sets 1.5 px).
    float merge_px = 0.0f;
    float merge_run_px = 4.0f;
};

struct FinishOptions {
    std::uint64_t seed = 0;
    float join_tolerance = 1.0f;      // px: stroke ends closer than this are joined
    float simplify_tolerance = 0.4f;  // px: Douglas-Peucker tolerance
    // Distance thinning: fractions of the drawing's largest eye distance (export's Style
    // near/far); keep probability falls linearly from 1 at near to keep_far at far.
    float near = 0.0f, far = 1.0f;
    glm::vec2 home{0.0f, 0.0f};       // plotter pen start (image pixels)
    // line_metrics into the stats (small_loops, doubled_share: what -v prints); the strokes are
    // the same without it, which spares a tenth of an interactive frame's time.
    bool measure = true;
    std::array<LayerFinish, layer_count> layers;  // indexed by LayerKind
    LayerFinish& layer(LayerKind k) { return layers[static_cast<std::size_t>(k)]; }
    const LayerFinish& layer(LayerKind k) const { return layers[static_cast<std::size_t>(k)]; }
};

struct LayerFinishStats {
    std::size_t strokes_in = 0;   // strokes before joining
    std::size_t joined = 0;       // after joining (and dropping)
    std::size_t strokes = 0;      // final strokes (after thinning and repeats)
    double length = 0.0;          // final pen-down length, px
    double travel_before = 0.0;   // pen-up travel before ordering, px
    double travel_after = 0.0;    // pen-up travel after ordering, px
    // line_metrics of the strokes before sketchiness and repeats (which double lines on purpose):
    // closed loops under 25 px across, share of length running within 1.5 px of another stroke
    // for 4 px or more.
    std::size_t small_loops = 0;
    double doubled_share = 0.0;
};

struct FinishStats {
    std::array<LayerFinishStats, layer_count> layers;  // indexed by LayerKind
};

// Finishes every layer's strokes in place (surface fill rings are left alone). Steps per layer:
// join (same kind, junctions of >= 3 ends kept, or with occlusion_joins the nearer contour
// continued through them) -> simplify -> drop strokes shorter than the layer's min_length -> join
// again (drops can leave 2-end nodes) -> merge doubled lines (the silhouettes first; creases and
// ridges yield to them) -> drop short strokes again -> distance thinning -> sketch / overshoot /
// repeat (image-space layers) -> plotter order from `home`.
FinishStats finish_drawing(Drawing& drawing, const FinishOptions& options);

// Strokes of one layer through the same steps; `max_depth` is the drawing's largest depth.
std::vector<Stroke> finish_strokes(std::vector<Stroke> strokes, const FinishOptions& options,
                                   const LayerFinish& layer, double max_depth, LayerFinishStats& stats);

// Object-space sketchiness hook for surface lines (ridges, creases): a 3D polyline (world units)
// with one surface normal per point and its eye distance per point.
struct ObjectLine {
    std::vector<glm::vec3> points, normals;
    std::vector<float> depth;  // depth per point (eye_depth, world units)
};

// Order-independent id of a 3D polyline (point count and end points' bits).
std::uint64_t object_line_id(const ObjectLine& line);

// The line and repeat-1 extra copies, each perturbed within the local tangent planes
// (sketch_polyline_3d) by up to amount_px image pixels converted to world units at the line's
// mean depth with the camera (world_per_pixel). amount_px <= 0 gives `repeat` unperturbed copies. Throws penink::Error (from
// sketch_polyline_3d) when normals are not one per point.
std::vector<ObjectLine> sketch_object_copies(const ObjectLine& line, float amount_px, int repeat,
                                             const Camera& camera, std::uint64_t seed);

}  // namespace penink
