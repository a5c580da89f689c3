// DM pass (Mower, "Concurrent Drainage Network Rendering", eq. 1-6; conventions.md): writes the
// terms of eq. 6 for every drainage (or divide) vertex and tests it against the TFT eye-distance
// texture:
//   sc = 1 - cos(slope) = 1 - n.z, ic = 1 - clamp(n . l, 0, 1), fc = flow normalised per basin,
//   d = the vertex's eye distance (view depth for an orthographic camera).
// The score itself is computed from them on the CPU (lines/crease_scores.hpp).
// The vertex is lifted off the surface along its normal by u_lift_px pixel footprints (no depth
// fighting) and is visible when its eye distance is within a grazing-aware tolerance of the
// nearest toward-facing surface at its pixel, or when that pixel holds no surface (a silhouette
// vertex lifted past the outline). Vertices with a zero normal (off the rendered surface) and
// outside the frustum are hidden. Output: (sc, ic, fc, d), or (0, 0, 0, PENINK_HIDDEN) when not
// visible.
#include "common.glsl"

layout(local_size_x = 64) in;

struct DmVertex {
    vec4 position_flow;  // world x, y, z (local metres), normalised flow
    vec4 normal;         // unit PN-surface normal, w unused
};
layout(std430, binding = 0) readonly buffer Vertices { DmVertex vertices[]; };
layout(std430, binding = 1) writeonly buffer Terms { vec4 terms[]; };
layout(binding = 0) uniform sampler2D u_toward;

uniform mat4 u_view_proj;
uniform vec3 u_eye;
uniform vec4 u_view;
uniform vec2 u_footprint;      // a pixel's world size at depth d: x d + y
uniform vec3 u_light;          // unit vector towards the light
uniform vec2 u_viewport;
uniform float u_lift_px;
uniform float u_tolerance_px;
uniform uint u_count;

const float PENINK_HIDDEN = -1.0e30;

void main() {
    uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec3 p = vertices[i].position_flow.xyz;
    float flow = vertices[i].position_flow.w;
    vec3 n = vertices[i].normal.xyz;
    float d = view_depth(p, u_eye, u_view);
    float sc = 1.0 - clamp(n.z, 0.0, 1.0);
    float ic = 1.0 - clamp(dot(n, u_light), 0.0, 1.0);

    float footprint = u_footprint.x * d + u_footprint.y;
    vec3 lifted = p + n * (u_lift_px * footprint);
    vec4 c = u_view_proj * vec4(lifted, 1.0);
    vec4 result = vec4(0.0, 0.0, 0.0, PENINK_HIDDEN);
    // A zero normal marks a vertex off the rendered surface: never drawn.
    bool on_surface = dot(n, n) > 0.25;
    if (on_surface && c.w > 0.0 && all(lessThanEqual(abs(c.xyz), vec3(c.w)))) {
        ivec2 q = clamp(ivec2(clip_to_pixels(c, u_viewport)), ivec2(0), ivec2(u_viewport) - 1);
        float t = texelFetch(u_toward, q, 0).r;
        float facing = abs(dot(n, toward_viewer(p, u_eye, u_view)));
        float tolerance = u_tolerance_px * footprint / max(facing, 0.1);
        // No surface at the pixel: the vertex sits on a silhouette (a crest against the sky, the
        // DEM's edge) and the lift took it past the outline; nothing lies in front of it.
        if (t >= PENINK_FAR || view_depth(lifted, u_eye, u_view) <= t + tolerance) result = vec4(sc, ic, flow, d);
    }
    terms[i] = result;
}
