// Creases and ridges of a terrain frame (Mower, "Concurrent Drainage Network Rendering"): the lines
// selected for the frames (drainage/line_selection.hpp) uploaded once to DM passes; per frame each
// vertex's terms are written on the GPU (render/dm.hpp), scored (lines/crease_scores.hpp) and the
// visible runs made into object-space strokes (lines/line_strokes.hpp) for the `creases` and
// `ridges` layers, thinned to the layer's spacing.
#pragma once
#include <memory>

#include "scene/scene.hpp"
#include "core/drawing.hpp"
#include "drainage/line_selection.hpp"
#include "lines/crease_scores.hpp"  // max_visible_distance: D of draw()
#include "lines/scored_polylines.hpp"
#include "render/dm.hpp"
#include "render/terrain_renderer.hpp"

namespace penink {

// One vertex set (branches or divides) uploaded to its DM pass.
struct UploadedLines {
    ScoredLineSet lines;
    std::unique_ptr<DmPass> pass;
};
// What the DM pass of a vertex set reads: its positions, normals and flow.
inline DmInput dm_input(const ScoredLineSet& s) { return {s.positions, s.normals, s.flow}; }

// Three spacings (the thinning's shortest stroke) of the closer-spaced layer, less what
// object-space sketchiness adds to a stroke's ends (twice the sketch amount) and a pixel of
// rounding; half of that with sketchy lines, as a margin: the sketch offsets are sized at a line's
// mean depth, so its nearest points may move further on screen. 0 (no culling) when either layer
// is not thinned. Test: LineCulling.DrawingIsTheSameWithAndWithoutIt.
float line_culling_px(const Scene& scene);

class DrainageLines {
public:
    // prepare_drainage_lines(db, model) without culling, uploaded.
    DrainageLines(const GlApi& gl, const DrainageDb& db, const Terrain& model);
    // Uploads prepared data (the GL half).
    DrainageLines(const GlApi& gl, DrainageLineData data);
    // Replaces the lines by other prepared data (uploaded into the same passes, whose programs
    // stay compiled).
    void set_lines(DrainageLineData data);
    // Adds the creases and ridges of one frame; DM and RIDGES GPU times go into `times`.
    void draw(const Camera& camera, const Scene& scene, GLuint toward_texture, float max_distance,
              Drawing& drawing, PassTimings& times);
    std::size_t crease_vertices() const { return creases_.lines.positions.size(); }

private:
    UploadedLines creases_, ridges_;
};

}  // namespace penink
