// The mesh frames of the scene layer (Xie et al. 2007 PELs, Winkenbach & Salesin 1994 feature
// lines and indication textures): OBJ/PLY/OFF mesh -> z-up world (y-up meshes rotated)
// -> camera (scene eye/target or auto-framed) -> GPU TFT pass (flat triangles) for the depth
// image -> object-space PELs, silhouettes, feature edges and textures, each split into visible
// strokes against that depth image, in the layers `pels`, `silhouettes` (+ surface mask fill),
// `feature-edges`, `textures` of a Drawing (image pixels, eye distance in mesh units).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scene/mesh_scene.hpp"
#include "scene/frame_source.hpp"
#include "input/mesh_reader.hpp"
#include "lines/feature_edges.hpp"
#include "lines/photic_extremum_lines.hpp"

namespace penink {

// The object-space lines of one frame, world frame (before hidden-line removal).
struct MeshLines {
    std::vector<ObjectPolyline> pels, silhouettes, feature_edges, textures;
    MeshLineTimings times;
};

// Every object-space line of the frame for the eye (and the light of `ms`, else at the eye):
// PELs and interpolated silhouettes on the crease-split mesh (PELs left out in flat-shaded
// triangles), contour creases as silhouettes, feature edges, textures.
MeshLines mesh_lines(const TriangleMesh& mesh, const MeshSettings& ms, const Scene& scene, const glm::vec3& eye,
                     const Log& log);

// A mesh read once (Loop-subdivided, turned z-up) with its GPU copy, drawn in any number of frames.
class MeshFrames : public FrameSource {
public:
    MeshFrames(const Scene& scene, GlContext& context, const Log& log);
    MeshFrames(const MeshFrames&) = delete;  // the renderer's geometry comes from surface_
    MeshFrames& operator=(const MeshFrames&) = delete;
    SceneDrawing draw(const Camera& camera, const Scene& frame) override;
    // The scene's camera: its eye/target, or the mesh framed from [camera] azimuth/altitude.
    Camera scene_camera(const Scene& scene) const;
    // `frames` cameras orbiting the mesh from the scene's camera (scene/orbit.hpp).
    std::vector<Camera> orbit(const Scene& scene, int frames) const;
    std::size_t triangles() const { return mesh_.triangles.size(); }

private:
    const Log* log_;
    MeshSettings ms_;
    TriangleMesh mesh_;
    SurfaceMesh surface_;
    std::unique_ptr<TerrainRenderer> renderer_;
};

// The scene's mesh read and set up for its own camera.
SceneView open_mesh_view(const Scene& scene, GlContext& context, const Log& log);

}  // namespace penink
