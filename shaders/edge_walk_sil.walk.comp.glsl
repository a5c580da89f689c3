// Edge-walk SIL, contour walk (Mower, "Fast Image-Space Silhouette Extraction", 3.1): for each silhouette edge e = (v, w) appended in
// the previous round (IDs u_first .. u_end - 1 of the edge list), walk the fan of triangles
// around each end point starting at e's toward triangle, away from e, across shared edges found
// in the edge hash table, until the facing flips: that edge is the contour's next edge at the end
// point and is appended (once), and the walk goes on from its other end point. Rounds repeat until no new edge appears, so the whole contour
// chain is found from the few edges whose thin triangles the ID raster sampled; the walk stops
// at mesh borders and at cracks no hash lookup bridges (other sampled edges restart it).
#include "edge_walk_sil.common.glsl"

layout(local_size_x = 64) in;
uniform uint u_first, u_end;

int nearest_corner(Tri X, vec3 p) {
    int k = 0;
    for (int i = 1; i < 3; ++i) if (distance(X.c[i], p) < distance(X.c[k], p)) k = i;
    return k;
}

// Walks the fan around v from triangle x, away from edge (v, w); on a facing flip appends that
// contour edge (v, u) and, when it is new, goes on from its toward triangle around u.
void walk(uint x, vec3 v, vec3 w) {
    for (int step = 0; step < 256; ++step) {
        Tri X = load(x);
        int kv = nearest_corner(X, v), kw = nearest_corner(X, w), ku = 3 - kv - kw;
        if (kv == kw) return;
        int i = (kv + 1) % 3 == ku ? kv : ku;  // X's edge (v, u)
        float tol = u_tolerance * X.longest + 1.0e-6 * (length(X.centre) + X.radius);
        int j;
        uint y = hash_neighbour(x, X.c[kv], X.c[ku], tol, 2, j);
        if (y == 0u) return;
        Tri Y = load(y);
        if (Y.toward == X.toward) {
            x = y, w = X.c[ku];
            continue;
        }
        bool added = X.toward ? match_edges(x, X, i, y, Y, j, pair_tolerance(X, Y))
                              : match_edges(y, Y, j, x, X, i, pair_tolerance(Y, X));
        if (!added) return;
        x = X.toward ? x : y, w = X.c[kv], v = X.c[ku];
    }
}

void main() {
    uint e = u_first + gl_GlobalInvocationID.x;
    if (e >= u_end) return;
    vec4 p0 = edge_points[2u * e], p1 = edge_points[2u * e + 1u];
    uint t = floatBitsToUint(p0.w);
    walk(t, p0.xyz, p1.xyz);
    walk(t, p1.xyz, p0.xyz);
}
