#version 430 core
// ImplicitContactSort — the contact term of the implicit solve, step 4 of 4: one invocation per
// node sorts its segment of the incidence list by a key that names the contact, not its list
// slot or its record: (which list, the pair as the list holds it, the corner). The feature-pair lists are filled
// by atomic appends, the records too, and the scatter by atomic cursors, so slots, records and positions vary from run to
// run; after the sort every row sums its contacts in the same order, so the solve is bit-identical
// on reruns. Insertion sort: rows are short (a node touches a few faces); its loops are bounded
// by the row's length.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/implicit_contact.glsl"

layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };

uniform uint u_nodeCount;
uniform uint u_edgeEdgeBase; // the first list slot of the edge-edge list

// (0: vertex-face | 1: edge-edge, the pair's two entries, the corner).
uvec4 incidenceKey(uint entry) {
    uint slot = recordSlot(incidenceRecord(entry));
    bool edgeEdge = slot >= u_edgeEdgeBase;
    uvec2 pair = edgeEdge ? g_edgeEdge[slot - u_edgeEdgeBase] : g_vertexFace[slot];
    return uvec4(edgeEdge ? 1u : 0u, pair, incidenceCorner(entry));
}

bool keyLess(uvec4 a, uvec4 b) {
    for (uint k = 0u; k < 4u; ++k)
        if (a[k] != b[k]) return a[k] < b[k];
    return false;
}

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    uint begin = contactRowBegin(i), end = contactRowEnd(i);
    for (uint a = begin + 1u; a < end; ++a) {
        uint entry = contactEntry(a);
        uvec4 key = incidenceKey(entry);
        uint b = a;
        while (b > begin && keyLess(key, incidenceKey(contactEntry(b - 1u)))) {
            setContactEntry(b, contactEntry(b - 1u));
            --b;
        }
        setContactEntry(b, entry);
    }
}
