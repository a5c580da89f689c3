// Renders one frame of a terrain surface through the GPU passes (TFT/AFT, SIL) and reads the
// results back for the lines stage: toward/away eye-distance images (metres, row 0 = top) and
// the silhouette pixel mask, with each pass's GPU time (GL timer queries, as the paper's Table 3).
// The silhouette mask comes from one of the GPU methods: Toward/Away (Mower, "Fast Image-Space Silhouette Extraction", 3.2; default),
// Adjacency (3.1, render/id_adjacency_sil.hpp) or penink's edge walk (render/edge_walk_sil.hpp). With object_space no SIL pass runs and the mask is
// left empty: the caller draws those silhouettes on the CPU (scene/terrain_frames.hpp).
#pragma once
#include <memory>

#include "core/camera.hpp"
#include "core/pixel_mask.hpp"
#include "render/edge_walk_sil.hpp"
#include "render/id_adjacency_sil.hpp"
#include "render/readback.hpp"
#include "render/sil.hpp"
#include "render/surface_geometry.hpp"
#include "render/tft_aft.hpp"

namespace penink {

enum class SilhouetteMethod { toward_away, adjacency, edge_walk, object_space };

struct FrameOptions {
    TessellationOptions tessellation;
    SilhouetteMethod silhouette_method = SilhouetteMethod::toward_away;
    IdAdjacencyOptions adjacency;
    EdgeWalkOptions edge_walk;
    bool separate_passes = false;  // TFT and AFT as two passes (paper) instead of one combined
    float silhouette_min_gap = 0.0f;
};

struct PassTimings {  // milliseconds
    double tft = 0, aft = 0, sil = 0, dm = 0, ridges = 0, lay = 0, readback = 0;
    double pel = 0;     // CPU: photic extremum lines of a mesh frame (scene/mesh_frames)
    double select = 0;  // CPU: the frame's level-of-detail mesh selected and uploaded (scene/terrain_frames)
    // Part of `sil` spent on the adjacency or edge-walk method's triangle-ID geometry pass (GPU). For the
    // object-space method the caller sets `sil` to its CPU wall time.
    double sil_ids = 0;
};

struct FrameImages {
    DepthImage toward, away;  // eye distance, +inf where no fragment
    PixelMask silhouettes;
    PassTimings times;
};

// The mesh is uploaded at construction or by set_surface (a frame's level-of-detail mesh); the
// renderer keeps no reference to it.
class TerrainRenderer {
public:
    TerrainRenderer(const GlApi& gl, const SurfaceMesh& mesh, int width, int height);
    // Replaces the uploaded surface.
    void set_surface(const SurfaceMesh& mesh);
    std::size_t triangle_count() const { return geometry_.triangle_count(); }
    FrameImages render(const Camera& camera, const FrameOptions& options);
    const GlApi& gl() const { return *gl_; }
    const TftAftPass& surface_pass() const { return tft_aft_; }

    // Tessellated triangles of the last edge-walk frame (0 for the other methods).
    std::size_t edge_walk_triangles() const { return edge_walk_ ? edge_walk_->triangle_count() : 0; }
    // The adjacency pass itself (null until its first frame), for tests.
    const IdAdjacencySilPass* adjacency_pass() const { return adjacency_.get(); }

private:
    double silhouettes(const Camera& camera, const FrameOptions& options, FrameImages& out);
    const GlApi* gl_;
    SurfaceGeometry geometry_;
    TftAftPass tft_aft_;
    SilPass sil_;
    std::unique_ptr<EdgeWalkSilPass> edge_walk_;  // built on first use (its programs compile then)
    std::unique_ptr<IdAdjacencySilPass> adjacency_;  // likewise
};

// Pixels covered by any surface fragment (toward or away): the surface mask.
PixelMask coverage_mask(const FrameImages& images);

}  // namespace penink
