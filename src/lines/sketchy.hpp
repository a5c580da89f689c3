// Sketchy rendering (Potter et al., "NPR-Style 3D Line Textures", section 4.3 "Sketchy Rendering": end points perturbed): seeded
// perturbation of strokes in image pixels (end points moved up to `amount` px in a random
// direction, interior points following smoothly, optional overshoot and repeated strokes), and
// of 3D polylines in world units within each point's tangent plane. Random numbers come from
// splitmix64 on (seed, id, k) (random_bits.hpp): independent of processing order and library.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/drawing.hpp"

namespace penink {

struct SketchParams {
    float amount = 1.5f;         // px; each end point moves by at most this (uniform in the disc)
    float overshoot = 0.0f;      // px; both ends extended along their end tangent (open strokes)
    int repeat = 0;              // extra strokes, each with its own perturbation
};

// Perturbed copy for pass `pass` (0 = the stroke itself, 1..repeat = the extra strokes); depth,
// strength and kind kept. Closed strokes stay closed: both ends take the start offset and no
// overshoot is applied. Interior points take the arc-length blend of the end offsets: |offset| <=
// amount everywhere.
Stroke sketch_stroke(const Stroke& s, const SketchParams& p, std::uint64_t seed, std::uint64_t stroke_id,
                     int pass = 0);

// The stroke and its `repeat` extra copies (passes 0..repeat).
std::vector<Stroke> sketch_copies(const Stroke& s, const SketchParams& p, std::uint64_t seed,
                                  std::uint64_t stroke_id);

// Order-independent id from a stroke's geometry (point count, end points, kind).
std::uint64_t stroke_geometry_id(const Stroke& s);

// 3D version (world units): end points move by up to `amount` within the plane perpendicular to
// their normal; interior points take the arc-length blend of the end offsets projected onto
// their own tangent plane. Points with a zero normal stay. Throws penink::Error when the
// normals are not one per point.
std::vector<glm::vec3> sketch_polyline_3d(const std::vector<glm::vec3>& points,
                                          const std::vector<glm::vec3>& normals, float amount,
                                          std::uint64_t seed, std::uint64_t id);

}  // namespace penink
