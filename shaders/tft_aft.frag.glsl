// TFT/AFT pass, fragment stage. u_mode 0 (combined, one geometry pass): toward-facing fragments
// write their eye distance to target 0 and away-facing ones to target 1, the other target gets
// PENINK_FAR; MIN blending keeps the nearest of each. u_mode 1/2 (separate TFT / AFT passes with
// face culling and a depth test): the fragment's eye distance to target 0.
#include "common.glsl"

in vec3 t_from_eye;
layout(location = 0) out float o_toward;
layout(location = 1) out float o_away;

uniform int u_mode;

void main() {
    float d = length(t_from_eye);
    bool toward = gl_FrontFacing;
    if (u_mode == 0) {
        o_toward = toward ? d : PENINK_FAR;
        o_away = toward ? PENINK_FAR : d;
    } else {
        o_toward = d;
        o_away = d;
    }
}
