#version 430 core
// TriTri — the narrow phase: triangle-triangle intersection tests (seeds/002, Alg. 3
// "Triangle-Triangle Intersection Compute Shader"). The test itself is triTriIntersect of
// common/tri_tri.glsl (fast, or robust with GLC_PRECISION_ROBUST). Variants (docs/broad-phase.md):
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

// Counts the exact fallbacks of the robust test (helper of common/tri_tri.glsl).
#define GLC_COUNT_EXACT_FALLBACK() atomicAdd(g_counters.exactFallbackCount, 1u)
#include "common/tri_tri.glsl"

uvec3 faceNodes(uint face) {
    return uvec3(g_faceIndices[3u * face], g_faceIndices[3u * face + 1u], g_faceIndices[3u * face + 2u]);
}

void appendIfIntersecting(uint f, uvec3 nf, uint g, uvec3 ng) {
    if (triTriIntersect(g_positions[nf.x].xyz, g_positions[nf.y].xyz, g_positions[nf.z].xyz,
                        g_positions[ng.x].xyz, g_positions[ng.y].xyz, g_positions[ng.z].xyz))
        GLC_APPEND(g_counters.intersectionCount, g_counters.intersectionCapacity, g_intersections, uvec2(f, g))
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
    if (boxesOverlap(loF, hiF, loG, hiG))
        GLC_APPEND(g_counters.candidateCount, g_counters.candidateCapacity, g_facePairs, uvec2(f, g))
    appendIfIntersecting(f, nf, g, ng);
}

#else // octree mode: one invocation per candidate

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_FACE_PAIRS) readonly buffer FacePairsBuf { uvec2 g_facePairs[]; };

void main() {
    uint i = globalIndex();
    if (i >= min(g_counters.candidateCount, g_counters.candidateCapacity)) return;
    uvec2 pair = g_facePairs[i];
    appendIfIntersecting(pair.x, faceNodes(pair.x), pair.y, faceNodes(pair.y));
}

#endif
