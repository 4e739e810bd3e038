#version 430 core
// Ccd — continuous collision detection of the substep's feature pairs (docs/ccd.md, "In the
// engine"): one invocation per entry of GLC_LIST_VERTEX_FACE (u_edgeEdge = 0) or
// GLC_LIST_EDGE_EDGE (u_edgeEdge = 1), indirect dispatch from the list's count. Each pair moves
// linearly from x0 (binding 0, the start of the substep) to x1 (the predicted end positions of
// NodePredict); the conservative float CCD of common/ccd.glsl decides whether it may touch
// (minimum separation u_minSeparation) during the substep and gives a time of impact never later
// than the true one. A pair that may touch lowers the time of impact of its four nodes and of the
// substep with atomicMin on the bits of a non-negative float (they order like the floats: the
// minimum, and so the result, does not depend on the order of the invocations). The refinement
// stops after u_budget boxes: the pair then counts as "may touch" at its lower bound and in
// GLC_STAT_CCD_CAPPED. CPU twin: cpu::featureCcd (src/cpu/ccd_twin.cpp).
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/ccd.glsl"
#include "common/contact_geometry.glsl"
#include "common/radial_cull.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_predicted[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };
layout(std430, binding = GLC_BIND_NODE_TOI) buffer NodeToiBuf { uint g_nodeToi[]; };
layout(std430, binding = GLC_BIND_TANGLED) readonly buffer TangledBuf { uint g_tangled[]; };

uniform uint u_edgeEdge;       // 0: vertex-face pairs, 1: edge-edge pairs
uniform uint u_budget;         // boxes one pair may evaluate (llvmpipe: <= 21844, docs/ccd.md)
uniform float u_minSeparation; // m: 0 for true contact
// 1 (the intersection-free response's safe step): a pair none of whose four nodes moves is not
// tested. It cannot come to intersect within the substep, and a still pair that touches at x0
// (a node frozen beside it) must not keep the safe step's rounds going.
uniform uint u_skipStill;
// 1 (the safe step): a pair counts as touching when it comes within min(u_minSeparation, d0/2),
// d0 its distance at x0 (float closest points: any separation >= 0 keeps the CCD never late for
// true contact, so their rounding is harmless). A pair arriving from afar is stopped short of
// u_minSeparation, inside the thickness where the response pushes it apart; a pair already closer
// may lose at most half its gap in a substep instead of being frozen for being close.
uniform uint u_gapRelative;
// 1 (the safe step): pairs of the features of faces that intersect at x0 (TangledMarks) are left
// out — they would touch at t = 0, or block the way back, and freeze their objects while the
// response pushes them apart.
uniform uint u_skipTangled;
uniform uint u_nodeCount; // GLC_BIND_TANGLED: the faces' marks start after the nodes'

// Distance at x0 of the pair (vertex-face: s0 against s1 s2 s3; edge-edge: s0s1 against s2s3).
float startDistance(vec3 s0, vec3 s1, vec3 s2, vec3 s3) {
    if (u_edgeEdge == 0u) {
        vec3 w = closestOnTriangle(s0, s1, s2, s3);
        return length(s0 - (w.x * s1 + w.y * s2 + w.z * s3));
    }
    vec2 st = closestSegmentParams(s0, s1, s2, s3);
    return length(mix(s0, s1, st.x) - mix(s2, s3, st.y));
}

// The pair's four nodes in the order of glcVertexFaceCcd / glcEdgeEdgeCcd.
uvec4 pairNodes(uint i) {
    if (u_edgeEdge == 0u) {
        uvec2 item = g_vertexFace[i]; // (node, face), the face maybe marked GLC_PAIR_CCD_ONLY: tested too
        uvec3 f = faceNodes(item.y & ~GLC_PAIR_CCD_ONLY);
        return uvec4(item.x, f.x, f.y, f.z);
    }
    uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g): edge e from corner e to corner (e+1)%3
    item.y &= ~GLC_PAIR_CCD_ONLY; // continuous detection's completion: tested like the others
    uvec3 a = faceNodes(item.x / 3u), b = faceNodes(item.y / 3u);
    uint e = item.x % 3u, g = item.y % 3u;
    return uvec4(a[e], a[(e + 1u) % 3u], b[g], b[(g + 1u) % 3u]);
}

// Whether radial culling leaves pair i out (common/radial_cull.glsl).
bool radialCulled(uint i) {
    if (u_edgeEdge == 0u) {
        uvec2 item = g_vertexFace[i]; // (node, face)
        return glcRadialCulledVertexFace(item.x, item.y & ~GLC_PAIR_CCD_ONLY);
    }
    uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g)
    return glcRadialCulled(item.x / 3u, (item.y & ~GLC_PAIR_CCD_ONLY) / 3u);
}

// Whether pair i has a marked node or face (vertex-face) or a marked face (edge-edge): to come
// apart, an intersecting region must pass back through the faces around it, so every pair of its
// features is left out, not only those between the intersecting faces themselves.
bool tangledPair(uint i) {
    if (u_edgeEdge == 0u) {
        uvec2 item = g_vertexFace[i];
        return g_tangled[item.x] != 0u || g_tangled[u_nodeCount + (item.y & ~GLC_PAIR_CCD_ONLY)] != 0u;
    }
    uvec2 item = g_edgeEdge[i];
    return g_tangled[u_nodeCount + item.x / 3u] != 0u ||
           g_tangled[u_nodeCount + (item.y & ~GLC_PAIR_CCD_ONLY) / 3u] != 0u;
}

// The safe step's second lower bound for a capped pair (conservative advancement): every point of
// a primitive is a convex combination of its nodes, which move linearly, so it moves at most the
// largest node displacement, and the distance at time t is at least d0 − t·(reachA + reachB).
// The pair cannot come within `separation` before (d0 − separation) / (reachA + reachB). Float
// margins: the computed distance is lowered by 2^-10 of itself and 2^-16 of the coordinates'
// magnitude, the displacement raised by 2^-10 — orders of magnitude above the rounding of these
// few operations however they are contracted or reordered. Returns 2 when the bound exceeds the
// substep (the pair cannot touch in it).
float advancementToi(vec3 s0, vec3 s1, vec3 s2, vec3 s3, vec3 e0, vec3 e1, vec3 e2, vec3 e3, float separation) {
    vec3 reach0 = abs(e0 - s0), reach1 = abs(e1 - s1), reach2 = abs(e2 - s2), reach3 = abs(e3 - s3);
    float r0 = length(reach0), r1 = length(reach1), r2 = length(reach2), r3 = length(reach3);
    float reach = u_edgeEdge == 0u ? r0 + max(r1, max(r2, r3)) : max(r0, r1) + max(r2, r3);
    vec3 big = max(max(max(abs(s0), abs(e0)), max(abs(s1), abs(e1))), max(max(abs(s2), abs(e2)), max(abs(s3), abs(e3))));
    float scale = max(big.x, max(big.y, big.z));
    float gap = startDistance(s0, s1, s2, s3) * (1.0 - 0.0009765625) - 1.52587890625e-5 * scale - separation;
    if (!(gap > 0.0)) return 0.0;
    reach *= 1.0 + 0.0009765625;
    return gap < 2.0 * reach ? gap / reach : 2.0;
}

void main() {
    uint i = globalIndex();
    uint list = u_edgeEdge == 0u ? GLC_LIST_VERTEX_FACE : GLC_LIST_EDGE_EDGE;
    if (i >= storedCount(list)) return;
    if (u_skipTangled != 0u && tangledPair(i)) {
        atomicAdd(g_counters.stats[GLC_STAT_CCD_TANGLED], 1u);
        return;
    }
    uvec4 n = pairNodes(i);
    vec3 s0 = g_positions[n.x].xyz, s1 = g_positions[n.y].xyz, s2 = g_positions[n.z].xyz, s3 = g_positions[n.w].xyz;
    vec3 e0 = g_predicted[n.x].xyz, e1 = g_predicted[n.y].xyz, e2 = g_predicted[n.z].xyz, e3 = g_predicted[n.w].xyz;
    if (u_skipStill != 0u && all(equal(s0, e0)) && all(equal(s1, e1)) && all(equal(s2, e2)) && all(equal(s3, e3)))
        return;
    float separation = u_minSeparation;
    if (u_gapRelative != 0u) {
        float halfGap = 0.5 * startDistance(s0, s1, s2, s3);
        separation = halfGap < u_minSeparation ? halfGap : 0.0;
    }
    // Radial culling: a pair tested for true contact (zero separation) with a free face cannot
    // touch (the face intersects nothing of its surface during the substep). Proximity tests
    // (separation > 0) are not culled: the theorem says nothing about distances.
    if (separation == 0.0 && radialCulled(i)) {
        atomicAdd(g_counters.stats[GLC_STAT_RADIAL_CULLED_CCD], 1u);
        return;
    }
    bool hit = glcCcdInclusion(u_edgeEdge != 0u, s0, s1, s2, s3, e0, e1, e2, e3, separation, int(u_budget));
    atomicAdd(g_counters.stats[GLC_STAT_CCD_BOXES], uint(glcCcdBoxes));
    if (glcCcdCapped) atomicAdd(g_counters.stats[GLC_STAT_CCD_CAPPED], 1u);
    if (hit && glcCcdCapped && u_gapRelative != 0u) {
        // Out of budget the search answers its lowest unsearched time, often 0 for a pair resting
        // in contact: a safe step would freeze its objects. The advancement bound is a lower
        // bound too; the larger of the two is.
        float advancement = advancementToi(s0, s1, s2, s3, e0, e1, e2, e3, separation);
        if (advancement > 1.0) hit = false;
        else glcCcdToi = max(glcCcdToi, advancement);
    }
    if (!hit) return;
    atomicAdd(g_counters.stats[u_edgeEdge == 0u ? GLC_STAT_CCD_VERTEX_FACE_HITS : GLC_STAT_CCD_EDGE_EDGE_HITS], 1u);
    uint toi = floatBitsToUint(glcCcdToi); // in [0, 1]: non-negative, so the bits order like the values
    atomicMin(g_counters.stats[GLC_STAT_CCD_EARLIEST_TOI], toi);
    atomicMin(g_nodeToi[n.x], toi);
    atomicMin(g_nodeToi[n.y], toi);
    atomicMin(g_nodeToi[n.z], toi);
    atomicMin(g_nodeToi[n.w], toi);
}
