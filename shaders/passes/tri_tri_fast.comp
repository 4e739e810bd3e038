#version 430 core
// TriTri, fast precision — the narrow phase (seeds/002, Alg. 3): one invocation per candidate face
// pair (indirect dispatch from the candidate count); appends the pair to the intersection list when
// triTriIntersect (common/tri_tri.glsl, Moeller 1997 in float) says the closed triangles meet.
// Fast may be wrong near degeneracies (docs/narrow-phase.md). CPU twin: cpu::fastTrianglesIntersect.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"
#include "common/tri_tri.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_INTERSECTIONS) writeonly buffer IntersectionsBuf { uvec2 g_intersections[]; };

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_CANDIDATES)) return;
    uvec2 pair = g_facePairs[i];
    uvec3 a = faceNodes(pair.x), b = faceNodes(pair.y);
    if (triTriIntersect(g_positions[a.x].xyz, g_positions[a.y].xyz, g_positions[a.z].xyz,
                        g_positions[b.x].xyz, g_positions[b.y].xyz, g_positions[b.z].xyz))
        GLC_APPEND(GLC_LIST_INTERSECTIONS, g_intersections, pair)
}
