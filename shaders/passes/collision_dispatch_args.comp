#version 430 core
// Writes glDispatchComputeIndirect arguments from an append counter, so the octree broad phase
// sizes its next dispatch on the GPU without a CPU read-back (docs/broad-phase.md, "Sync points").
// A helper of BBCollision (expansion: one group per box pair), TriTri (one invocation per
// candidate) and the robust TriTriExact (one per undecided candidate) in the AABB-octree pipeline
// (seeds/002, Fig. 4). One invocation.
#include "common/layout.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = GLC_BIND_COLLISION_COUNTERS) readonly buffer CollisionCountersBuf { GpuCollisionCounters g_counters; };
layout(std430, binding = GLC_BIND_DISPATCH_ARGS) writeonly buffer DispatchArgsBuf { uint g_dispatchArgs[]; };

uniform uint u_source;              // 0: box pairs, 1: candidates, 2: undecided candidates (robust TriTri)
uniform uint u_invocationsPerGroup; // items handled by one work group
uniform uint u_slot;                // writes g_dispatchArgs[3 * u_slot .. 3 * u_slot + 2]
uniform uint u_z;                   // groups in z (the expansion's slices of one box pair's work)

void main() {
    uint n = u_source == 0u ? min(g_counters.boxPairCount, g_counters.boxPairCapacity)
           : u_source == 1u ? min(g_counters.candidateCount, g_counters.candidateCapacity)
                            : min(g_counters.undecidedCount, g_counters.candidateCapacity);
    uint groups = (n + u_invocationsPerGroup - 1u) / u_invocationsPerGroup;
    // GL 4.3 guarantees 65535 groups per dimension; the kernels fold y back into their index.
    uint x = min(groups, 65535u);
    uint y = x == 0u ? 1u : (groups + x - 1u) / x;
    g_dispatchArgs[3u * u_slot] = x;
    g_dispatchArgs[3u * u_slot + 1u] = y;
    g_dispatchArgs[3u * u_slot + 2u] = max(u_z, 1u);
}
