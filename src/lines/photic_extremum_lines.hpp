// Photic extremum lines (Xie et al. 2007, "An Effective Illustrative Visualization Framework
// Based on Photic Extremum Lines", sec. 3): on a TriangleMesh with unit vertex normals, the
// illumination phi = max(0, n . l) (light at the eye by default: l = unit vector from the
// vertex to the eye), its per-vertex gradient (face gradients averaged with Meyer et al. 2001
// mixed Voronoi areas, projected on the tangent plane), g = |grad phi| / max |grad phi|,
// w = grad phi / |grad phi|, D_w g and D_w^2 g; PELs are the zero crossings of D_w g on edges
// where D_w^2 g < 0 and g >= tau, at most one segment per triangle. Also object-space mesh
// silhouettes: the zero set of n . (eye - p) interpolated inside each triangle.
// Post-processing as the paper does it (docs/reproduction.md, "PELs"): PELs take third derivatives
// of the surface (phi is first order in the normal, D_w g and D_w^2 g two more), so noise in the
// normal field is amplified and the paper smooths the normals before the illumination is
// differentiated; penink's filter is gaussian_filter_normals (surface/mesh_normals.hpp), sigma in
// mean edge lengths ([pels] normal_filter). Two quantities are thresholded: per point g >= tau
// (PelOptions::threshold, [pels] threshold), and per line its strength, the integral of g along
// it (pel_line_strengths / strong_pel_lines, [pels] line_strength in mean edge lengths), which
// drops the short loops noise leaves while long weak-ish lines stay whole.
// All positions are in the mesh's world frame and units; timings in milliseconds.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/triangle_mesh.hpp"

namespace penink {

// A piece of line on the mesh surface, world frame. Edge keys name the mesh edges (vertex pair,
// lower index first) the endpoints lie on, for chaining; ~0 when not on an edge.
struct ObjectSegment {
    glm::vec3 a{0.0f}, b{0.0f};
    float strength = 1.0f;  // normalised |grad phi| for PELs (mean of both ends), 1 otherwise
    std::uint64_t edge_a = ~std::uint64_t(0), edge_b = ~std::uint64_t(0);
};

// An open 3D polyline in world coordinates (closed when the first point repeats at the end).
struct ObjectPolyline {
    std::vector<glm::vec3> points;
    float strength = 1.0f;
    std::string kind;      // "pel", "silhouette", "crease", "boundary", "material", "texture"
    std::string material;  // material name where it applies (feature edges, textures)
};

// Per-mesh constants of the gradient operator; build once, reuse for every frame.
struct PelGeometry {
    std::vector<glm::vec3> grad_basis;  // 3 per triangle: grad of the hat function of each corner
    std::vector<float> corner_weight;   // 3 per triangle: mixed Voronoi area of each corner
    std::vector<float> vertex_weight;   // sum of the corner weights per vertex
};

struct PelOptions {
    float threshold = 0.1f;       // tau on g (0..1); above 1 nothing is drawn
    bool light_at_eye = true;     // l = normalize(eye - p) per vertex
    glm::vec3 light_dir{0, 0, 1}; // otherwise: towards the (directional) light (normalised here)
    bool clamp_diffuse = true;    // phi = max(0, n . l); false: phi = n . l
};

struct PelTimings {  // milliseconds per step of one frame
    double illumination = 0, gradient = 0, magnitude = 0, derivative1 = 0, derivative2 = 0,
           extraction = 0, total = 0;
};

// Per-vertex fields, exposed for tests and debugging.
struct PelField {
    std::vector<float> phi, g, dw, dw2;  // illumination, normalised |grad|, D_w g, D_w^2 g
    std::vector<glm::vec3> w;            // unit gradient direction (zero where grad = 0)
    float max_gradient = 0;              // max |grad phi| before normalisation (1 / units)
};

struct PelResult {
    std::vector<ObjectSegment> segments;
    PelField field;
    PelTimings timings;
};

// Mixed Voronoi area of each corner (Meyer et al. 2001, fig. 4) and hat-function gradients.
PelGeometry pel_geometry(const TriangleMesh& mesh);

// Gradient per vertex of a per-vertex scalar f, projected on the plane normal to `normals`.
std::vector<glm::vec3> vertex_gradient(const TriangleMesh& mesh, const PelGeometry& geom,
                                       const std::vector<glm::vec3>& normals,
                                       const std::vector<float>& f);

// PELs for an eye position (and options.light_dir when the light is not at the eye).
PelResult photic_extremum_lines(const TriangleMesh& mesh, const PelGeometry& geom,
                                const std::vector<glm::vec3>& normals, const glm::vec3& eye,
                                const PelOptions& options = {});

// Line strength (Xie et al., "Photic Extremum Lines": a PEL is kept by its strength along the
// line, not point by point, as ridge-valley lines are by the integral of curvature): for each
// segment, the integral of g (the normalised |grad phi|) along the connected line it belongs to,
// sum of strength x length over the segments joined end to end (end points on the same mesh edge,
// as chain_segments joins them); mesh units of length.
std::vector<float> pel_line_strengths(const std::vector<ObjectSegment>& segments);

// The segments whose line's strength (pel_line_strengths) is at least `min_strength` (mesh
// units); min_strength <= 0 keeps every segment. Short noisy loops go, long lines stay whole.
std::vector<ObjectSegment> strong_pel_lines(const std::vector<ObjectSegment>& segments, float min_strength);

// Object-space silhouettes: per triangle, the segment where the interpolated n . (eye - p)
// crosses zero (front and back facing regions meet).
std::vector<ObjectSegment> mesh_silhouettes(const TriangleMesh& mesh,
                                            const std::vector<glm::vec3>& normals,
                                            const glm::vec3& eye);

// Joins segments sharing an edge key (or, for keyless ends, a bit-identical point) into
// polylines, deterministic order; strength = mean of the segments' strengths.
std::vector<ObjectPolyline> chain_segments(const std::vector<ObjectSegment>& segments,
                                           const std::string& kind);

// The segments outside flat-shaded triangles: a segment whose two edges' four vertex normals
// (`normals`, per vertex) are all equal (within 1e-3) lies in a planar fan, where phi only varies
// with the light direction and its extrema mean nothing. Keyless segments are kept.
std::vector<ObjectSegment> curved_only(std::vector<ObjectSegment> segments, const std::vector<glm::vec3>& normals);

}  // namespace penink
