// The external force on one node: gravity, viscous (air) damping, linear wind drag on its faces.
// Shared by NodeForce (scenes without springs) and SpringUpdate / ImplicitSetup, which add it to
// the springs' force in the same dispatch. Compiled with any of GLC_GRAVITY, GLC_DAMPING,
// GLC_WIND. Include after g_positions and g_velocities are declared. Twin: cpu::nodeForce.
#ifdef GLC_WIND
layout(std430, binding = GLC_BIND_FACES) readonly buffer FacesBuf { uint g_faceIndices[]; };
layout(std430, binding = GLC_BIND_NODE_FACE_OFFSETS) readonly buffer NodeFaceOffsetsBuf { uint g_nodeFaceOffsets[]; };
layout(std430, binding = GLC_BIND_NODE_FACE_LIST) readonly buffer NodeFaceListBuf { uint g_nodeFaceList[]; };
uniform vec3 u_windVelocity; // m/s
uniform float u_windDrag;    // kg/(m^2 s)
#endif
uniform vec3 u_gravity;  // m/s^2
uniform float u_damping; // 1/s

// Zero for a pinned node (w = 0). Wind gathers the node's faces through a CSR list (no atomics).
vec3 externalForce(uint i) {
    float w = g_positions[i].w;
    vec3 f = vec3(0.0);
    if (w > 0.0) {
        float m = 1.0 / w;
#ifdef GLC_GRAVITY
        f += m * u_gravity;
#endif
#ifdef GLC_DAMPING
        f -= (u_damping * m) * g_velocities[i].xyz;
#endif
#ifdef GLC_WIND
        for (uint k = g_nodeFaceOffsets[i]; k < g_nodeFaceOffsets[i + 1u]; ++k) {
            uint face = g_nodeFaceList[k];
            uint a = g_faceIndices[3u * face], b = g_faceIndices[3u * face + 1u], c = g_faceIndices[3u * face + 2u];
            vec3 twiceAreaNormal = cross(g_positions[b].xyz - g_positions[a].xyz, g_positions[c].xyz - g_positions[a].xyz);
            float twiceArea = length(twiceAreaNormal);
            if (twiceArea <= 0.0) continue; // a degenerate face catches no wind
            vec3 normal = twiceAreaNormal / twiceArea;
            vec3 faceVelocity = (g_velocities[a].xyz + g_velocities[b].xyz + g_velocities[c].xyz) / 3.0;
            float normalSpeed = dot(u_windVelocity - faceVelocity, normal);
            f += (u_windDrag * twiceArea * normalSpeed / 6.0) * normal; // drag * area * speed, a third per corner
        }
#endif
    }
    return f;
}
