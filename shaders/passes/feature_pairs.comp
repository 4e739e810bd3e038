#version 430 core
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
}
