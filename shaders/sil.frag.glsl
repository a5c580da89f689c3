// SIL pass, Toward/Away algorithm (Mower, "Fast Image-Space Silhouette Extraction", section 3.2): pixel p is a silhouette pixel when it
// holds a toward-facing fragment at eye distance t, an away-facing fragment behind it at a > t
// (at p, or at an 8-neighbour: a back-facing sliver thinner than a pixel can miss p's centre;
// measured on volcano at 1000x750: recall within 1 px 0.63 -> 0.77, precision within 2 px stays
// 1.0), and one of its 8 neighbours holds a toward-facing fragment further still (> a, by the
// relative gap u_min_gap). A neighbour with no surface at all (sky, or beyond the DEM) counts as infinitely
// far, so skylines are silhouettes too; the DEM's cut edges have no away fragment and are not.
#include "common.glsl"

layout(binding = 0) uniform sampler2D u_toward;  // eye distance, PENINK_FAR where none
layout(binding = 1) uniform sampler2D u_away;
uniform float u_min_gap;  // relative depth gap, e.g. 0.001

layout(location = 0) out float o_silhouette;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_toward, 0);
    float t = texelFetch(u_toward, p, 0).r;
    o_silhouette = 0.0;
    if (t >= PENINK_FAR) return;
    // The nearest away fragment behind t at p or an 8-neighbour (a back-facing sliver thinner
    // than a pixel may miss p's own centre).
    float a = PENINK_FAR;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            float aq = texelFetch(u_away, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0).r;
            if (aq > t && aq < a) a = aq;
        }
    }
    if (a >= PENINK_FAR) return;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
            float tq = texelFetch(u_toward, q, 0).r;
            if (tq > a * (1.0 + u_min_gap)) o_silhouette = 1.0;
        }
    }
}
