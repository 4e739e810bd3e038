// The broad phases' shared rule for one face pair f < g: a valid pair (collision.glsl) whose
// inflated float face boxes (face_bounds.glsl: swept over the substep with GLC_SWEPT) overlap is
// a candidate. Include after layout.glsl, collision.glsl and face_nodes.glsl, with
// NodePositionsBuf (g_positions) and FaceInfoBuf (g_faceInfo) declared.
#include "common/face_bounds.glsl"

uniform uint u_pairRules;      // GLC_RULE_* bits
uniform float u_halfThickness; // m: float(0.5 * thickness), as model::halfThicknessFloat

bool isCandidatePair(uint f, uint g) {
    uvec3 nf = faceNodes(f), ng = faceNodes(g);
    if (!validFacePair(g_faceInfo[f].object, nf, g_faceInfo[g].object, ng, u_pairRules)) return false;
    vec3 loF, hiF, loG, hiG;
    faceBoxOfNodes(nf, u_halfThickness, loF, hiF);
    faceBoxOfNodes(ng, u_halfThickness, loG, hiG);
    return boxesOverlap(loF, hiF, loG, hiG);
}
