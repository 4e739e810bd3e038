#version 430 core
// Radix sort, pass step 2 of 3: an exclusive prefix sum, in place, over the digit-major block
// counts (radix_count.comp), by one work group: each invocation sums a contiguous segment, the
// group scans the segment sums in shared memory, and each invocation rewrites its segment as
// running offsets. Integer sums: exact and order-independent. A segment is at most 65535
// entries (llvmpipe's loop limit), so up to 2^24 counts: 2^28 keys.
#include "common/layout.glsl"

layout(local_size_x = GLC_SCAN_GROUP) in;

layout(std430, binding = GLC_BIND_SORT_BLOCK_COUNTS) buffer SortBlockCountsBuf { uint g_blockCounts[]; };

uniform uint u_length; // entries to scan: digits x blocks

shared uint s_sums[GLC_SCAN_GROUP];

void main() {
    uint t = gl_LocalInvocationID.x;
    uint perInvocation = (u_length + uint(GLC_SCAN_GROUP) - 1u) / uint(GLC_SCAN_GROUP);
    uint begin = min(t * perInvocation, u_length);
    uint end = min(begin + perInvocation, u_length);
    uint sum = 0u;
    for (uint k = begin; k < end; ++k) sum += g_blockCounts[k];
    s_sums[t] = sum;
    // Hillis-Steele inclusive scan of the segment sums.
    for (uint offset = 1u; offset < uint(GLC_SCAN_GROUP); offset <<= 1u) {
        memoryBarrierShared();
        barrier();
        uint before = t >= offset ? s_sums[t - offset] : 0u;
        memoryBarrierShared();
        barrier();
        s_sums[t] += before;
    }
    uint running = s_sums[t] - sum; // exclusive: everything before this segment
    for (uint k = begin; k < end; ++k) {
        uint count = g_blockCounts[k];
        g_blockCounts[k] = running;
        running += count;
    }
}
