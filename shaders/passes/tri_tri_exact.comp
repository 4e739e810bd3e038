#version 430 core
// TriTriExact — the second half of the robust narrow phase: one invocation per candidate that the
// filtered TriTri pass left undecided (touching, coplanar, degenerate or nearly so), decided by
// glcTriTriExact of common/tri_tri_robust.glsl (every sign exact, in integer arithmetic where the
// filter cannot certify it). Dispatched indirectly with the undecided count
// (collision_dispatch_args.comp, source 2). Kept apart so the common TriTri kernel stays small.
// CPU twin: the same library compiled as C++ (src/cpu/shader_library.hpp).
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_INTERSECTIONS) writeonly buffer IntersectionsBuf { uvec2 g_intersections[]; };
layout(std430, binding = GLC_BIND_FACES) readonly buffer FacesBuf { uint g_faceIndices[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_UNDECIDED) readonly buffer UndecidedBuf { uint g_undecided[]; };
layout(std430, binding = GLC_BIND_COLLISION_COUNTERS) coherent buffer CollisionCountersBuf { GpuCollisionCounters g_counters; };

#include "common/collision.glsl"
#include "common/tri_tri_robust.glsl"

vec3 corner(uint face, uint k) { return g_positions[g_faceIndices[3u * face + k]].xyz; }

void main() {
    uint i = globalIndex();
    if (i >= min(g_counters.undecidedCount, g_counters.candidateCapacity)) return;
    uvec2 pair = g_facePairs[g_undecided[i]];
    bool hit = glcTriTriExact(corner(pair.x, 0u), corner(pair.x, 1u), corner(pair.x, 2u),
                              corner(pair.y, 0u), corner(pair.y, 1u), corner(pair.y, 2u));
    if (glcExactEvaluations != 0u) atomicAdd(g_counters.exactFallbackCount, glcExactEvaluations);
    if (hit) GLC_APPEND(g_counters.intersectionCount, g_counters.intersectionCapacity, g_intersections, pair)
}
