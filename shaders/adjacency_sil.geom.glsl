// Adjacency SIL, triangle-ID pass, geometry stage (seed 001, 3.1): every tessellated triangle
// gets an ID (1-based, in emission order) and is written to the triangle SSBO as three
// eye-relative corner positions (metres); w of the first corner is its facing, 1 when
// n . (eye - p) > 0 (toward), 0 otherwise. Triangles past the buffer's capacity are still counted
// (the host grows the buffer and redraws) and get ID 0 (none).
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 t_from_eye[];
out vec3 g_from_eye;
flat out uint g_id;

layout(std430, binding = 0) buffer Counter { uint tri_count; uint tri_capacity; };
layout(std430, binding = 1) writeonly buffer Triangles { vec4 tri_corners[]; };

void main() {
    uint index = atomicAdd(tri_count, 1u);
    uint id = 0u;
    if (index < tri_capacity) {
        vec3 a = t_from_eye[0], b = t_from_eye[1], c = t_from_eye[2];
        float toward = dot(cross(b - a, c - a), -a) > 0.0 ? 1.0 : 0.0;
        tri_corners[3u * index] = vec4(a, toward);
        tri_corners[3u * index + 1u] = vec4(b, 0.0);
        tri_corners[3u * index + 2u] = vec4(c, 0.0);
        id = index + 1u;
    }
    for (int i = 0; i < 3; ++i) {
        g_from_eye = t_from_eye[i];
        g_id = id;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
