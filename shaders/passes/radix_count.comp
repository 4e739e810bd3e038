#version 430 core
// Radix sort, pass step 1 of 3 (reduce-then-scan, after Merrill & Grimshaw's "reduce then scan"
// LSD radix sort; no look-back, so no assumption about work groups progressing together): each
// work group counts the digits (GLC_SORT_DIGIT_BITS at u_shift) of its block of GLC_SORT_BLOCK
// keys and writes the counts digit-major, g_blockCounts[digit * u_blocks + block], so that one
// exclusive scan over the whole array (radix_scan.comp) gives every (digit, block) its first
// output position. CPU reference: std::stable_sort (tests/gl/bvh_gl_test.cpp).
#include "common/layout.glsl"

layout(local_size_x = GLC_SORT_BLOCK) in;

layout(std430, binding = GLC_BIND_SORT_KEYS_IN) readonly buffer SortKeysInBuf { uint g_keysIn[]; };
layout(std430, binding = GLC_BIND_SORT_BLOCK_COUNTS) writeonly buffer SortBlockCountsBuf { uint g_blockCounts[]; };

uniform uint u_count;  // keys to sort
uniform uint u_blocks; // work groups that hold keys
uniform uint u_shift;  // the digit's lowest bit

#define DIGITS (1u << GLC_SORT_DIGIT_BITS)
shared uint s_counts[DIGITS];

void main() {
    // More than 65535 blocks spill into y (ComputeProgram::dispatch1D); extra groups count nothing.
    uint block = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    uint t = gl_LocalInvocationID.x;
    if (t < DIGITS) s_counts[t] = 0u;
    memoryBarrierShared();
    barrier();
    uint i = block * uint(GLC_SORT_BLOCK) + t;
    if (block < u_blocks && i < u_count) atomicAdd(s_counts[(g_keysIn[i] >> u_shift) & (DIGITS - 1u)], 1u);
    memoryBarrierShared();
    barrier();
    if (block < u_blocks && t < DIGITS) g_blockCounts[t * u_blocks + block] = s_counts[t];
}
