// A run of consecutive vertices in a shared vertex array: a polyline stored as [first, first +
// count) (drainage lines, scored crease and ridge polylines); polylines stored so, with a normal
// per vertex; and the vertex layout the DM pass reads (render/dm.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace penink {

struct VertexRun {
    std::uint32_t first = 0, count = 0;  // vertices [first, first + count)
};

// Polylines as runs of one vertex array: world positions (local metres) and unit surface normals
// (zero: off the modelled surface).
struct VertexLines {
    std::vector<glm::vec3> positions, normals;
    std::vector<VertexRun> runs;
};

// One vertex as the DM pass reads it (std430: two vec4): position (local metres), normalised flow,
// unit normal.
struct DmVertex {
    glm::vec3 position;
    float flow = 0.0f;
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    float unused = 0.0f;
};

}  // namespace penink
