#version 430 core
// RadialGhostNodes — the ghost nodes of radial view-based culling (docs/culling.md, "Ghost
// triangles"): one invocation per ghost node, its position at the start of the substep (the
// positions x0) and at its end (the predicted positions x1), each the mean of its boundary loop's
// nodes, summed in loop order (so the result does not depend on scheduling). The ghost fan then
// moves with its loop; classification assumes the node moves linearly between the two, which
// defines the ghost surface during the substep (any closing surface serves the theorem of decision
// 0025). Nothing here needs to be exact: every later decision reads these stored floats.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; };
layout(std430, binding = GLC_BIND_RADIAL_GHOST_LOOPS) readonly buffer RadialGhostLoopsBuf { uint g_loops[]; };
layout(std430, binding = GLC_BIND_RADIAL_GHOST_POSITIONS) writeonly buffer RadialGhostPositionsBuf { vec4 g_ghostPositions[]; };

uniform uint u_ghostNodeCount;

void main() {
    uint ghost = globalIndex();
    if (ghost >= u_ghostNodeCount) return;
    uint first = g_loops[ghost], end = g_loops[ghost + 1u];
    vec3 start = vec3(0.0), finish = vec3(0.0);
    for (uint k = first; k < end; ++k) {
        uint node = g_loops[k];
        start += g_start[node].xyz;
        finish += g_end[node].xyz;
    }
    float count = float(max(end - first, 1u));
    g_ghostPositions[2u * ghost] = vec4(start / count, 1.0);
    g_ghostPositions[2u * ghost + 1u] = vec4(finish / count, 1.0);
}
