// The broad phases' shared rule for one face pair f < g: a valid pair (collision.glsl) whose
// inflated float face boxes overlap is a candidate. Include after layout.glsl, collision.glsl and
// face_nodes.glsl, with NodePositionsBuf (g_positions) and FaceInfoBuf (g_faceInfo) declared.

uniform uint u_pairRules;      // GLC_RULE_* bits
uniform float u_halfThickness; // m: float(0.5 * thickness), as model::halfThicknessFloat

bool isCandidatePair(uint f, uint g) {
    uvec3 nf = faceNodes(f), ng = faceNodes(g);
    if (!validFacePair(g_faceInfo[f].object, nf, g_faceInfo[g].object, ng, u_pairRules)) return false;
    vec3 loF, hiF, loG, hiG;
    faceBox(g_positions[nf.x].xyz, g_positions[nf.y].xyz, g_positions[nf.z].xyz, u_halfThickness, loF, hiF);
    faceBox(g_positions[ng.x].xyz, g_positions[ng.y].xyz, g_positions[ng.z].xyz, u_halfThickness, loG, hiG);
    return boxesOverlap(loF, hiF, loG, hiG);
}
