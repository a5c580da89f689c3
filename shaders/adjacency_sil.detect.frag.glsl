// Adjacency SIL, detection (seed 001, 3.1): pixel p is a silhouette pixel when its nearest
// surface is toward-facing (triangle T) and the contour through T, found from the away-facing
// triangles A nearest at p and its 8 neighbours, projects within u_half_width pixels of p's
// centre. A front triangle T and a back triangle A that touch in 3-space meet on the contour:
// each corner of T that A touches is a contour vertex, and an edge of T whose two corners are
// contour vertices is a contour edge (touched with A, or with the fan of back triangles around
// it). "Touch": corners within u_tolerance times the larger triangle's longest edge (plus float
// precision); crack fallback: a corner of one lying on an edge of the other within that
// tolerance (T-junctions, patch-edge points that two patches evaluated to slightly different
// floats) counts as a contour point. The mask is thus the projected contour itself, not every
// pixel where A lies behind T. Where T touches the contour only at a corner farther than
// u_half_width (thin, sub-pixel contour triangles that no pixel centre samples), p is marked
// when it also passes the Toward/Away test (an away fragment behind T at p, a neighbour's toward
// fragment farther still). Pairs that do not touch (occluders, farther terrain, mesh borders and
// hole rims) are never silhouettes, so hidden contours are not drawn.
#include "common.glsl"

layout(binding = 0) uniform sampler2D u_toward;
layout(binding = 1) uniform sampler2D u_away;
layout(std430, binding = 1) readonly buffer Triangles { vec4 tri_corners[]; };
layout(std430, binding = 2) readonly buffer PixelIds { uint pixel_ids[]; };
uniform float u_tolerance;
uniform float u_half_width;   // pixels
uniform mat4 u_view_proj_rel; // eye-relative world -> clip
uniform vec2 u_viewport;

layout(location = 0) out float o_silhouette;

float point_segment(vec3 p, vec3 a, vec3 b) {
    vec3 d = b - a;
    float t = clamp(dot(p - a, d) / max(dot(d, d), 1e-30), 0.0, 1.0);
    return distance(p, a + d * t);
}

struct Tri { vec3 c[3]; };

Tri load(uint id) {
    Tri t;
    for (int i = 0; i < 3; ++i) t.c[i] = tri_corners[3u * (id - 1u) + uint(i)].xyz;
    return t;
}

float touch_tolerance(Tri a, Tri b) {
    float scale = 0.0, far_point = 0.0;
    for (int i = 0; i < 3; ++i) {
        scale = max(scale, max(distance(a.c[i], a.c[(i + 1) % 3]), distance(b.c[i], b.c[(i + 1) % 3])));
        far_point = max(far_point, max(length(a.c[i]), length(b.c[i])));
    }
    return u_tolerance * scale + 1.0e-6 * far_point;
}

// Window pixel of an eye-relative point; false behind the eye.
bool project(vec3 p, out vec2 px) {
    vec4 k = u_view_proj_rel * vec4(p, 1.0);
    px = clip_to_pixels(k, u_viewport);
    return k.w > 0.0;
}

float pixel_segment(vec2 p, vec2 a, vec2 b) {
    vec2 d = b - a;
    float t = clamp(dot(p - a, d) / max(dot(d, d), 1e-20), 0.0, 1.0);
    return distance(p, a + d * t);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_toward, 0);
    o_silhouette = 0.0;
    uint t_id = pixel_ids[2 * (p.y * size.x + p.x)];
    float t = texelFetch(u_toward, p, 0).r;
    if (t_id == 0u || t >= PENINK_FAR || texelFetch(u_away, p, 0).r < t) return;
    Tri T = load(t_id);
    bool on_contour[3] = bool[3](false, false, false);
    bool has_extra = false;
    vec3 extra = vec3(0.0);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            uint a_id = pixel_ids[2 * (q.y * size.x + q.x) + 1];
            if (a_id == 0u) continue;
            Tri A = load(a_id);
            float tol = touch_tolerance(T, A);
            bool touched = false;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    if (distance(T.c[i], A.c[j]) <= tol) on_contour[i] = touched = true;
            if (touched) continue;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) {
                    if (point_segment(T.c[i], A.c[j], A.c[(j + 1) % 3]) <= tol) on_contour[i] = true;
                    if (point_segment(A.c[i], T.c[j], T.c[(j + 1) % 3]) <= tol) has_extra = true, extra = A.c[i];
                }
        }
    }
    vec2 s[3];
    bool ok[3];
    for (int i = 0; i < 3; ++i) ok[i] = on_contour[i] && project(T.c[i], s[i]);
    float best = 1.0e9;
    for (int i = 0; i < 3; ++i) {
        if (!ok[i]) continue;
        best = min(best, distance(gl_FragCoord.xy, s[i]));
        int j = (i + 1) % 3;
        if (ok[j]) best = min(best, pixel_segment(gl_FragCoord.xy, s[i], s[j]));
    }
    vec2 e;
    if (has_extra && project(extra, e)) best = min(best, distance(gl_FragCoord.xy, e));
    if (best <= u_half_width) {
        o_silhouette = 1.0;
        return;
    }
    // Contour confirmed but only touched at a corner far from p: localise it like Toward/Away,
    // at the front side of the depth jump to farther toward-facing surface behind the fold.
    float a = texelFetch(u_away, p, 0).r;
    if (!(on_contour[0] || on_contour[1] || on_contour[2] || has_extra) || a >= PENINK_FAR) return;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 r = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
            float tr = texelFetch(u_toward, r, 0).r;
            if (tr < PENINK_FAR && tr > a) o_silhouette = 1.0;
        }
}
