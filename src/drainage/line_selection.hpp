// Creases and ridges selected for a frame (Mower, "Concurrent Drainage Network Rendering"): the
// drainage database's stems and divides, smoothed and draped on the PN surface once when the
// database was built (line_set.hpp), picked by the modelled box through the database's line
// index, culled and decimated at the frames' screen size, exaggerated, and laid out as runs of
// one vertex array for the DM pass (render/dm.hpp). Positions in local metres.
#pragma once
#include <functional>
#include <memory>
#include <limits>
#include <vector>

#include <glm/vec2.hpp>

#include "core/camera.hpp"
#include "core/vertex_run.hpp"
#include "drainage/drainage_db.hpp"
#include "drainage/stored_creases.hpp"
#include "input/terrain.hpp"

namespace penink {

// One vertex set (branches or divides) ready for the DM pass.
// The DM pass reads positions, normals and flow (DmInput, render/dm.hpp, laid out on the GPU a
// chunk at a time: no DmVertex array held).
struct ScoredLineSet : VertexLines {
    std::vector<float> flow;  // normalised flow per vertex (the creases' weight by flow)
};

// The creases and ridges of a frame; needs no GL context, so it can be made on another thread
// while the frame renders.
struct DrainageLineData {
    ScoredLineSet creases, ridges;
};

// The stored creases and ridges of `db` whose plan box meets the plan box of `model` (the terrain
// the frame models: terrain_bounds; only that and its vertical exaggeration are used), cut to the
// box as lines_in_box cuts lines (stems.hpp: the runs inside, with one vertex beyond the box at
// each cut; vertices outside the box are off the modelled surface and get a zero normal, so they
// are never drawn), exaggerated by e = model.vertical_exaggeration: z' = e z, normal' =
// normalize(e nx, e ny, nz) (as stored at e = 1). Work in proportion to the lines selected: no
// pass over the database's vertices.
// Screen-size culling (the creases at the level of detail of the image): a piece is left out when
// no camera of `culling` can show it min_px pixels long (its exaggerated length times
// lod_pixel_scale over its nearest vertex's eye distance: an upper bound on its image length
// inside the frame). DrainageLines::draw's spacing thinning drops every stroke shorter than three
// spacings, so with min_px = line_culling_px(scene) the drawing is the same as without culling.
// Vertex decimation: inside a piece's drawable part, a vertex closer than decimate_px pixels (same
// bound) to the last one kept is not written; the part's two ends always are.
struct LineCulling {
    std::vector<Camera> cameras;  // none: no culling, no decimation
    float min_px = 0.0f;
    float decimate_px = 0.5f;
};
// The modelled box: plan bounds (local metres) of what the frames model, and the exaggeration
// the lines are drawn at.
// Water: a vertex at or below the sea level (unexaggerated, GridNodes::sea_level) counts as
// outside the box, so the lines are cut where they reach the sea and nothing is drawn on water.
struct LineBox {
    glm::vec2 lo{0.0f}, hi{-1.0f};  // empty when hi < lo
    double exaggeration = 1.0;
    double sea_level = -std::numeric_limits<double>::infinity();  // -inf: no water
};
// The box of a modelled terrain's valid nodes (empty when it has none).
LineBox line_box(const Terrain& model);
DrainageLineData prepare_drainage_lines(const DrainageDb& db, const LineBox& box, const LineCulling& culling = {});
DrainageLineData prepare_drainage_lines(const DrainageDb& db, const Terrain& model, const LineCulling& culling = {});

// What a render selects its lines from (scene_drainage): a database whose lines carry their
// vertices (a build, or a whole lines-part read), or the cache's line records and index with the
// vertices left in the file (load_or_build_drainage's `in_file`, read_drainage_line_index).
struct DrainageLineSource {
    DrainageDb db;
    DvLineVertices vertices;  // file set: db's creases and ridges hold no vertices; they are here
    // Where db stores the creases' source (DrainageDb::crease_source): the creases a frame's box
    // and culling can draw built stem by stem, kept for the next frame of this process. None: a
    // StoredCreases made for each frame from db (nothing kept).
    std::shared_ptr<StoredCreases> creases;
    std::size_t batch_bytes = std::size_t(4) << 20;  // vertices read from the file at a time (at least one line)
    // The database read whole (every checksum checked) or rebuilt: what a file set falls back to
    // when a block of its vertices is found damaged (DvCorrupt). None: the error goes on.
    std::function<DrainageDb()> read_whole;
};
// The same lines as prepare_drainage_lines(db) gives for the database whose lines `source` holds
// (same pieces, order and floats); from a file, only the vertices of the lines meeting the box
// are read (memory and time follow the selection), each block checked the first time it is read;
// a damaged block makes it select from source.read_whole() instead (never from damaged vertices).
DrainageLineData prepare_drainage_lines(const DrainageLineSource& source, const LineBox& box,
                                        const LineCulling& culling = {});
DrainageLineData prepare_drainage_lines(const DrainageLineSource& source, const Terrain& model,
                                        const LineCulling& culling = {});

}  // namespace penink
