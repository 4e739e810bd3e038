#version 430 core
// BvhTraverse: one query per sorted leaf q. It walks the tree depth-first without a stack, by
// the links (bvh.glsl): into the left child of a node whose box overlaps q's, else to the escape.
// A subtree whose last leaf is at or before q is skipped (its pairs with q are found by the
// earlier leaf's query), so every unordered face pair is met once; a leaf after q whose box
// overlaps q's is a candidate when the pair is valid (collision.glsl), appended as (lower,
// higher) face. The boxes are the exact inflated face boxes of the candidate rule, so the set
// equals the all-pairs broad phase's (face_pair_candidate.glsl).
// Resuming: an invocation visits at most u_visitsPerRound nodes per dispatch (llvmpipe ends a
// loop silently after 65535 iterations) and saves the next node in g_resume; the next round's
// dispatch goes on from there. The last round counts the queries still unfinished; the host then
// reruns the stage with twice the rounds, so no pair is lost. CPU twin: cpu::twinBvhCandidates.
#include "common/layout.glsl"
#include "common/collision.glsl"
#include "common/lists.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl"
#include "common/face_nodes.glsl"
#include "common/bvh.glsl"

layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_BVH_BOXES) readonly buffer BvhBoxesBuf { GpuBox g_boxes[]; };
layout(std430, binding = GLC_BIND_BVH_LINKS) readonly buffer BvhLinksBuf { uvec4 g_links[]; };
layout(std430, binding = GLC_BIND_BVH_RESUME) buffer BvhResumeBuf { uint g_resume[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) writeonly buffer FacePairsBuf { uvec2 g_facePairs[]; };

uniform uint u_faceCount;
uniform uint u_pairRules;      // GLC_RULE_* bits
uniform uint u_visitsPerRound; // nodes one invocation visits per dispatch, < 65535
uniform uint u_firstRound;     // 1: start at the root, not at g_resume
uniform uint u_lastRound;      // 1: count the queries left unfinished

void main() {
    uint q = globalIndex();
    if (q >= u_faceCount) return;
    uint node = u_firstRound != 0u ? 0u : g_resume[q];
    if (node == GLC_BVH_NONE) return;
    uint queryNode = bvhLeafNode(q, u_faceCount);
    vec3 lo = g_boxes[queryNode].lo.xyz, hi = g_boxes[queryNode].hi.xyz;
    uint face = g_links[queryNode].x;
    uvec3 faceNodesQ = faceNodes(face);
    uint object = g_faceInfo[face].object;
    uint visits = 0u;
    for (; visits < u_visitsPerRound && node != GLC_BVH_NONE; ++visits) {
        uvec4 links = g_links[node];
        bool holdsLaterLeaf = bvhEscapeStart(links.w, u_faceCount) > q + 1u;
        if (holdsLaterLeaf && boxesOverlap(lo, hi, g_boxes[node].lo.xyz, g_boxes[node].hi.xyz)) {
            if (bvhIsLeaf(node, u_faceCount)) {
                uint other = links.x;
                if (validFacePair(object, faceNodesQ, g_faceInfo[other].object, faceNodes(other), u_pairRules))
                    GLC_APPEND(GLC_LIST_CANDIDATES, g_facePairs, uvec2(min(face, other), max(face, other)))
                node = links.w;
            } else {
                node = links.x;
            }
        } else {
            node = links.w;
        }
    }
    g_resume[q] = node;
    if (node != GLC_BVH_NONE && u_lastRound != 0u) atomicAdd(g_counters.stats[GLC_STAT_BVH_UNFINISHED], 1u);
    atomicAdd(g_counters.stats[GLC_STAT_BVH_NODE_VISITS], visits);
}
