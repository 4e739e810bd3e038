#version 430 core
// TriTri — the narrow phase: triangle-triangle intersection tests (seeds/002, Alg. 3
// "Triangle-Triangle Intersection Compute Shader"). Fast: triTriIntersect of common/tri_tri.glsl.
// Robust (GLC_PRECISION_ROBUST): the filtered test glcTriTriFiltered of common/tri_tri_robust.glsl;
// a pair it cannot decide is appended (as its candidate index) to the undecided list, which the
// exact pass tri_tri_exact.comp finishes. With robust precision only candidates are tested: closed
// triangles that meet have overlapping face boxes (each box contains its triangle), so a valid pair
// that is not a candidate does not intersect. Variants (docs/broad-phase.md):
//   (default)            octree mode: one invocation per candidate pair of BBCollision
//                        (indirect dispatch) -> intersection list.
//   GLC_TRITRI_ALL_PAIRS 2D over every face pair f < g (host loops over 2D tiles of 16 x 16
//                        groups; only tiles on or above the diagonal). A valid pair whose face boxes
//                        overlap is appended to the candidate list (for the contact response); every
//                        valid pair is tested and appended to the intersections when it intersects:
//                        the paper's reference.
//     + GLC_TRITRI_MASKED the paper's masked scheme: a pair whose leaf boxes' mask entry is 0 returns
//                        at once (Alg. 3 line 9); the rest as above.
// CPU twin: cpu::twinCandidates and cpu::twinIntersections (exact oracle).
#include "common/layout.glsl"
#include "common/collision.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_INTERSECTIONS) writeonly buffer IntersectionsBuf { uvec2 g_intersections[]; };
layout(std430, binding = GLC_BIND_FACES) readonly buffer FacesBuf { uint g_faceIndices[]; };
layout(std430, binding = GLC_BIND_COLLISION_COUNTERS) coherent buffer CollisionCountersBuf { GpuCollisionCounters g_counters; };

#ifdef GLC_PRECISION_ROBUST
#include "common/tri_tri_robust.glsl"
layout(std430, binding = GLC_BIND_UNDECIDED) writeonly buffer UndecidedBuf { uint g_undecided[]; };
#else
#include "common/tri_tri.glsl"
#endif

uvec3 faceNodes(uint face) {
    return uvec3(g_faceIndices[3u * face], g_faceIndices[3u * face + 1u], g_faceIndices[3u * face + 2u]);
}

// Tests candidate `slot` (the face pair f, g): appends it to the intersections when it intersects;
// robust appends the slot to the undecided list when the filters cannot tell (its capacity is the
// candidate capacity, so it overflows only with the candidates, which reruns everything).
void testCandidate(uint slot, uint f, uvec3 nf, uint g, uvec3 ng) {
    vec3 a0 = g_positions[nf.x].xyz, a1 = g_positions[nf.y].xyz, a2 = g_positions[nf.z].xyz;
    vec3 b0 = g_positions[ng.x].xyz, b1 = g_positions[ng.y].xyz, b2 = g_positions[ng.z].xyz;
#ifdef GLC_PRECISION_ROBUST
    int answer = glcTriTriFiltered(a0, a1, a2, b0, b1, b2);
    if (answer == GLC_UNDECIDED) {
        GLC_APPEND(g_counters.undecidedCount, g_counters.candidateCapacity, g_undecided, slot)
        return;
    }
    bool hit = answer == 1;
#else
    bool hit = triTriIntersect(a0, a1, a2, b0, b1, b2);
#endif
    if (hit) GLC_APPEND(g_counters.intersectionCount, g_counters.intersectionCapacity, g_intersections, uvec2(f, g))
}

#ifdef GLC_TRITRI_ALL_PAIRS

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) writeonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
#ifdef GLC_TRITRI_MASKED
layout(std430, binding = GLC_BIND_BOX_MASK) readonly buffer BoxMaskBuf { uint g_boxMask[]; };
uniform uint u_boxCount;
#endif

uniform uint u_faceCount;
uniform uint u_pairRules;      // GLC_RULE_* bits
uniform float u_halfThickness; // m: float(0.5 * thickness), as cpu::halfThicknessFloat
uniform uint u_originX;        // first face g of this 2D tile
uniform uint u_originY;        // first face f of this 2D tile

void main() {
    uint g = u_originX + gl_GlobalInvocationID.x;
    uint f = u_originY + gl_GlobalInvocationID.y;
    if (f >= u_faceCount || g >= u_faceCount || g <= f) return;
    GpuFaceInfo infoF = g_faceInfo[f], infoG = g_faceInfo[g];
#ifdef GLC_TRITRI_MASKED
    if (g_boxMask[infoF.box * u_boxCount + infoG.box] == 0u) return;
#endif
    uvec3 nf = faceNodes(f), ng = faceNodes(g);
    if (!validFacePair(infoF.object, nf, infoG.object, ng, u_pairRules)) return;
    vec3 loF, hiF, loG, hiG;
    faceBox(g_positions[nf.x].xyz, g_positions[nf.y].xyz, g_positions[nf.z].xyz, u_halfThickness, loF, hiF);
    faceBox(g_positions[ng.x].xyz, g_positions[ng.y].xyz, g_positions[ng.z].xyz, u_halfThickness, loG, hiG);
    bool candidate = boxesOverlap(loF, hiF, loG, hiG);
    uint slot = 0u;
    if (candidate) {
        slot = atomicAdd(g_counters.candidateCount, 1u);
        if (slot < g_counters.candidateCapacity) g_facePairs[slot] = uvec2(f, g);
    }
#ifdef GLC_PRECISION_ROBUST
    if (candidate && slot < g_counters.candidateCapacity) testCandidate(slot, f, nf, g, ng);
#else
    testCandidate(slot, f, nf, g, ng); // the paper's reference: fast tests every valid pair
#endif
}

#else // octree mode: one invocation per candidate

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };

void main() {
    uint i = globalIndex();
    if (i >= min(g_counters.candidateCount, g_counters.candidateCapacity)) return;
    uvec2 pair = g_facePairs[i];
    testCandidate(i, pair.x, faceNodes(pair.x), pair.y, faceNodes(pair.y));
}

#endif
