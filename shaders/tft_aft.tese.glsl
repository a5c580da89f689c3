// TFT/AFT pass, tessellation evaluation: evaluates the PN patch at gl_TessCoord and sends the
// vector from the eye (metres) to the fragment stage, which takes its length (exact per
// fragment; interpolating distances themselves would not be). Orthographic: the vector's
// projection on the view direction, whose length is the depth along it (linear, so exact too).
#include "common.glsl"

layout(triangles, equal_spacing, ccw) in;

patch in vec3 pn_b[10];
patch in vec3 pn_n[6];
out vec3 t_from_eye;
out vec3 t_world;  // the tessellated vertex, world (local metres): the triangle list of id_adjacency_sil

uniform mat4 u_view_proj;
uniform vec3 u_eye;
uniform vec4 u_view;

void main() {
    vec3 b[10] = pn_b;
    vec3 p = pn_position(b, gl_TessCoord);
    t_world = p;
    t_from_eye = u_view.w > 0.5 ? u_view.xyz * dot(p - u_eye, u_view.xyz) : p - u_eye;
    gl_Position = u_view_proj * vec4(p, 1.0);
}
