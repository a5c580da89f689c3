// The coastline layer of a terrain frame: the shore at the scene's sea level (the DEM's contour
// there, surface/sea_level_contour.hpp, over the modelled window), drawn as the creases are
// (drainage_lines.hpp): its vertices uploaded once to a DM pass (render/dm.hpp), which projects
// each and tests it against the frame's TFT eye distances (lifted a pixel footprint along the
// water's normal, grazing-aware tolerance), and the visible runs projected into image strokes
// (lines/scored_polylines.hpp) of kind "coastline". The depth test is made at the rendered
// mesh's height over each shore point (ShoreLine::ground: the land node's edge rises from the
// water there), the stroke drawn at the water surface, sea_level times the exaggeration. Vertices
// outside the frustum are hidden: the lines are clipped to the view. Units: local metres in,
// image pixels and eye distances (metres) out.
#pragma once
#include <memory>

#include "core/drawing.hpp"
#include "render/dm.hpp"
#include "scene/drainage_lines.hpp"
#include "surface/sea_level_contour.hpp"

namespace penink {

// The shore lines as one vertex set: positions at the water surface, normals straight up, one run
// per line; `ground`: each vertex at the ground height, where the DM pass tests it. Empty without
// water.
ScoredLineSet coastline_vertices(const std::vector<ShoreLine>& lines, std::vector<glm::vec3>& ground);

class CoastlineLines {
public:
    // The coastline of `nodes` inside `window`, uploaded (nothing when the nodes have no sea).
    CoastlineLines(const GlApi& gl, const GridNodes& nodes, GridWindow window);
    // The visible coastline of one frame into drawing's coastline layer.
    void draw(const Camera& camera, GLuint toward_texture, Drawing& drawing);
    std::size_t vertices() const { return set_.lines.positions.size(); }

private:
    std::vector<glm::vec3> ground_;  // the DM pass's positions (made before set_, which fills it)
    UploadedLines set_;
};

}  // namespace penink
