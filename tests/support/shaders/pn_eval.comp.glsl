// PN evaluation pass, test support only (tests/support/pn_eval.hpp; not among the production
// shaders/): evaluates common.glsl's pn_control_points / pn_position / pn_normal (the functions
// the TFT/AFT tessellation stages use; the include resolves to the embedded shaders/common.glsl)
// at given barycentric points of given patches, so the GPU maths can be checked against the CPU
// reference (src/surface/pn_triangle.hpp).
#include "common.glsl"

layout(local_size_x = 64) in;

struct PnQuery {
    vec4 p[3];     // patch vertex positions (w unused)
    vec4 n[3];     // patch vertex normals
    vec4 bary;     // barycentric (t0, t1, t2), w unused
};
layout(std430, binding = 0) readonly buffer Queries { PnQuery queries[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };  // position, normal pairs

uniform uint u_count;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec3 b[10];
    vec3 n[6];
    PnQuery q = queries[i];
    pn_control_points(q.p[0].xyz, q.p[1].xyz, q.p[2].xyz, q.n[0].xyz, q.n[1].xyz, q.n[2].xyz, b, n);
    results[2u * i] = vec4(pn_position(b, q.bary.xyz), 1.0);
    results[2u * i + 1u] = vec4(pn_normal(n, q.bary.xyz), 0.0);
}
