// Edge-walk SIL, line pass, fragment stage: a fragment of a silhouette edge is visible, and marks
// its pixel, when its depth (eye distance, or distance along an orthographic view) is at most (1 + u_depth_tolerance) times the nearest toward
// distance at its pixel or one of the 8 neighbours (the contour lies on the front sheet's edge,
// so the pixel centre may see the front sheet slightly nearer; one neighbour beyond the contour
// sees farther surface or sky). Edges hidden behind nearer surface are discarded.
#include "common.glsl"

layout(binding = 0) uniform sampler2D u_toward;
uniform float u_depth_tolerance;
in vec3 l_from_eye;
uniform vec4 u_view;  // common.glsl's camera: depth along the view direction when orthographic
layout(location = 0) out float o_silhouette;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_toward, 0);
    float limit = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            limit = max(limit, texelFetch(u_toward, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0).r);
    if (view_depth(l_from_eye, vec3(0.0), u_view) > limit * (1.0 + u_depth_tolerance)) discard;
    o_silhouette = 1.0;
}
