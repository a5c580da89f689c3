// A preview's drawing side: a terrain scene drawn again for each view the page asks for, through
// the path `penink render` takes (scene/frame_output.hpp's render_scene_frame, to an SVG in
// memory). Each frame's scene is the file Save writes (preview_view.hpp's scene_text), written to
// a private folder under the same name and loaded with load_scene, so the saved file renders to
// the same bytes. A frame may be drawn smaller (a share of the view's image size; a map scale
// follows, so that the image spans the same ground) while the page is being dragged. A click on the last full-size frame
// is found on the ground through its eye-distance image (the pixel's ray out to that distance)
// and given in the DEM's CRS, as lon/lat and as an elevation (unexaggerated, DEM units).
// Not thread-safe: made, used and destroyed on the one thread that owns its OpenGL context.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/log.hpp"
#include "core/pixel_mask.hpp"
#include "input/terrain.hpp"
#include "preview/preview_view.hpp"
#include "render/gl_context.hpp"
#include "scene/scene.hpp"
#include "scene/terrain_keep.hpp"

namespace penink {

struct PreviewFrame {
    std::string svg;
    int width = 0, height = 0;
    double draw_ms = 0.0;  // wall time of the drawing and its SVG
};

struct PreviewPoint {
    double x = 0.0, y = 0.0;  // DEM CRS units
    double elevation = 0.0;   // metres above the datum, unexaggerated
    std::optional<double> lon, lat;  // degrees, the CRS's geographic CRS
};

class PreviewSession {
public:
    // `scene`: a terrain scene, loaded with the command's overrides and validated; Save writes
    // `save_path` and Export the same name with other extensions. Draws the scene's own view once
    // to find the view's target (the ground at the image centre) and distance.
    PreviewSession(const Scene& scene, std::string save_path, GlBackend gl, const Log& log);
    ~PreviewSession();
    PreviewSession(const PreviewSession&) = delete;
    PreviewSession& operator=(const PreviewSession&) = delete;

    const PreviewView& initial_view() const { return initial_; }
    const std::string& save_path() const { return save_path_; }

    // The view drawn at `scale` (0.05..1) of its image size; at 1 the frame `locate` answers for.
    PreviewFrame draw(const PreviewView& view, double scale);
    // The ground under pixel (px, py) of the last full-size frame; none off the terrain.
    std::optional<PreviewPoint> locate(double px, double py) const;
    // Writes scene_text of the view to the save path (atomically); returns the path.
    std::string save(const PreviewView& view);
    // Draws the view into save_path's name with each extension (svg, pdf, png, ...), all or none;
    // returns the paths.
    std::vector<std::string> export_files(const PreviewView& view, const std::vector<std::string>& extensions);

private:
    Scene load_view(const PreviewView& view);

    std::string base_;  // the scene file's TOML text ("" for a bare DEM)
    std::string dem_;
    std::string save_path_;
    std::string folder_;      // private folder of the frames' scene files
    std::string scene_file_;  // folder_/<save file name>
    Log log_;
    std::unique_ptr<GlContext> context_;
    TerrainKeep keep_;        // the frames' terrain, drainage lines and renderers (before context_ goes)
    PreviewView initial_;
    Terrain meta_;            // the DEM's CRS and origin (no nodes)
    Camera camera_;           // of the last full-size frame
    DepthImage depth_;        // its eye distances
    double exaggeration_ = 1.0;
};

// The ground point under pixel (px, py) of a frame drawn with `camera`, eye distances `depth`:
// along the pixel centre's ray to the depth there (depth_at's 3x3 fallback); none where no
// surface is near. World coordinates of the frame (local metres, z as drawn).
std::optional<glm::dvec3> unproject_pixel(const Camera& camera, const DepthImage& depth, double px, double py);

}  // namespace penink
