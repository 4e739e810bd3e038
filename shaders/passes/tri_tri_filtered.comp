#version 430 core
// TriTri, robust precision, first pass — the narrow phase (seeds/002, Alg. 3) with certified
// signs: one invocation per candidate face pair (indirect dispatch from the candidate count).
// glcTriTriFiltered (common/tri_tri_robust.glsl) answers from float filters whose error bound
// holds on any conforming device; a pair it cannot decide is appended, as its candidate index, to
// the undecided list, which tri_tri_exact.comp decides in integer arithmetic
// (docs/narrow-phase.md). Closed triangles that meet have overlapping face boxes, so testing only
// candidates loses no intersection. CPU twin: shader::robustTrianglesIntersect (this library
// compiled as C++) and the exact oracle.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"
#include "common/tri_tri_robust.glsl"
#include "common/radial_cull.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_INTERSECTIONS) writeonly buffer IntersectionsBuf { uvec2 g_intersections[]; };
layout(std430, binding = GLC_BIND_UNDECIDED) writeonly buffer UndecidedBuf { uint g_undecided[]; };

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_CANDIDATES)) return;
    uvec2 pair = g_facePairs[i];
    if (glcRadialCulled(pair.x, pair.y)) { // a free face intersects nothing of its surface
        atomicAdd(g_counters.stats[GLC_STAT_RADIAL_CULLED_TRI_TRI], 1u);
        return;
    }
    uvec3 a = faceNodes(pair.x), b = faceNodes(pair.y);
    int answer = glcTriTriFiltered(g_positions[a.x].xyz, g_positions[a.y].xyz, g_positions[a.z].xyz,
                                   g_positions[b.x].xyz, g_positions[b.y].xyz, g_positions[b.z].xyz);
    if (answer == GLC_UNDECIDED) GLC_APPEND(GLC_LIST_UNDECIDED, g_undecided, i)
    else if (answer == 1) GLC_APPEND(GLC_LIST_INTERSECTIONS, g_intersections, pair)
}
