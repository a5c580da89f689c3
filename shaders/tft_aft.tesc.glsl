// TFT/AFT pass, tessellation control: builds the PN control points once per patch, culls
// patches whose control hull is outside the frustum, and sets each edge's level from its
// projected length (pixels / u_target_px, clamped to [1, u_max_level]; an edge's level depends
// on its two end points only, so neighbouring patches agree and no cracks open). u_patch_level 1:
// every edge takes the patch's largest level (one level per patch: neighbours disagree and
// T-junction cracks open; kept to reproduce that case).
#include "common.glsl"

layout(vertices = 3) out;

in vec3 v_position[];
in vec3 v_normal[];
patch out vec3 pn_b[10];
patch out vec3 pn_n[6];

uniform mat4 u_view_proj;
uniform vec2 u_viewport;     // pixels
uniform float u_target_px;   // wanted tessellated edge length, pixels
uniform float u_max_level;
uniform int u_no_cull;       // 1: keep every patch (bench: culling off); unset = 0 = cull
uniform int u_patch_level;   // 1: one level per patch; unset = 0 = per edge

float edge_level(vec4 a, vec4 b) {
    if (a.w <= 0.0 || b.w <= 0.0) return u_max_level;
    float len = distance(clip_to_pixels(a, u_viewport), clip_to_pixels(b, u_viewport));
    return clamp(ceil(len / u_target_px), 1.0, u_max_level);
}

void main() {
    if (gl_InvocationID != 0) return;
    vec3 b[10];
    vec3 n[6];
    pn_control_points(v_position[0], v_position[1], v_position[2],
                      normalize(v_normal[0]), normalize(v_normal[1]), normalize(v_normal[2]), b, n);
    pn_b = b;
    pn_n = n;
    vec4 c[10];
    for (int i = 0; i < 10; ++i) c[i] = u_view_proj * vec4(b[i], 1.0);
    if (u_no_cull == 0 && outside_frustum(c)) {
        gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = 0.0;
        gl_TessLevelInner[0] = 0.0;
        return;
    }
    gl_TessLevelOuter[0] = edge_level(c[1], c[2]);
    gl_TessLevelOuter[1] = edge_level(c[2], c[0]);
    gl_TessLevelOuter[2] = edge_level(c[0], c[1]);
    gl_TessLevelInner[0] = max(gl_TessLevelOuter[0], max(gl_TessLevelOuter[1], gl_TessLevelOuter[2]));
    if (u_patch_level == 1)
        gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = gl_TessLevelInner[0];
}
