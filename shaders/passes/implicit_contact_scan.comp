#version 430 core
// ImplicitContactScan — the contact term of the implicit solve, step 2 of 4: one work group turns
// the per-node incidence counts into CSR row offsets (exclusive prefix sum, offsets[nodes] = the
// total). Each invocation sums a contiguous chunk of ⌈nodes / GLC_WORKGROUP_SIZE⌉ counts, a
// Hillis-Steele scan in shared memory offsets the chunks, then each invocation writes its chunk.
// Integer sums: exact and order-independent.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/implicit_contact.glsl"

layout(std430, binding = GLC_BIND_NODE_CONTACT_COUNTS) readonly buffer NodeContactCountsBuf { uint g_nodeContactCounts[]; };

uniform uint u_nodeCount;

shared uint s_chunkSums[GLC_WORKGROUP_SIZE];

void main() {
    uint lane = gl_LocalInvocationID.x;
    uint chunk = (u_nodeCount + GLC_WORKGROUP_SIZE - 1u) / GLC_WORKGROUP_SIZE;
    uint begin = min(lane * chunk, u_nodeCount), end = min(begin + chunk, u_nodeCount);
    uint sum = 0u;
    for (uint i = begin; i < end; ++i) sum += g_nodeContactCounts[i];
    s_chunkSums[lane] = sum;
    memoryBarrierShared();
    barrier();
    for (uint width = 1u; width < GLC_WORKGROUP_SIZE; width <<= 1u) { // inclusive scan
        uint add = lane >= width ? s_chunkSums[lane - width] : 0u;
        memoryBarrierShared();
        barrier();
        s_chunkSums[lane] += add;
        memoryBarrierShared();
        barrier();
    }
    uint running = s_chunkSums[lane] - sum; // exclusive: the counts of the chunks before this one
    for (uint i = begin; i < end; ++i) {
        setContactRowOffset(i, running);
        running += g_nodeContactCounts[i];
    }
    if (lane == GLC_WORKGROUP_SIZE - 1u) setContactRowOffset(u_nodeCount, s_chunkSums[lane]);
}
