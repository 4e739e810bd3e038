#version 430 core
// BvhBuild, step 4: the binary radix tree over the sorted Morton codes (Karras 2012, "Maximizing
// parallelism in the construction of BVHs, octrees, and k-d trees", Alg. 3 and 4), every node in
// parallel: invocation i finds internal node i's range of sorted leaves and its split, and writes
// its links and its children's parent; it also writes leaf i's face, sorted index and escape.
// Equal codes are told apart by their index (delta below), so every key is distinct and the tree
// has exactly n-1 internal nodes. Integer arithmetic only: the tree is a function of the keys.
// CPU twin: cpu::twinHierarchy.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl"
#include "common/bvh.glsl"

layout(std430, binding = GLC_BIND_SORT_KEYS_IN) readonly buffer SortKeysInBuf { uint g_keys[]; };
layout(std430, binding = GLC_BIND_SORT_VALUES_IN) readonly buffer SortValuesInBuf { uint g_sortedFaces[]; };
layout(std430, binding = GLC_BIND_BVH_LINKS) buffer BvhLinksBuf { uvec4 g_links[]; };

uniform uint u_faceCount;

// Length of the common prefix of keys i and j, ties extended by the indices; -1 outside.
int delta(int i, int j) {
    if (j < 0 || j >= int(u_faceCount)) return -1;
    uint a = g_keys[i], b = g_keys[j];
    if (a == b) return 32 + 31 - findMSB(uint(i ^ j));
    return 31 - findMSB(a ^ b);
}

// +1 when internal node k's range starts at k, -1 when it ends there (Karras: d).
int direction(int k) {
    return delta(k, k + 1) > delta(k, k - 1) ? 1 : -1;
}

// The node a depth-first walk visits after a subtree whose last sorted leaf is `last`: the
// largest subtree starting at leaf last+1, which is internal node last+1 when that node's range
// starts there, and the leaf otherwise (docs/design/decisions/0017-gpu-linear-bvh.md).
uint escapeAfter(uint last) {
    uint next = last + 1u;
    if (next >= u_faceCount) return GLC_BVH_NONE;
    if (next + 1u < u_faceCount && direction(int(next)) > 0) return next;
    return bvhLeafNode(next, u_faceCount);
}

void main() {
    uint idx = globalIndex();
    if (idx >= u_faceCount) return;
    uint n = u_faceCount;
    uint leaf = bvhLeafNode(idx, n);
    g_links[leaf].x = g_sortedFaces[idx];
    g_links[leaf].y = idx;
    g_links[leaf].w = escapeAfter(idx);
    if (idx == 0u) g_links[0].z = GLC_BVH_NONE; // the root, internal or (one face) a leaf
    if (idx + 1u >= n) return;                   // n-1 internal nodes

    int i = int(idx);
    int d = direction(i);
    int deltaMin = delta(i, i - d);
    // Upper bound of the range's length, then its exact other end j by binary search.
    int lengthMax = 2;
    while (delta(i, i + lengthMax * d) > deltaMin) lengthMax *= 2;
    int l = 0;
    for (int t = lengthMax / 2; t >= 1; t /= 2)
        if (delta(i, i + (l + t) * d) > deltaMin) l += t;
    int j = i + l * d;
    // The split: the last position sharing more than the range's common prefix with i.
    int deltaNode = delta(i, j);
    int s = 0;
    int step = l;
    do {
        step = (step + 1) >> 1;
        if (delta(i, i + (s + step) * d) > deltaNode) s += step;
    } while (step > 1);
    int gamma = i + s * d + min(d, 0);
    uint first = uint(min(i, j)), last = uint(max(i, j));
    uint left = first == uint(gamma) ? bvhLeafNode(uint(gamma), n) : uint(gamma);
    uint right = last == uint(gamma + 1) ? bvhLeafNode(uint(gamma + 1), n) : uint(gamma + 1);
    g_links[idx].x = left;
    g_links[idx].y = right;
    g_links[idx].w = escapeAfter(last);
    g_links[left].z = idx;
    g_links[right].z = idx;
}
