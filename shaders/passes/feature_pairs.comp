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
// candidate exists whenever the pair can touch: its faces' boxes contain the features' boxes.
// Which orphans a face pair carries depends on the topology alone, so the host lists them once
// (model::orphanTable, GLC_BIND_FEATURE_ORPHANS) and a candidate looks its pair up; searching the
// faces around each feature here instead cost 90 % of this kernel (llvmpipe, 20K-face cloth ball).
// Without the define the lists are those of discrete detection.
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
layout(std430, binding = GLC_BIND_FEATURE_ORPHANS) readonly buffer FeatureOrphansBuf { uint g_orphans[]; };

// The orphan bits of face pair (lower, higher) (model::orphanTable): a binary search among the
// lower face's entries, (higher face, bits) word pairs in increasing higher face; 0 when absent.
uint orphanBits(uint lower, uint higher) {
    uint first = g_orphans[lower], count = (g_orphans[lower + 1u] - first) / 2u;
    while (count > 0u) { // the first entry whose face is >= higher: in [first, first + 2 count)
        uint step = count / 2u, mid = first + 2u * step;
        if (g_orphans[mid] < higher) {
            first = mid + 2u;
            count -= step + 1u;
        } else {
            count = step;
        }
    }
    return first < g_orphans[lower + 1u] && g_orphans[first] == higher ? g_orphans[first + 1u] : 0u;
}

// Edge-pair bits 3e+g (edge e of one face, g of the other) with the faces' roles swapped.
uint transposedEdgeBits(uint bits) {
    uint swapped = 0u;
    for (uint e = 0u; e < 3u; ++e)
        for (uint g = 0u; g < 3u; ++g)
            if ((bits & (1u << (3u * e + g))) != 0u) swapped |= 1u << (3u * g + e);
    return swapped;
}

void appendOrphans(uvec2 pair, uvec3 fa, uvec3 fb) {
    // The broad phases list (lower, higher); the table's bits are for that order.
    bool ordered = pair.x < pair.y;
    uint bits = ordered ? orphanBits(pair.x, pair.y) : orphanBits(pair.y, pair.x);
    if (bits == 0u) return;
    uint lowerCorners = bits & 7u, higherCorners = (bits >> GLC_ORPHAN_HIGHER_CORNERS) & 7u;
    uint edgePairs = bits >> GLC_ORPHAN_EDGE_PAIRS;
    uint va = ordered ? lowerCorners : higherCorners, vb = ordered ? higherCorners : lowerCorners;
    uint ee = ordered ? edgePairs : transposedEdgeBits(edgePairs);
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
    appendOrphans(pair, fa, fb);
#endif
}
