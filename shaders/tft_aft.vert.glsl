// TFT/AFT pass, vertex stage: passes world positions and vertex normals to the PN patch.
layout(location = 0) in vec3 a_position;  // world (local metres)
layout(location = 1) in vec3 a_normal;

out vec3 v_position;
out vec3 v_normal;

void main() {
    v_position = a_position;
    v_normal = a_normal;
}
