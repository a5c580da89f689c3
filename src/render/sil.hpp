// SIL pass, Toward/Away algorithm (Mower, "Fast Image-Space Silhouette Extraction", 3.2): a full-screen pass over the TFT and AFT
// eye-distance textures producing an R8 silhouette-pixel texture (1 = silhouette), same size.
#pragma once
#include "render/gl_objects.hpp"

namespace penink {

class SilPass {
public:
    SilPass(const GlApi& gl, int width, int height);
    // Returns GPU milliseconds. min_gap: relative eye-distance gap between the away fragment
    // and the farther toward neighbour (0 = any).
    double draw(GLuint toward_texture, GLuint away_texture, float min_gap);
    GLuint silhouette_texture() const { return mask_.id(); }

private:
    const GlApi* gl_;
    int width_, height_;
    GlHandle program_, mask_, fb_, empty_vao_;
    GpuTimer timer_;
};

}  // namespace penink
