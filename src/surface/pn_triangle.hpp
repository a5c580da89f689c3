// Curved PN triangles (Vlachos et al. 2001, "Curved PN Triangles"): the 10 cubic Bezier control
// points and 6 quadratic normal coefficients of a flat triangle with vertex normals, and their
// evaluation at barycentric coordinates. This is the CPU reference of shaders/common.glsl's
// pn_* functions (same formulas, same order), used by tests and the drainage resampler.
// Barycentric b = (b0, b1, b2) weights vertices (p0, p1, p2), like gl_TessCoord.
#pragma once
#include <array>

#include <glm/vec3.hpp>

namespace penink {

struct PnPatch {
    // b[0]=b300 (p0), b[1]=b030 (p1), b[2]=b003 (p2), b[3]=b210, b[4]=b120, b[5]=b021,
    // b[6]=b012, b[7]=b102, b[8]=b201, b[9]=b111.
    std::array<glm::vec3, 10> b;
    // n[0]=n200, n[1]=n020, n[2]=n002, n[3]=n110, n[4]=n011, n[5]=n101.
    std::array<glm::vec3, 6> n;
};

PnPatch pn_patch(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                 const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& n2);

glm::vec3 pn_position(const PnPatch& patch, const glm::vec3& bary);
glm::vec3 pn_normal(const PnPatch& patch, const glm::vec3& bary);  // unit length

// pn_position(patch, bary).z and pn_normal(patch, bary) (into `normal`) of the patch
// pn_patch(p0, p1, p2, n0, n1, n2), the same floats, without the x and y of the control points
// (a height field's draping needs only the height: about half the work).
float pn_height_normal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& n0,
                       const glm::vec3& n1, const glm::vec3& n2, const glm::vec3& bary, glm::vec3& normal);
// pn_height_normal of four patches at once (z[i], normal[i] of patch p[i], n[i] at t[i]), the
// same floats, on 4-wide vector lanes.
void pn_height_normal4(const glm::vec3 p[4][3], const glm::vec3 n[4][3], const glm::vec3 t[4], float z[4],
                       glm::vec3 normal[4]);

}  // namespace penink
