// Edge-walk SIL, triangle-ID pass, fragment stage: a fragment whose eye distance equals (within
// a relative 1e-5) the nearest toward- or away-facing distance the TFT/AFT pass found at its
// pixel writes its triangle ID to that pixel's toward or away slot of the ID buffer (two uints
// per pixel, row 0 = bottom as in GL). No colour output.
#include "common.glsl"

in vec3 g_from_eye;
uniform vec4 u_view;  // common.glsl's camera: depth along the view direction when orthographic
flat in uint g_id;

layout(binding = 0) uniform sampler2D u_toward;
layout(binding = 1) uniform sampler2D u_away;
layout(std430, binding = 2) buffer PixelIds { uint pixel_ids[]; };
uniform int u_width;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float d = view_depth(g_from_eye, vec3(0.0), u_view);
    bool toward = gl_FrontFacing;
    float nearest = toward ? texelFetch(u_toward, p, 0).r : texelFetch(u_away, p, 0).r;
    if (g_id != 0u && d <= nearest * (1.0 + 1.0e-5))
        pixel_ids[2 * (p.y * u_width + p.x) + (toward ? 0 : 1)] = g_id;
}
