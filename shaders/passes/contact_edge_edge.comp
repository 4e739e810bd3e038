#version 430 core
// glcollide-features: GLC_PREDICTED_FORCES
// ContactResponse, edge-edge — one invocation per entry (3*fa+e, 3*fb+g) of GLC_LIST_EDGE_EDGE
// (indirect dispatch from its count; the pairs come from FeaturePairs, feature_pairs.comp; edge e
// of a face runs from corner e to corner (e+1)%3): two edges closer than the thickness h are
// pushed apart along the line of their closest points when both closest points are inside their
// edges (an endpoint is a vertex: the vertex-face contacts have it); edges that crossed within
// the substep are pushed back to their sides at its start. Force law and fixed-point sums:
// common/contact_force.glsl. Twin: cpu::contactForces.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"
#include "common/contact_force.glsl"
// Contacts within the thickness only (common/contact_pair.glsl).
const bool kContactCrossings = false;
#include "common/contact_pair.glsl"
#include "common/tangled.glsl"

layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };

// Returns 1 when a force was applied (geometry: common/contact_pair.glsl).
uint edgeEdge(uint p0, uint p1, uint q0, uint q1) {
    ContactPair c = edgeEdgeContact(p0, p1, q0, q1);
    return c.found ? respond(c.nodes, c.weights, c.normal, c.depth) : 0u;
}

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_EDGE_EDGE)) return;
    uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g)
    if (faceTangled(item.x / 3u) || faceTangled(item.y / 3u)) return; // intersecting at x0 (tangled.glsl)
    uvec3 a = faceNodes(item.x / 3u), b = faceNodes(item.y / 3u);
    uint e = item.x % 3u, g = item.y % 3u;
    if (edgeEdge(a[e], a[(e + 1u) % 3u], b[g], b[(g + 1u) % 3u]) != 0u) atomicAdd(g_counters.stats[GLC_STAT_CONTACTS], 1u);
}
