// Adjacency SIL (Mower, "Fast Image-Space Silhouette Extraction", 3.1), ID pass, geometry stage:
// each tessellated triangle takes the next ID (1-based, in emission order) and appends its three
// world vertices (local metres, exactly as the tessellation evaluation stage computed them) to
// the triangle list, the paper's transform-feedback capture. Triangles past the list's capacity
// are counted (the host grows the list and redraws) and get ID 0.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 t_world[];
flat out uint g_id;

layout(std430, binding = 0) buffer Counter { uint tri_count; uint tri_capacity; };
layout(std430, binding = 1) writeonly buffer Triangles { vec4 tri_corners[]; };

void main() {
    uint index = atomicAdd(tri_count, 1u);
    uint id = 0u;
    if (index < tri_capacity) {
        for (int i = 0; i < 3; ++i) tri_corners[3u * index + uint(i)] = vec4(t_world[i], 0.0);
        id = index + 1u;
    }
    for (int i = 0; i < 3; ++i) {
        g_id = id;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
