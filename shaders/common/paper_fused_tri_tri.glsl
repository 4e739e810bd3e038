// The paper's fused TriTri (seeds/002, Alg. 3), kept as a benchmark reference in shaders/bench/:
// one invocation per face pair f < g over the upper triangle of the faces x faces grid (2D tiles
// the host walks). Every valid pair is tested with the fast triangle test (no broad-phase list in
// between) and appended to the intersections when it meets; a valid pair whose face boxes overlap
// is also appended to the candidates, so the result can be compared with the engine's pipeline.
// The masked variant first drops pairs whose leaf boxes' mask entry is 0 (Alg. 3 line 9).
// Include after layout.glsl.
#include "common/collision.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"
#include "common/tri_tri.glsl"

layout(local_size_x = GLC_FACE_PAIR_TILE, local_size_y = GLC_FACE_PAIR_TILE) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_FACE_PAIRS) writeonly buffer FacePairsBuf { uvec2 g_facePairs[]; };
layout(std430, binding = GLC_BIND_INTERSECTIONS) writeonly buffer IntersectionsBuf { uvec2 g_intersections[]; };

uniform uint u_faceCount;
uniform uint u_pairRules;      // GLC_RULE_* bits
uniform float u_halfThickness; // m: float(0.5 * thickness)
uniform uint u_tileOriginX;    // first face g (x) of this dispatch
uniform uint u_tileOriginY;    // first face f (y) of this dispatch

// Returns false when the pair is out of range or below the diagonal.
bool paperPair(out uint f, out uint g) {
    g = u_tileOriginX + gl_GlobalInvocationID.x;
    f = u_tileOriginY + gl_GlobalInvocationID.y;
    return f < u_faceCount && g < u_faceCount && g > f;
}

void paperTestPair(uint f, uint g) {
    uvec3 nf = faceNodes(f), ng = faceNodes(g);
    if (!validFacePair(g_faceInfo[f].object, nf, g_faceInfo[g].object, ng, u_pairRules)) return;
    vec3 a0 = g_positions[nf.x].xyz, a1 = g_positions[nf.y].xyz, a2 = g_positions[nf.z].xyz;
    vec3 b0 = g_positions[ng.x].xyz, b1 = g_positions[ng.y].xyz, b2 = g_positions[ng.z].xyz;
    vec3 loF, hiF, loG, hiG;
    faceBox(a0, a1, a2, u_halfThickness, loF, hiF);
    faceBox(b0, b1, b2, u_halfThickness, loG, hiG);
    if (boxesOverlap(loF, hiF, loG, hiG)) GLC_APPEND(GLC_LIST_CANDIDATES, g_facePairs, uvec2(f, g))
    if (triTriIntersect(a0, a1, a2, b0, b1, b2)) GLC_APPEND(GLC_LIST_INTERSECTIONS, g_intersections, uvec2(f, g))
}
