#version 430 core
// Radix sort, pass step 3 of 3: each work group recomputes its block's digits and moves every
// (key, value) to its digit's offset for the block (radix_scan.comp) plus its rank among the
// block's earlier keys with the same digit. The ranks come from one shared-memory prefix sum of
// one-hot digit vectors, 16 counters of 16 bits packed in two uvec4 (a block holds 256 keys, so
// no counter carries into its neighbour): keys keep their order within a digit, so every pass,
// and the sort, is stable.
#include "common/layout.glsl"

layout(local_size_x = GLC_SORT_BLOCK) in;

layout(std430, binding = GLC_BIND_SORT_KEYS_IN) readonly buffer SortKeysInBuf { uint g_keysIn[]; };
layout(std430, binding = GLC_BIND_SORT_VALUES_IN) readonly buffer SortValuesInBuf { uint g_valuesIn[]; };
layout(std430, binding = GLC_BIND_SORT_KEYS_OUT) writeonly buffer SortKeysOutBuf { uint g_keysOut[]; };
layout(std430, binding = GLC_BIND_SORT_VALUES_OUT) writeonly buffer SortValuesOutBuf { uint g_valuesOut[]; };
layout(std430, binding = GLC_BIND_SORT_BLOCK_COUNTS) readonly buffer SortBlockCountsBuf { uint g_blockOffsets[]; };

uniform uint u_count;
uniform uint u_blocks;
uniform uint u_shift;

shared uvec4 s_low[GLC_SORT_BLOCK];  // digits 0-7: digit d in component d/2, bits 16*(d%2)
shared uvec4 s_high[GLC_SORT_BLOCK]; // digits 8-15 likewise

void main() {
    uint block = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    uint t = gl_LocalInvocationID.x;
    uint i = block * uint(GLC_SORT_BLOCK) + t;
    bool valid = block < u_blocks && i < u_count;
    uint key = valid ? g_keysIn[i] : 0u;
    uint digit = (key >> u_shift) & 15u;
    uint word = (digit >> 1u) & 3u;
    uint shift = (digit & 1u) * 16u;
    uvec4 oneHot = uvec4(0u);
    if (valid) oneHot[word] = 1u << shift;
    s_low[t] = digit < 8u ? oneHot : uvec4(0u);
    s_high[t] = digit < 8u ? uvec4(0u) : oneHot;
    for (uint offset = 1u; offset < uint(GLC_SORT_BLOCK); offset <<= 1u) {
        memoryBarrierShared();
        barrier();
        uvec4 low = t >= offset ? s_low[t - offset] : uvec4(0u);
        uvec4 high = t >= offset ? s_high[t - offset] : uvec4(0u);
        memoryBarrierShared();
        barrier();
        s_low[t] += low;
        s_high[t] += high;
    }
    if (!valid) return;
    uint inclusive = ((digit < 8u ? s_low[t][word] : s_high[t][word]) >> shift) & 0xffffu;
    uint destination = g_blockOffsets[digit * u_blocks + block] + inclusive - 1u;
    g_keysOut[destination] = key;
    g_valuesOut[destination] = g_valuesIn[i];
}
