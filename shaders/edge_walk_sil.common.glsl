// Edge-walk SIL, shared by the detection and walk passes (Mower, "Fast Image-Space Silhouette Extraction", 3.1): the triangle list
// (3 eye-relative corners per ID, metres; w of corner 0 = 1 for toward-facing), per-triangle
// flags (bits 0-2: T's edge i appended, 3-5: A's edge j appended, 6/7: hash neighbours looked up
// as toward/away), the silhouette edge list (2 points per edge; w holds the toward and away IDs
// as float bits) with its atomic counter, and the edge hash table of edge_walk_sil.geom.glsl.
// Edges "share" when they lie on each other within a tolerance: u_tolerance times the longer
// triangle edge plus 1e-6 of the eye distance, which also matches crack fragments (two patches'
// slightly different floats of one edge, T-junctions: the overlapping part is used).
layout(std430, binding = 0) buffer Counter { uint tri_count; uint tri_capacity; uint edge_count; uint edge_capacity; };
layout(std430, binding = 1) readonly buffer Triangles { vec4 tri_corners[]; };
layout(std430, binding = 3) buffer EdgeFlags { uint edge_flags[]; };
layout(std430, binding = 4) buffer Edges { vec4 edge_points[]; };
layout(std430, binding = 5) readonly buffer EdgeTable { uint edge_table[]; };
uniform float u_tolerance;
uniform float u_cell;  // metres: hash cell size
uniform uint u_table_mask;

struct Tri { vec3 c[3]; vec3 centre; float radius, longest; bool toward; };

Tri load(uint id) {
    Tri t;
    for (int i = 0; i < 3; ++i) t.c[i] = tri_corners[3u * (id - 1u) + uint(i)].xyz;
    t.toward = tri_corners[3u * (id - 1u)].w > 0.5;
    t.centre = (t.c[0] + t.c[1] + t.c[2]) / 3.0;
    t.radius = 0.0, t.longest = 0.0;
    for (int i = 0; i < 3; ++i) {
        t.radius = max(t.radius, distance(t.c[i], t.centre));
        t.longest = max(t.longest, distance(t.c[i], t.c[(i + 1) % 3]));
    }
    return t;
}

float point_segment(vec3 p, vec3 a, vec3 b) {
    vec3 d = b - a;
    float t = clamp(dot(p - a, d) / max(dot(d, d), 1e-30), 0.0, 1.0);
    return distance(p, a + d * t);
}

float pair_tolerance(Tri T, Tri A) {
    return u_tolerance * max(T.longest, A.longest) + 1.0e-6 * (length(T.centre) + T.radius);
}

// The common part of segments (a0,a1) and (b0,b1) when they lie on each other within tol: the
// first two end points (farther than tol apart) that lie on the other segment. kind: 0 = the
// whole of a, 1 = the whole of b, 2 = a partial overlap.
bool shared_part(vec3 a0, vec3 a1, vec3 b0, vec3 b1, float tol, out vec3 s0, out vec3 s1, out int kind) {
    bool on[4] = bool[4](point_segment(a0, b0, b1) <= tol, point_segment(a1, b0, b1) <= tol,
                         point_segment(b0, a0, a1) <= tol, point_segment(b1, a0, a1) <= tol);
    vec3 pts[4] = vec3[4](a0, a1, b0, b1);
    kind = on[0] && on[1] ? 0 : (on[2] && on[3] ? 1 : 2);
    int n = 0;
    for (int i = 0; i < 4; ++i) {
        if (!on[i]) continue;
        if (n == 0) s0 = pts[i], n = 1;
        else if (distance(pts[i], s0) > tol) { s1 = pts[i]; return true; }
    }
    return false;
}

void append_edge(vec3 s0, vec3 s1, uint t, uint a) {
    uint k = atomicAdd(edge_count, 1u);
    if (k < edge_capacity)
        edge_points[2u * k] = vec4(s0, uintBitsToFloat(t)), edge_points[2u * k + 1u] = vec4(s1, uintBitsToFloat(a));
}

// Appends the part of toward T's edge i that away A's edge j shares (once, keyed by the
// contained edge); true when it was appended now.
bool match_edges(uint t, Tri T, int i, uint a, Tri A, int j, float tol) {
    vec3 s0, s1;
    int kind;
    if (!shared_part(T.c[i], T.c[(i + 1) % 3], A.c[j], A.c[(j + 1) % 3], tol, s0, s1, kind)) return false;
    uint owner = kind == 1 ? a : t, bit = kind == 1 ? 1u << (3 + j) : 1u << i;
    if (kind != 2 && (atomicOr(edge_flags[owner - 1u], bit) & bit) != 0u) return false;
    append_edge(s0, s1, t, a);
    return true;
}

uint cell_hash(ivec3 c) { return (uint(c.x) * 73856093u) ^ (uint(c.y) * 19349663u) ^ (uint(c.z) * 83492791u); }

// The triangle (not x) with an edge j lying on segment (a, b) within tol, found in the edge hash
// table: the mid-point's cell, and the next cell along each axis where the mid-point lies within
// 15 % of a cell boundary. want: 0 away-facing, 1 toward, 2 either. Returns 0 when none.
uint hash_neighbour(uint x, vec3 a, vec3 b, float tol, int want, out int j) {
    vec3 m = (a + b) * 0.5 / u_cell;
    ivec3 base = ivec3(floor(m));
    vec3 f = m - vec3(base);
    ivec3 step = ivec3(greaterThan(f, vec3(0.85))) - ivec3(lessThan(f, vec3(0.15)));
    for (int n = 0; n < 8; ++n) {
        ivec3 o = ivec3(n & 1, (n >> 1) & 1, (n >> 2) & 1) * step;
        if (n > 0 && o == ivec3(0)) continue;
        uint h = cell_hash(base + o) & u_table_mask;
        for (uint k = 0u; k <= u_table_mask; ++k, h = (h + 1u) & u_table_mask) {
            uint code = edge_table[h];
            if (code == 0u) break;
            uint y = code >> 2;
            if (y == x || (want != 2 && (tri_corners[3u * (y - 1u)].w > 0.5) != (want == 1))) continue;
            j = int(code & 3u);
            vec3 c0 = tri_corners[3u * (y - 1u) + uint(j)].xyz, c1 = tri_corners[3u * (y - 1u) + uint((j + 1) % 3)].xyz;
            if (point_segment(c0, a, b) <= tol && point_segment(c1, a, b) <= tol) return y;
        }
    }
    return 0u;
}
