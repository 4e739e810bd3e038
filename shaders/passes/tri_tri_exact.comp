#version 430 core
// TriTriExact — the second pass of the robust narrow phase: one invocation per candidate that
// tri_tri_filtered.comp left undecided (touching, coplanar, degenerate or nearly so), decided by
// glcTriTriExact of common/tri_tri_robust.glsl (every sign exact, in integer arithmetic where the
// filter cannot certify it). Dispatched indirectly from the undecided count. Kept apart so the
// common TriTri kernel stays small. CPU twin: the same library compiled as C++
// (src/cpu/shader_library.hpp).
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"
#include "common/tri_tri_robust.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_UNDECIDED) readonly buffer UndecidedBuf { uint g_undecided[]; };
layout(std430, binding = GLC_BIND_INTERSECTIONS) writeonly buffer IntersectionsBuf { uvec2 g_intersections[]; };

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_UNDECIDED)) return;
    uvec2 pair = g_facePairs[g_undecided[i]];
    uvec3 a = faceNodes(pair.x), b = faceNodes(pair.y);
    bool hit = glcTriTriExact(g_positions[a.x].xyz, g_positions[a.y].xyz, g_positions[a.z].xyz,
                              g_positions[b.x].xyz, g_positions[b.y].xyz, g_positions[b.z].xyz);
    if (glcExactEvaluations != 0u) atomicAdd(g_counters.stats[GLC_STAT_EXACT_FALLBACKS], glcExactEvaluations);
    if (glcExactFailed) atomicAdd(g_counters.stats[GLC_STAT_EXACT_ERRORS], 1u); // no answer: the host throws
    else if (hit) GLC_APPEND(GLC_LIST_INTERSECTIONS, g_intersections, pair)
}
