#version 430 core
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

layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };

// Edges that crossed within the substep (their closest-point offset points the other way than at
// its start, from the previous positions x − dt·v) are pushed back, depth h + d (decision 0019).
uint edgeEdge(uint p0, uint p1, uint q0, uint q1) {
    vec3 x0 = g_positions[p0].xyz, x1 = g_positions[p1].xyz;
    vec3 y0 = g_positions[q0].xyz, y1 = g_positions[q1].xyz;
    vec2 st = closestSegmentParams(x0, x1, y0, y1);
    if (!(st.x > 0.0 && st.x < 1.0 && st.y > 0.0 && st.y < 1.0)) return 0u;
    vec3 diff = mix(x0, x1, st.x) - mix(y0, y1, st.y);
    float d = length(diff);
    if (!(d < u_thickness)) return 0u;
    vec3 diffPrev = mix(previousPosition(p0), previousPosition(p1), st.x) -
                    mix(previousPosition(q0), previousPosition(q1), st.y);
    vec3 u;
    float depth;
    if (d > 0.0 && dot(diffPrev, diff) >= 0.0) {
        u = diff / d;
        depth = u_thickness - d;
    } else if (d > 0.0) { // crossed: back to the side of the start of the substep
        u = -diff / d;
        depth = u_thickness + d;
    } else { // touching now (no direction): the direction they had
        float dPrev = length(diffPrev);
        if (!(dPrev > 0.0)) return 0u;
        u = diffPrev / dPrev;
        depth = u_thickness;
    }
    return respond(uvec4(p0, p1, q0, q1), vec4(1.0 - st.x, st.x, st.y - 1.0, -st.y), u, depth);
}

void main() {
    uint i = globalIndex();
    if (i >= storedCount(GLC_LIST_EDGE_EDGE)) return;
    uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g)
    uvec3 a = faceNodes(item.x / 3u), b = faceNodes(item.y / 3u);
    uint e = item.x % 3u, g = item.y % 3u;
    if (edgeEdge(a[e], a[(e + 1u) % 3u], b[g], b[(g + 1u) % 3u]) != 0u) atomicAdd(g_counters.stats[GLC_STAT_CONTACTS], 1u);
}
