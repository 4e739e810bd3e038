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
// whose owner faces share a node (no candidate: an *orphan*), and a lost pair is a contact the
// response never sees while the CCD would stop the step at it (a twisted sleeve froze: every
// substep cut to the time of impact of pairs nothing pushed apart). Each orphan is appended, as a
// contact like the others, by exactly one candidate: for a vertex against a face, the lowest face
// around the vertex that shares no node with that face; for an edge pair, the lowest face pair
// around the two edges whose faces share no node (decision 0018, addendum "Orphans"). That
// candidate exists whenever the pair can touch: its faces' boxes contain the features' boxes. The
// owner faces come from GLC_BIND_FEATURE_OWNERS, each node's faces from
// GLC_BIND_FEATURE_NODE_FACES. Without the define the lists are those of discrete detection.
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
layout(std430, binding = GLC_BIND_FEATURE_NODE_FACES) readonly buffer FeatureNodeFacesBuf { uint g_nodeFaces[]; };

const uint kNone = 0xffffffffu;

bool sharesNode(uvec3 a, uvec3 b) {
    return any(equal(a, b.xxx)) || any(equal(a, b.yyy)) || any(equal(a, b.zzz));
}

// The lowest face around `node` that shares no node with the face of nodes `other`: the one
// candidate that carries the orphan pair (node, other). Each node's faces are listed in
// increasing order, so the first that qualifies is the lowest.
uint lowestFaceApart(uint node, uvec3 other) {
    for (uint k = g_nodeFaces[node]; k < g_nodeFaces[node + 1u]; ++k)
        if (!sharesNode(faceNodes(g_nodeFaces[k]), other)) return g_nodeFaces[k];
    return kNone;
}

// The lowest face pair (lower face, higher face) around edges a and b (node pairs) whose faces
// share no node: the one candidate that carries the orphan edge pair (a, b).
uvec2 lowestFacePairApart(uvec2 a, uvec2 b) {
    uvec2 best = uvec2(kNone);
    for (uint i = g_nodeFaces[a.x]; i < g_nodeFaces[a.x + 1u]; ++i) {
        uint f = g_nodeFaces[i];
        uvec3 nf = faceNodes(f);
        if (!any(equal(nf, uvec3(a.y)))) continue; // around a.x, not around the edge
        for (uint j = g_nodeFaces[b.x]; j < g_nodeFaces[b.x + 1u]; ++j) {
            uint g = g_nodeFaces[j];
            uvec3 ng = faceNodes(g);
            if (!any(equal(ng, uvec3(b.y))) || sharesNode(nf, ng)) continue;
            uvec2 key = uvec2(min(f, g), max(f, g));
            if (key.x < best.x || (key.x == best.x && key.y < best.y)) best = key;
        }
    }
    return best;
}

// Bits k (0..2): corner k of `face`, not owned by it, whose owner face shares a node with `other`
// (an orphan: ownership's candidate does not exist), when `face` is the lowest face around the
// corner apart from `other` — so of all candidates that see the orphan, exactly one appends it.
uint orphanVertices(uint face, uint owned, uvec3 nodes, uvec3 other) {
    uint bits = 0u;
    for (uint k = 0u; k < 3u; ++k)
        if ((owned & (GLC_OWN_VERTEX0 << k)) == 0u && sharesNode(faceNodes(g_featureOwner[6u * face + k]), other) &&
            lowestFaceApart(nodes[k], other) == face)
            bits |= 1u << k;
    return bits;
}

// The nodes of the owner face of edge e (0..2) of `face`.
uvec3 edgeOwnerNodes(uint face, uint owned, uvec3 nodes, uint e) {
    return (owned & (GLC_OWN_EDGE01 << e)) != 0u ? nodes : faceNodes(g_featureOwner[6u * face + 3u + e]);
}

// Bit 3*e+g: edge e of the first face against edge g of the second whose owner faces share a
// node (an orphan; a pair owned here on both sides never is one: the candidate's faces share
// none), when this candidate is the lowest face pair around the two edges whose faces share no
// node — exactly one candidate appends it.
uint orphanEdgePairs(uvec2 pair, uvec3 fa, uvec3 fb, uint oa, uint ob) {
    uvec3 ownerA[3], ownerB[3];
    for (uint e = 0u; e < 3u; ++e) {
        ownerA[e] = edgeOwnerNodes(pair.x, oa, fa, e);
        ownerB[e] = edgeOwnerNodes(pair.y, ob, fb, e);
    }
    uvec2 key = uvec2(min(pair.x, pair.y), max(pair.x, pair.y));
    uint bits = 0u;
    for (uint e = 0u; e < 3u; ++e)
        for (uint g = 0u; g < 3u; ++g)
            if (sharesNode(ownerA[e], ownerB[g]) &&
                lowestFacePairApart(uvec2(fa[e], fa[(e + 1u) % 3u]), uvec2(fb[g], fb[(g + 1u) % 3u])) == key)
                bits |= 1u << (3u * e + g);
    return bits;
}

void appendOrphans(uvec2 pair, uvec3 fa, uvec3 fb, uint oa, uint ob) {
    uint va = orphanVertices(pair.x, oa, fa, fb), vb = orphanVertices(pair.y, ob, fb, fa);
    uint vertexFace = uint(bitCount(va) + bitCount(vb));
    if (vertexFace != 0u) {
        uint slot = glcReserve(GLC_LIST_VERTEX_FACE, vertexFace);
        uint capacity = g_counters.lists[GLC_LIST_VERTEX_FACE].capacity;
        for (uint k = 0u; k < 3u; ++k) {
            if ((va & (1u << k)) != 0u) {
                if (slot < capacity) g_vertexFace[slot] = uvec2(fa[k], pair.y);
                ++slot;
            }
            if ((vb & (1u << k)) != 0u) {
                if (slot < capacity) g_vertexFace[slot] = uvec2(fb[k], pair.x);
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
                if (slot < capacity) g_edgeEdge[slot] = uvec2(3u * pair.x + e, 3u * pair.y + g);
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
