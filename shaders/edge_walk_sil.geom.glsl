// Edge-walk SIL, triangle-ID pass, geometry stage (Mower, "Fast Image-Space Silhouette Extraction", 3.1): every tessellated triangle
// gets an ID (1-based, in emission order) and is written to the triangle SSBO as three
// eye-relative corner positions (metres); w of the first corner is its facing, 1 when
// n . (towards the viewer) > 0 (toward), 0 otherwise (common.glsl's camera: an orthographic
// view's viewer direction is the view direction reversed). Its "edge already drawn" flags (used by the detection
// pass to append each silhouette edge once) are cleared here, and its three edges are inserted
// into the edge hash table (open addressing, key = the cell of the edge's mid-point, value =
// ID * 4 + edge index), through which the detection pass finds a triangle's 3-space neighbours. Triangles past the buffer's capacity
// are still counted (the host grows the buffer and redraws) and get ID 0 (none).
#include "common.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 t_world[];
out vec3 g_from_eye;
uniform vec3 u_eye;
uniform vec4 u_view;
flat out uint g_id;

layout(std430, binding = 0) buffer Counter { uint tri_count; uint tri_capacity; uint edge_count; uint edge_capacity; };
layout(std430, binding = 1) writeonly buffer Triangles { vec4 tri_corners[]; };
layout(std430, binding = 3) writeonly buffer EdgeFlags { uint edge_flags[]; };
layout(std430, binding = 5) buffer EdgeTable { uint edge_table[]; };
uniform float u_cell;       // metres: hash cell size
uniform uint u_table_mask;  // table size - 1 (a power of two)

uint cell_hash(ivec3 c) { return (uint(c.x) * 73856093u) ^ (uint(c.y) * 19349663u) ^ (uint(c.z) * 83492791u); }

void insert_edge(uint code, vec3 a, vec3 b) {
    uint h = cell_hash(ivec3(floor((a + b) * 0.5 / u_cell))) & u_table_mask;
    for (uint k = 0u; k <= u_table_mask && atomicCompSwap(edge_table[h], 0u, code) != 0u; ++k) h = (h + 1u) & u_table_mask;
}

void main() {
    uint index = atomicAdd(tri_count, 1u);
    uint id = 0u;
    if (index < tri_capacity) {
        vec3 a = t_world[0] - u_eye, b = t_world[1] - u_eye, c = t_world[2] - u_eye;
        float toward = dot(cross(b - a, c - a), toward_viewer(a, vec3(0.0), u_view)) > 0.0 ? 1.0 : 0.0;
        tri_corners[3u * index] = vec4(a, toward);
        tri_corners[3u * index + 1u] = vec4(b, 0.0);
        tri_corners[3u * index + 2u] = vec4(c, 0.0);
        edge_flags[index] = 0u;
        insert_edge(4u * (index + 1u), a, b);
        insert_edge(4u * (index + 1u) + 1u, b, c);
        insert_edge(4u * (index + 1u) + 2u, c, a);
        id = index + 1u;
    }
    for (int i = 0; i < 3; ++i) {
        g_from_eye = t_world[i] - u_eye;
        g_id = id;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
