// The Ccd stage's pair selection, shared by the CCD kernel (feature_ccd.comp) and its filter
// (feature_ccd_filter.comp, which compacts the pairs left to test when radial culling is on):
// which pairs are tested at all, and at what separation. Both kernels decide each pair with this
// same code, so the pairs the filter passes on are decided alike by the CCD kernel. Include after
// common/layout.glsl, lists.glsl, face_nodes.glsl, index.glsl, contact_geometry.glsl and
// radial_cull.glsl.
#ifndef GLC_CCD_PAIR_SELECTION_GLSL
#define GLC_CCD_PAIR_SELECTION_GLSL

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_predicted[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };
layout(std430, binding = GLC_BIND_TANGLED) readonly buffer TangledBuf { uint g_tangled[]; };

uniform uint u_edgeEdge;       // 0: vertex-face pairs, 1: edge-edge pairs
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
        uvec2 item = g_vertexFace[i]; // (node, face)
        uvec3 f = faceNodes(item.y);
        return uvec4(item.x, f.x, f.y, f.z);
    }
    uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g): edge e from corner e to corner (e+1)%3
    uvec3 a = faceNodes(item.x / 3u), b = faceNodes(item.y / 3u);
    uint e = item.x % 3u, g = item.y % 3u;
    return uvec4(a[e], a[(e + 1u) % 3u], b[g], b[(g + 1u) % 3u]);
}

// Whether radial culling leaves pair i out (common/radial_cull.glsl).
bool radialCulled(uint i) {
    if (u_edgeEdge == 0u) {
        uvec2 item = g_vertexFace[i]; // (node, face)
        return glcRadialCulledVertexFace(item.x, item.y);
    }
    uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g)
    return glcRadialCulled(item.x / 3u, item.y / 3u);
}

// Whether pair i has a marked node or face (vertex-face) or a marked face (edge-edge): to come
// apart, an intersecting region must pass back through the faces around it, so every pair of its
// features is left out, not only those between the intersecting faces themselves.
bool tangledPair(uint i) {
    if (u_edgeEdge == 0u) {
        uvec2 item = g_vertexFace[i];
        return g_tangled[item.x] != 0u || g_tangled[u_nodeCount + item.y] != 0u;
    }
    uvec2 item = g_edgeEdge[i];
    return g_tangled[u_nodeCount + item.x / 3u] != 0u ||
           g_tangled[u_nodeCount + item.y / 3u] != 0u;
}

// What the Ccd stage does with pair i: test it, or leave it out — its faces intersect at x0
// (counted: GLC_STAT_CCD_TANGLED), none of its nodes moves, or radial culling proves it cannot
// touch (counted: GLC_STAT_RADIAL_CULLED_CCD).
#define GLC_CCD_TEST 0
#define GLC_CCD_LEFT_OUT 1

struct CcdPair {
    int action;
    uvec4 nodes;
    vec3 s0, s1, s2, s3; // x0
    vec3 e0, e1, e2, e3; // x1
    float separation;
};

CcdPair selectCcdPair(uint i) {
    CcdPair p;
    p.action = GLC_CCD_LEFT_OUT;
    p.separation = u_minSeparation;
    if (u_skipTangled != 0u && tangledPair(i)) {
        atomicAdd(g_counters.stats[GLC_STAT_CCD_TANGLED], 1u);
        return p;
    }
    uvec4 n = pairNodes(i);
    p.nodes = n;
    p.s0 = g_positions[n.x].xyz; p.s1 = g_positions[n.y].xyz; p.s2 = g_positions[n.z].xyz; p.s3 = g_positions[n.w].xyz;
    p.e0 = g_predicted[n.x].xyz; p.e1 = g_predicted[n.y].xyz; p.e2 = g_predicted[n.z].xyz; p.e3 = g_predicted[n.w].xyz;
    if (u_skipStill != 0u && all(equal(p.s0, p.e0)) && all(equal(p.s1, p.e1)) && all(equal(p.s2, p.e2)) &&
        all(equal(p.s3, p.e3)))
        return p;
    if (u_gapRelative != 0u) {
        float halfGap = 0.5 * startDistance(p.s0, p.s1, p.s2, p.s3);
        p.separation = halfGap < u_minSeparation ? halfGap : 0.0;
    }
    // Radial culling: a pair tested for true contact (zero separation) with a free face cannot
    // touch (the face intersects nothing of its surface during the substep). Proximity tests
    // (separation > 0) are not culled: the theorem says nothing about distances.
    if (p.separation == 0.0 && radialCulled(i)) {
        atomicAdd(g_counters.stats[GLC_STAT_RADIAL_CULLED_CCD], 1u);
        return p;
    }
    p.action = GLC_CCD_TEST;
    return p;
}

#endif
