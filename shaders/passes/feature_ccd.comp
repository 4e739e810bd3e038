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
// GLC_STAT_CCD_CAPPED. Which pairs are tested: common/ccd_pair_selection.glsl; with radial
// culling the filter kernel first compacts them, and this kernel runs over its lists (the CCD's
// private search stack is then paid only for pairs that are tested). CPU twin: cpu::featureCcd
// (src/cpu/ccd_twin.cpp).
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/ccd.glsl"
#include "common/contact_geometry.glsl"
#include "common/radial_cull.glsl"
#include "common/ccd_pair_selection.glsl"

layout(std430, binding = GLC_BIND_NODE_TOI) buffer NodeToiBuf { uint g_nodeToi[]; };
// The pairs feature_ccd_filter.comp left to test (u_compacted = 1): indices into the feature list.
layout(std430, binding = GLC_BIND_CCD_VERTEX_FACE_TESTS) readonly buffer CcdVertexFaceTestsBuf { uint g_vertexFaceTests[]; };
layout(std430, binding = GLC_BIND_CCD_EDGE_EDGE_TESTS) readonly buffer CcdEdgeEdgeTestsBuf { uint g_edgeEdgeTests[]; };

uniform uint u_budget;    // boxes one pair may evaluate (llvmpipe: <= 21844, docs/ccd.md)
uniform uint u_compacted; // 1: one invocation per entry of the filter's lists, not of the feature lists

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
    uint k = globalIndex(), i = k;
    if (u_compacted != 0u) {
        uint list = u_edgeEdge == 0u ? GLC_LIST_CCD_VERTEX_FACE_TESTS : GLC_LIST_CCD_EDGE_EDGE_TESTS;
        if (k >= storedCount(list)) return;
        i = u_edgeEdge == 0u ? g_vertexFaceTests[k] : g_edgeEdgeTests[k];
    } else if (k >= storedCount(u_edgeEdge == 0u ? GLC_LIST_VERTEX_FACE : GLC_LIST_EDGE_EDGE)) {
        return;
    }
    CcdPair p = selectCcdPair(i);
    if (p.action != GLC_CCD_TEST) return;
    uvec4 n = p.nodes;
    vec3 s0 = p.s0, s1 = p.s1, s2 = p.s2, s3 = p.s3, e0 = p.e0, e1 = p.e1, e2 = p.e2, e3 = p.e3;
    float separation = p.separation;
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
