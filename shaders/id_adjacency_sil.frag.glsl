// Adjacency SIL (Mower, "Fast Image-Space Silhouette Extraction", 3.1), pixel pass over the
// triangle-ID raster (render/id_adjacency_sil.hpp): pixel p with triangle a is a silhouette pixel
// when a 4-neighbour q holds a triangle b != a farther from the eye that is not adjacent to a in
// 3-space (no common pair of world vertices, nor one with u_vertex_adjacency; with
// u_crack_tolerance > 0, no T-junction either) or holds no surface at all (sky). Unless
// u_mesh_borders is 1, p must also be where the surface turns away (an away fragment behind p's
// at p or an 8-neighbour): DEM cut edges and hole rims, where the triangles beyond are not
// adjacent either, are then left to the outline.
#include "common.glsl"

layout(binding = 0) uniform sampler2D u_toward;  // eye distance, PENINK_FAR where none
layout(binding = 1) uniform sampler2D u_away;
layout(binding = 2) uniform usampler2D u_ids;    // 0 = no surface
layout(std430, binding = 1) readonly buffer Triangles { vec4 tri_corners[]; };
uniform float u_crack_tolerance;  // relative to an edge's length; 0 = off
uniform uint u_triangles;         // IDs above this are not in the list
uniform int u_mesh_borders;       // 1: the ID test alone (borders are silhouettes too)
uniform int u_vertex_adjacency;   // 1: one common vertex is adjacency too (0: the paper's edge test)

layout(location = 0) out float o_silhouette;

void load(uint id, out vec3 c[3]) {
    for (int i = 0; i < 3; ++i) c[i] = tri_corners[3u * (id - 1u) + uint(i)].xyz;
}

float point_segment(vec3 p, vec3 a, vec3 b) {
    vec3 d = b - a;
    float t = clamp(dot(p - a, d) / max(dot(d, d), 1e-30), 0.0, 1.0);
    return distance(p, a + d * t);
}

// True when a vertex of X lies on an edge of Y (within u_crack_tolerance x that edge's length):
// a T-junction, where a finer patch's edge vertex sits on a coarser patch's edge.
bool touches(vec3 X[3], vec3 Y[3]) {
    for (int j = 0; j < 3; ++j) {
        float tol = u_crack_tolerance * distance(Y[j], Y[(j + 1) % 3]);
        for (int i = 0; i < 3; ++i)
            if (point_segment(X[i], Y[j], Y[(j + 1) % 3]) <= tol) return true;
    }
    return false;
}

// Triangles a and b share an edge in 3-space (two common vertices, equal within float rounding
// of world coordinates: 1e-5 of the eye distance t or of the coordinates' size), a vertex (with
// u_vertex_adjacency) or, with crack handling, a T-junction (a vertex of one on an edge of the other).
bool adjacent(uint a, uint b, float t) {
    if (a > u_triangles || b > u_triangles) return true;  // not in the list: no evidence of a silhouette
    vec3 A[3], B[3];
    load(a, A);
    load(b, B);
    float vertex_eps = 1.0e-5 * max(min(t, 1.0e7), length(A[0]));
    int common_vertices = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) common_vertices += distance(A[i], B[j]) <= vertex_eps ? 1 : 0;
    if (common_vertices >= 2 - u_vertex_adjacency) return true;
    return u_crack_tolerance > 0.0 && (touches(A, B) || touches(B, A));
}

// The surface turns away at p: an away fragment behind the toward one at p or an 8-neighbour.
bool turns_away(ivec2 p, float t, ivec2 size) {
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            float a = texelFetch(u_away, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0).r;
            if (a > t && a < PENINK_FAR) return true;
        }
    return false;
}

void main() {
    o_silhouette = 0.0;
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_ids, 0);
    uint a = texelFetch(u_ids, p, 0).r;
    if (a == 0u) return;
    float t = texelFetch(u_toward, p, 0).r;
    const ivec2 steps[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    bool marked = false;
    for (int k = 0; k < 4 && !marked; ++k) {
        ivec2 q = p + steps[k];
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        uint b = texelFetch(u_ids, q, 0).r;
        if (b == a) continue;
        marked = b == 0u || (texelFetch(u_toward, q, 0).r > t && !adjacent(a, b, t));
    }
    if (marked && (u_mesh_borders == 1 || turns_away(p, t, size))) o_silhouette = 1.0;
}
