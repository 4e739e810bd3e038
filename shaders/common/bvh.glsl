// The linear BVH's node numbering and the helpers its kernels share
// (docs/design/decisions/0017-gpu-linear-bvh.md). With n faces there are n-1 internal nodes,
// numbered 0 .. n-2 (node 0 is the root; Karras 2012), and n leaves: the leaf of the face at
// position i of the Morton order is node n-1+i. With one face the root is that face's leaf.
// Links per node (GLC_BIND_BVH_LINKS): x = left child (leaf: its face), y = right child (leaf:
// its sorted index i), z = parent (root: GLC_BVH_NONE), w = escape: the node a depth-first walk
// visits after this node's subtree (GLC_BVH_NONE after the last one). A subtree covers a range
// of sorted leaves [first, last]; the escape starts at leaf last+1, so the escape also tells
// the subtree's last leaf (bvhEscapeStart - 1) without storing it.

uint bvhLeafNode(uint sortedIndex, uint faceCount) {
    return faceCount - 1u + sortedIndex;
}

bool bvhIsLeaf(uint node, uint faceCount) {
    return node >= faceCount - 1u;
}

// The first sorted leaf of the subtree escape points to: faceCount when it points nowhere.
uint bvhEscapeStart(uint escape, uint faceCount) {
    if (escape == GLC_BVH_NONE) return faceCount;
    return bvhIsLeaf(escape, faceCount) ? escape - (faceCount - 1u) : escape;
}

// Floats as uints in the same order (negative floats reversed below the positive ones), so that
// atomicMin/atomicMax on uints reduce floats exactly.
uint orderedBits(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

float orderedFloat(uint u) {
    return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}
