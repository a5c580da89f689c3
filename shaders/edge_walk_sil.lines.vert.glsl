// Edge-walk SIL, line pass, vertex stage: vertex gl_VertexID is end point gl_VertexID % 2 of
// silhouette edge gl_VertexID / 2 in the edge SSBO (eye-relative metres), drawn as GL_LINES.
layout(std430, binding = 4) readonly buffer Edges { vec4 edge_points[]; };
uniform mat4 u_view_proj_rel;  // eye-relative world -> clip
out vec3 l_from_eye;

void main() {
    l_from_eye = edge_points[gl_VertexID].xyz;
    gl_Position = u_view_proj_rel * vec4(l_from_eye, 1.0);
}
