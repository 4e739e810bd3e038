#version 430 core
// glcollide-features: GLC_SWEPT
// Octree broad phase, step 2 of BBCollision: expands the overlapping leaf-box pairs of
// octree_box_pairs.comp into candidate face pairs. One work group per box pair (indirect dispatch
// from the box-pair count; more than 65535 pairs spill into y), looping over faces(i) x faces(j);
// a valid pair whose face boxes overlap is appended to the candidate list as (lower, higher).
// Work is proportional to the face pairs of overlapping boxes, never to faces^2. A face box lies
// inside its leaf box (same float min/max, same inflation), so no candidate is lost.
// CPU twin: cpu::twinCandidates (brute force over all pairs).
#include "common/layout.glsl"
#include "common/collision.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_EXPAND_GROUP) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_BOX_FACE_LIST) readonly buffer BoxFaceListBuf { uint g_boxFaceList[]; };
layout(std430, binding = GLC_BIND_BOX_FACE_OFFSETS) readonly buffer BoxFaceOffsetsBuf { uint g_boxFaceOffsets[]; };
layout(std430, binding = GLC_BIND_BOX_PAIRS) readonly buffer BoxPairsBuf { uvec2 g_boxPairs[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) writeonly buffer FacePairsBuf { uvec2 g_facePairs[]; };

#include "common/face_pair_candidate.glsl"

void main() {
    // Groups (x, y) = box pair, z = slice. The nA x nB face pairs of a box pair are one flat index
    // range, shared out over the group's threads and the z slices, so no invocation runs more than
    // 2^15 loop iterations: llvmpipe ends any shader invocation after 65535 loop iterations in
    // total (gallivm's loop limiter), and an earlier version, one group per box pair walking
    // faces(i) x faces(j), silently lost pairs there once a box held ~1000 faces. The host sizes z
    // from the largest box.
    uint pair = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    if (pair >= storedCount(GLC_LIST_BOX_PAIRS)) return;
    uvec2 boxes = g_boxPairs[pair];
    bool sameBox = boxes.x == boxes.y;
    uint aBegin = g_boxFaceOffsets[boxes.x], aCount = g_boxFaceOffsets[boxes.x + 1u] - aBegin;
    uint bBegin = g_boxFaceOffsets[boxes.y], bCount = g_boxFaceOffsets[boxes.y + 1u] - bBegin;
    uint total = aCount * bCount; // < 2^32: boxes hold < 65536 faces (checked on the host)
    uint stride = uint(GLC_EXPAND_GROUP) * gl_NumWorkGroups.z;
    for (uint k = gl_WorkGroupID.z * uint(GLC_EXPAND_GROUP) + gl_LocalInvocationID.x; k < total; k += stride) {
        uint ia = k / bCount, ib = k - ia * bCount;
        // Within one box, list position order is face order: partners b > a only.
        if (sameBox && ib <= ia) continue;
        uint faceA = g_boxFaceList[aBegin + ia], faceB = g_boxFaceList[bBegin + ib];
        if (isCandidatePair(faceA, faceB))
            GLC_APPEND(GLC_LIST_CANDIDATES, g_facePairs, uvec2(min(faceA, faceB), max(faceA, faceB)))
    }
}
