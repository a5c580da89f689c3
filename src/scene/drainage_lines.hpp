// Creases and ridges of a terrain frame (Mower, "Concurrent Drainage Network Rendering"): the drainage database's branch and divide
// vertices, with PN-surface normals looked up under them, uploaded once to DM passes; per frame
// each is scored and visibility-tested on the GPU and clipped into object-space strokes for the
// `creases` and `ridges` layers.
#pragma once
#include <memory>

#include "scene/scene.hpp"
#include "core/drawing.hpp"
#include "drainage/drainage_db.hpp"
#include "lines/scored_polylines.hpp"
#include "render/dm.hpp"
#include "render/terrain_renderer.hpp"
#include "surface/surface_mesh.hpp"

namespace penink {

// One vertex set (branches or divides) ready for the DM pass.
struct ScoredLineSet {
    std::vector<glm::vec3> positions, normals;
    std::vector<VertexRun> runs;
    std::vector<DmVertex> upload;  // prepared vertices, moved to the GPU by DrainageLines
    std::unique_ptr<DmPass> pass;
};

// The CPU half of DrainageLines (stems, cropping to the surface, smoothing, draping, normals):
// needs no GL context, so it can run on another thread while the frame renders.
struct DrainageLineData {
    ScoredLineSet creases, ridges;
};
DrainageLineData prepare_drainage_lines(const DrainageDb& db, const SurfaceMesh& mesh);

class DrainageLines {
public:
    // `mesh` is the rendered (cropped) surface: vertices outside it are never visible.
    DrainageLines(const GlApi& gl, const DrainageDb& db, const SurfaceMesh& mesh);
    // Uploads prepared data (the GL half).
    DrainageLines(const GlApi& gl, DrainageLineData data);
    // Adds the creases and ridges of one frame; DM and RIDGES GPU times go into `times`.
    void draw(const Camera& camera, const Scene& scene, GLuint toward_texture, float max_distance,
              Drawing& drawing, PassTimings& times);
    std::size_t crease_vertices() const { return creases_.positions.size(); }

private:
    ScoredLineSet creases_, ridges_;
};

// Largest finite eye distance of the frame (D of rs_min), metres.
float max_visible_distance(const DepthImage& toward);

}  // namespace penink
