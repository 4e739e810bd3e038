#version 430 core
// BBCollision — the broad phase of the AABB-octree pipeline (seeds/002, Alg. 2 "BBCollision
// Compute Shader", Fig. 7). Three variants (docs/broad-phase.md):
//   (default)     octree, step 1: 2D over leaf-box pairs (i <= j); a pair whose objects may
//                 collide (i == j only with self-collisions) and whose boxes overlap is appended
//                 to the box-pair list.
//   GLC_BB_EXPAND octree, step 2: one work group per box pair, looping over faces(i) x faces(j)
//                 (flattened, shared by the group's threads and z slices); valid pairs whose face boxes overlap
//                 are appended to the candidate list as (lower, higher) face index. Work is
//                 proportional to the face pairs of overlapping boxes, never to faces^2.
//   GLC_BB_MASK   the paper's masked scheme: 2D over box pairs, writes mask[i * boxes + j] (and
//                 [j * boxes + i]) = 1 where the boxes may collide and overlap, else 0; TriTri then
//                 visits every face pair and skips those whose boxes' mask is 0.
// A face box lies inside its leaf box (same float min/max, same inflation), so two faces whose
// boxes overlap always lie in overlapping leaf boxes: no candidate is lost. CPU twin:
// cpu::twinCandidates (brute force over all pairs).
#include "common/layout.glsl"
#include "common/collision.glsl"

layout(std430, binding = GLC_BIND_BOXES) readonly buffer BoxesBuf { GpuBox g_boxes[]; };

uniform uint u_pairRules;      // GLC_RULE_* bits
uniform uint u_boxCount;       // objects * boxesPerObject
uniform uint u_boxesPerObject; // 8^depth; object of box b = b / u_boxesPerObject
uniform uint u_originX;        // first box (x = j) of this 2D tile (host loops over tiles)
uniform uint u_originY;        // first box (y = i) of this 2D tile

#if defined(GLC_BB_EXPAND)

#define GLC_EXPAND_GROUP 64
layout(local_size_x = GLC_EXPAND_GROUP) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_FACES) readonly buffer FacesBuf { uint g_faceIndices[]; };
layout(std430, binding = GLC_BIND_BOX_FACE_LIST) readonly buffer BoxFaceListBuf { uint g_boxFaceList[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) writeonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_BOX_FACE_OFFSETS) readonly buffer BoxFaceOffsetsBuf { uint g_boxFaceOffsets[]; };
layout(std430, binding = GLC_BIND_BOX_PAIRS) readonly buffer BoxPairsBuf { uvec2 g_boxPairs[]; };
layout(std430, binding = GLC_BIND_COLLISION_COUNTERS) coherent buffer CollisionCountersBuf { GpuCollisionCounters g_counters; };

uniform float u_halfThickness; // m: float(0.5 * thickness), as cpu::halfThicknessFloat

uvec3 faceNodes(uint face) {
    return uvec3(g_faceIndices[3u * face], g_faceIndices[3u * face + 1u], g_faceIndices[3u * face + 2u]);
}

void main() {
    // Groups (x, y) = box pair (indirect dispatch; more than 65535 spill into y), z = slice. The
    // nA x nB face pairs of a box pair are one flat index range, shared out over the group's
    // threads and the z slices, so no invocation runs more than 2^15 loop iterations: llvmpipe
    // ends any shader invocation after 65535 loop iterations in total (gallivm's loop limiter),
    // and an earlier version, one group per box pair walking faces(i) x faces(j), silently lost
    // pairs there once a box held ~1000 faces. The host sizes z from the largest box.
    uint pair = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    if (pair >= min(g_counters.boxPairCount, g_counters.boxPairCapacity)) return;
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
        uvec3 nodesA = faceNodes(faceA), nodesB = faceNodes(faceB);
        if (!validFacePair(g_faceInfo[faceA].object, nodesA, g_faceInfo[faceB].object, nodesB, u_pairRules)) continue;
        vec3 loA, hiA, loB, hiB;
        faceBox(g_positions[nodesA.x].xyz, g_positions[nodesA.y].xyz, g_positions[nodesA.z].xyz, u_halfThickness,
                loA, hiA);
        faceBox(g_positions[nodesB.x].xyz, g_positions[nodesB.y].xyz, g_positions[nodesB.z].xyz, u_halfThickness,
                loB, hiB);
        if (!boxesOverlap(loA, hiA, loB, hiB)) continue;
        GLC_APPEND(g_counters.candidateCount, g_counters.candidateCapacity, g_facePairs,
                   uvec2(min(faceA, faceB), max(faceA, faceB)))
    }
}

#else // box-pair variants: 2D over leaf-box pairs

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef GLC_BB_MASK
layout(std430, binding = GLC_BIND_BOX_MASK) writeonly buffer BoxMaskBuf { uint g_boxMask[]; };
#else
layout(std430, binding = GLC_BIND_BOX_PAIRS) writeonly buffer BoxPairsBuf { uvec2 g_boxPairs[]; };
layout(std430, binding = GLC_BIND_COLLISION_COUNTERS) coherent buffer CollisionCountersBuf { GpuCollisionCounters g_counters; };
#endif

void main() {
    uint j = u_originX + gl_GlobalInvocationID.x;
    uint i = u_originY + gl_GlobalInvocationID.y;
    if (i >= u_boxCount || j >= u_boxCount || j < i) return;
    bool mayCollide = objectsMayCollide(i / u_boxesPerObject, j / u_boxesPerObject, u_pairRules) &&
                      (i != j || (u_pairRules & GLC_RULE_SELF) != 0u);
    bool hit = mayCollide && boxesOverlap(g_boxes[i].lo.xyz, g_boxes[i].hi.xyz, g_boxes[j].lo.xyz, g_boxes[j].hi.xyz);
#ifdef GLC_BB_MASK
    g_boxMask[i * u_boxCount + j] = hit ? 1u : 0u;
    g_boxMask[j * u_boxCount + i] = hit ? 1u : 0u;
#else
    if (hit) GLC_APPEND(g_counters.boxPairCount, g_counters.boxPairCapacity, g_boxPairs, uvec2(i, j))
#endif
}

#endif
