// Shared by every pass. PN triangles (Vlachos et al. 2001): 10 cubic Bezier control points and
// 6 quadratic normal coefficients, in the order of src/surface/pn_triangle.hpp (the CPU
// reference these functions must match): b300 b030 b003 b210 b120 b021 b012 b102 b201 b111;
// n200 n020 n002 n110 n011 n101. Barycentric t = (t0, t1, t2) weights (p0, p1, p2), as gl_TessCoord.

const float PENINK_FAR = 1.0e30;  // "no surface" in eye-distance images

// The frame's camera (src/render/gl_objects.hpp, set_camera_uniforms): u_view.xyz is the unit
// view direction, u_view.w 1 for an orthographic camera, 0 for a perspective one. Depth is the
// eye distance (perspective) or the distance along the view direction (orthographic), as
// eye_depth in src/core/camera.hpp; a pixel's world size at depth d is u_footprint.x * d +
// u_footprint.y.
float view_depth(vec3 p, vec3 eye, vec4 view) {
    return view.w > 0.5 ? dot(p - eye, view.xyz) : distance(p, eye);
}

// Unit vector from p towards the viewer.
vec3 toward_viewer(vec3 p, vec3 eye, vec4 view) {
    return view.w > 0.5 ? -view.xyz : normalize(eye - p);
}

vec3 pn_edge_point(vec3 pi, vec3 pj, vec3 ni) {
    return (2.0 * pi + pj - dot(pj - pi, ni) * ni) / 3.0;
}

vec3 pn_edge_normal(vec3 pi, vec3 pj, vec3 ni, vec3 nj) {
    vec3 e = pj - pi;
    float ee = dot(e, e);
    float v = ee > 0.0 ? 2.0 * dot(e, ni + nj) / ee : 0.0;
    vec3 n = ni + nj - v * e;
    float len = length(n);
    return len > 0.0 ? n / len : normalize(ni + nj);
}

void pn_control_points(vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2,
                       out vec3 b[10], out vec3 n[6]) {
    b[0] = p0; b[1] = p1; b[2] = p2;
    b[3] = pn_edge_point(p0, p1, n0);
    b[4] = pn_edge_point(p1, p0, n1);
    b[5] = pn_edge_point(p1, p2, n1);
    b[6] = pn_edge_point(p2, p1, n2);
    b[7] = pn_edge_point(p2, p0, n2);
    b[8] = pn_edge_point(p0, p2, n0);
    vec3 e = (b[3] + b[4] + b[5] + b[6] + b[7] + b[8]) / 6.0;
    vec3 v = (p0 + p1 + p2) / 3.0;
    b[9] = e + (e - v) * 0.5;
    n[0] = n0; n[1] = n1; n[2] = n2;
    n[3] = pn_edge_normal(p0, p1, n0, n1);
    n[4] = pn_edge_normal(p1, p2, n1, n2);
    n[5] = pn_edge_normal(p2, p0, n2, n0);
}

vec3 pn_position(vec3 b[10], vec3 t) {
    float w = t.x, u = t.y, v = t.z;
    return b[0] * (w * w * w) + b[1] * (u * u * u) + b[2] * (v * v * v) +
           b[3] * (3.0 * w * w * u) + b[4] * (3.0 * w * u * u) +
           b[5] * (3.0 * u * u * v) + b[6] * (3.0 * u * v * v) +
           b[7] * (3.0 * w * v * v) + b[8] * (3.0 * w * w * v) +
           b[9] * (6.0 * w * u * v);
}

vec3 pn_normal(vec3 n[6], vec3 t) {
    float w = t.x, u = t.y, v = t.z;
    return normalize(n[0] * (w * w) + n[1] * (u * u) + n[2] * (v * v) +
                     n[3] * (w * u) + n[4] * (u * v) + n[5] * (w * v));
}

// Window position (pixels) of a clip-space point; w <= 0 means behind the eye.
vec2 clip_to_pixels(vec4 clip, vec2 viewport) {
    return (clip.xy / clip.w * 0.5 + 0.5) * viewport;
}

// True when every point lies outside the same clip plane (conservative culling of a convex hull).
bool outside_frustum(vec4 c[10]) {
    for (int axis = 0; axis < 3; ++axis) {
        bool all_low = true, all_high = true;
        for (int i = 0; i < 10; ++i) {
            all_low = all_low && c[i][axis] < -c[i].w;
            all_high = all_high && c[i][axis] > c[i].w;
        }
        if (all_low || all_high) return true;
    }
    return false;
}
