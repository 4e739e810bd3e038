// The box that bounds a face for the broad phase: the AABB of its three nodes' positions, and
// with GLC_SWEPT (continuous detection, docs/ccd.md "In the engine") of their predicted positions
// at the end of the substep too, inflated by the half thickness. Under linear motion every point
// of the face between t = 0 and t = 1 is a convex combination of those six points, so the swept
// box holds the face over the whole substep. min and max are exact: without GLC_SWEPT the box is
// bit for bit faceBox() of collision.glsl. Include with NodePositionsBuf
// (g_positions) declared. CPU twin: cpu::sweptFaceBox.
#ifdef GLC_SWEPT
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_predicted[]; };
#endif

// Grows [lo, hi] by node n over the substep.
void addNodeBounds(uint n, inout vec3 lo, inout vec3 hi) {
    vec3 x0 = g_positions[n].xyz;
    lo = min(lo, x0);
    hi = max(hi, x0);
#ifdef GLC_SWEPT
    vec3 x1 = g_predicted[n].xyz;
    lo = min(lo, x1);
    hi = max(hi, x1);
#endif
}

void faceBoxOfNodes(uvec3 nodes, float halfThickness, out vec3 lo, out vec3 hi) {
    lo = g_positions[nodes.x].xyz;
    hi = lo;
    addNodeBounds(nodes.x, lo, hi);
    addNodeBounds(nodes.y, lo, hi);
    addNodeBounds(nodes.z, lo, hi);
    lo = lo - vec3(halfThickness);
    hi = hi + vec3(halfThickness);
}
