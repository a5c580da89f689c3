// Edge-walk SIL, edge detection (Mower, "Fast Image-Space Silhouette Extraction", 3.1): a full-screen pass over the triangle-ID raster.
// Pixel p whose nearest surface is toward-facing (triangle T, visible at p) tests T against every
// distinct away-facing triangle A whose ID lies in the (2 u_radius + 1)^2 neighbourhood of p;
// when they share an edge in 3-space, the edge lies on the contour and is appended to the edge
// list. Contour triangles are often thinner than a pixel and sampled on one side only, so each
// sampled triangle (toward at p, or away at p) also looks up its opposite-facing neighbours
// across its three edges in the edge hash table (once per triangle). The walk pass
// (edge_walk_sil.walk.comp.glsl) continues along the contour from the found edges and the line
// pass (edge_walk_sil.lines.*) draws them. Pairs that do not touch (occluders, farther terrain,
// mesh borders, hole rims) never match. Writes 0 to the mask (clearing it for the line pass).
#include "common.glsl"
#include "edge_walk_sil.common.glsl"

layout(binding = 0) uniform sampler2D u_toward;
layout(binding = 1) uniform sampler2D u_away;
layout(std430, binding = 2) readonly buffer PixelIds { uint pixel_ids[]; };
uniform int u_radius;

layout(location = 0) out float o_silhouette;

// Appends the edges toward T (ID t) shares with away A (ID a).
void match(uint t, Tri T, uint a, Tri A) {
    float tol = pair_tolerance(T, A);
    if (distance(T.centre, A.centre) > T.radius + A.radius + tol) return;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) match_edges(t, T, i, a, A, j, tol);
}

// Once per triangle (flag bit 6 toward / 7 away): its opposite-facing hash neighbours.
void neighbours_once(uint x, bool x_toward) {
    uint bit = x_toward ? 1u << 6 : 1u << 7;
    if ((atomicOr(edge_flags[x - 1u], bit) & bit) != 0u) return;
    Tri X = load(x);
    for (int i = 0; i < 3; ++i) {
        int j;
        float tol = u_tolerance * X.longest + 1.0e-6 * (length(X.centre) + X.radius);
        uint y = hash_neighbour(x, X.c[i], X.c[(i + 1) % 3], tol, x_toward ? 0 : 1, j);
        if (y == 0u) continue;
        Tri Y = load(y);
        if (x_toward) match_edges(x, X, i, y, Y, j, pair_tolerance(X, Y));
        else match_edges(y, Y, j, x, X, i, pair_tolerance(Y, X));
    }
}

void main() {
    o_silhouette = 0.0;
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_toward, 0);
    uint a_here = pixel_ids[2 * (p.y * size.x + p.x) + 1];
    if (a_here != 0u) neighbours_once(a_here, false);
    uint t_id = pixel_ids[2 * (p.y * size.x + p.x)];
    float t = texelFetch(u_toward, p, 0).r;
    if (t_id == 0u || t >= PENINK_FAR || texelFetch(u_away, p, 0).r < t) return;
    neighbours_once(t_id, true);
    Tri T = load(t_id);
    uint seen[8] = uint[8](0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u);
    int n_seen = 0;
    for (int dy = -u_radius; dy <= u_radius; ++dy)
        for (int dx = -u_radius; dx <= u_radius; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            uint a_id = pixel_ids[2 * (q.y * size.x + q.x) + 1];
            bool dup = a_id == 0u;
            for (int k = 0; k < 8; ++k) dup = dup || seen[k] == a_id;
            if (dup) continue;
            seen[n_seen & 7] = a_id, ++n_seen;
            match(t_id, T, a_id, load(a_id));
        }
}
