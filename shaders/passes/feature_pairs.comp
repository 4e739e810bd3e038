#version 430 core
// glcollide-features: GLC_CCD_COMPLETE
// FeaturePairs — Representative Triangles (seeds/001, Kim 2024; docs/design/decisions/
// 0018-representative-triangles.md): one invocation per candidate face pair (indirect dispatch
// from the candidate count) expands the pair into the feature pairs the contact response tests:
//  * GLC_LIST_VERTEX_FACE: (node, face) for every vertex one face of the pair owns
//    (GLC_OWN_VERTEX*) against the other face, both ways;
//  * GLC_LIST_EDGE_EDGE: (3*fa+e, 3*fb+g) for every edge e the first face fa owns against every
//    edge g the other face fb owns (GLC_OWN_EDGE*; edge e runs from corner e to corner (e+1)%3).
// A feature is owned by exactly one face (the lowest-indexed one containing it), so over a
// candidate list that holds each unordered face pair once every feature pair is appended once:
// at most 6 vertex-face and 9 edge-edge pairs per candidate, and fewer the more features the pair's
// faces share with lower faces. Each invocation reserves its slots with one atomic per list.
// GLC_CCD_COMPLETE (continuous detection): ownership loses, in self-collisions, the feature pairs
// whose owner faces share a node (no candidate). Each invocation also appends, marked
// GLC_PAIR_CCD_ONLY, every vertex of either face not owned by it whose owner face shares a node
// with the other face, and every edge pair whose owner faces share a node (not both owned here), so
// the CCD sees every feature pair of the candidate whose features may touch (decision 0018,
// addendum). The owner faces come from GLC_BIND_FEATURE_OWNERS. Without the define the lists are
// those of discrete detection, bit for bit.
// CPU twin: cpu::featurePairs (src/cpu/contact_twin.cpp).
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) writeonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) writeonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };

#ifdef GLC_CCD_COMPLETE
layout(std430, binding = GLC_BIND_FEATURE_OWNERS) readonly buffer FeatureOwnersBuf { uint g_featureOwner[]; };

bool sharesNode(uvec3 a, uvec3 b) {
    return any(equal(a, b.xxx)) || any(equal(a, b.yyy)) || any(equal(a, b.zzz));
}

// Bits k (0..2): corner k of `face`, not owned by it, whose owner face shares a node with `other`:
// no candidate pairs that owner with `other`, so only candidates like this one can test it.
uint orphanVertices(uint face, uint owned, uvec3 other) {
    uint bits = 0u;
    for (uint k = 0u; k < 3u; ++k)
        if ((owned & (GLC_OWN_VERTEX0 << k)) == 0u && sharesNode(faceNodes(g_featureOwner[6u * face + k]), other))
            bits |= 1u << k;
    return bits;
}

// The nodes of the owner face of edge e (0..2) of `face`.
uvec3 edgeOwnerNodes(uint face, uint owned, uvec3 nodes, uint e) {
    return (owned & (GLC_OWN_EDGE01 << e)) != 0u ? nodes : faceNodes(g_featureOwner[6u * face + 3u + e]);
}

// Bit 3*e+g: edge e of the first face against edge g of the second whose owner faces share a
// node (a pair owned here on both sides never is one: the candidate's faces share none).
uint orphanEdgePairs(uvec2 pair, uvec3 fa, uvec3 fb, uint oa, uint ob) {
    uvec3 ownerA[3], ownerB[3];
    for (uint e = 0u; e < 3u; ++e) {
        ownerA[e] = edgeOwnerNodes(pair.x, oa, fa, e);
        ownerB[e] = edgeOwnerNodes(pair.y, ob, fb, e);
    }
    uint bits = 0u;
    for (uint e = 0u; e < 3u; ++e)
        for (uint g = 0u; g < 3u; ++g)
            if (sharesNode(ownerA[e], ownerB[g])) bits |= 1u << (3u * e + g);
    return bits;
}

void appendOrphans(uvec2 pair, uvec3 fa, uvec3 fb, uint oa, uint ob) {
    uint va = orphanVertices(pair.x, oa, fb), vb = orphanVertices(pair.y, ob, fa);
    uint vertexFace = uint(bitCount(va) + bitCount(vb));
    if (vertexFace != 0u) {
        uint slot = glcReserve(GLC_LIST_VERTEX_FACE, vertexFace);
        uint capacity = g_counters.lists[GLC_LIST_VERTEX_FACE].capacity;
        for (uint k = 0u; k < 3u; ++k) {
            if ((va & (1u << k)) != 0u) {
                if (slot < capacity) g_vertexFace[slot] = uvec2(fa[k], pair.y | GLC_PAIR_CCD_ONLY);
                ++slot;
            }
            if ((vb & (1u << k)) != 0u) {
                if (slot < capacity) g_vertexFace[slot] = uvec2(fb[k], pair.x | GLC_PAIR_CCD_ONLY);
                ++slot;
            }
        }
    }
    uint ee = orphanEdgePairs(pair, fa, fb, oa, ob);
    uint edgeEdge = uint(bitCount(ee));
    if (edgeEdge != 0u) {
        uint slot = glcReserve(GLC_LIST_EDGE_EDGE, edgeEdge);
        uint capacity = g_counters.lists[GLC_LIST_EDGE_EDGE].capacity;
        for (uint e = 0u; e < 3u; ++e)
            for (uint g = 0u; g < 3u; ++g) {
                if ((ee & (1u << (3u * e + g))) == 0u) continue;
                if (slot < capacity) g_edgeEdge[slot] = uvec2(3u * pair.x + e, (3u * pair.y + g) | GLC_PAIR_CCD_ONLY);
                ++slot;
            }
    }
}
#endif

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_CANDIDATES)) return;
    uvec2 pair = g_facePairs[i];
    uvec3 fa = faceNodes(pair.x), fb = faceNodes(pair.y);
    uint oa = g_faceInfo[pair.x].owned, ob = g_faceInfo[pair.y].owned;

    const uint kVertices = GLC_OWN_VERTEX0 | GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2;
    const uint kEdges = GLC_OWN_EDGE01 | GLC_OWN_EDGE12 | GLC_OWN_EDGE20;
    uint vertexFace = uint(bitCount(oa & kVertices) + bitCount(ob & kVertices));
    if (vertexFace != 0u) {
        uint slot = glcReserve(GLC_LIST_VERTEX_FACE, vertexFace);
        uint capacity = g_counters.lists[GLC_LIST_VERTEX_FACE].capacity;
        for (uint k = 0u; k < 3u; ++k) {
            if ((oa & (GLC_OWN_VERTEX0 << k)) != 0u) {
                if (slot < capacity) g_vertexFace[slot] = uvec2(fa[k], pair.y);
                ++slot;
            }
            if ((ob & (GLC_OWN_VERTEX0 << k)) != 0u) {
                if (slot < capacity) g_vertexFace[slot] = uvec2(fb[k], pair.x);
                ++slot;
            }
        }
    }

    uint edgeEdge = uint(bitCount(oa & kEdges) * bitCount(ob & kEdges));
    if (edgeEdge != 0u) {
        uint slot = glcReserve(GLC_LIST_EDGE_EDGE, edgeEdge);
        uint capacity = g_counters.lists[GLC_LIST_EDGE_EDGE].capacity;
        for (uint e = 0u; e < 3u; ++e) {
            if ((oa & (GLC_OWN_EDGE01 << e)) == 0u) continue;
            for (uint g = 0u; g < 3u; ++g) {
                if ((ob & (GLC_OWN_EDGE01 << g)) == 0u) continue;
                if (slot < capacity) g_edgeEdge[slot] = uvec2(3u * pair.x + e, 3u * pair.y + g);
                ++slot;
            }
        }
    }
#ifdef GLC_CCD_COMPLETE
    appendOrphans(pair, fa, fb, oa, ob);
#endif
}
