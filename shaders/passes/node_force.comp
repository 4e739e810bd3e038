#version 430 core
// glcollide-features: GLC_GRAVITY GLC_DAMPING GLC_WIND
// NodeForce — per-node external forces: gravity, viscous damping, linear wind drag on faces.
// The NodeForce stage of the AABB-octree pipeline (seeds/002, Table 2, Fig. 4). One invocation
// per node; wind gathers the node's faces through a CSR list, so no atomics are needed.
// Compiled with any of GLC_GRAVITY, GLC_DAMPING, GLC_WIND. CPU twin: cpu::nodeForce.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_NODE_FORCES) writeonly buffer NodeForcesBuf { vec4 g_forces[]; };
#ifdef GLC_WIND
layout(std430, binding = GLC_BIND_FACES) readonly buffer FacesBuf { uint g_faceIndices[]; };
layout(std430, binding = GLC_BIND_NODE_FACE_OFFSETS) readonly buffer NodeFaceOffsetsBuf { uint g_nodeFaceOffsets[]; };
layout(std430, binding = GLC_BIND_NODE_FACE_LIST) readonly buffer NodeFaceListBuf { uint g_nodeFaceList[]; };
uniform vec3 u_windVelocity; // m/s
uniform float u_windDrag;    // kg/(m^2 s)
#endif

uniform uint u_nodeCount;
uniform vec3 u_gravity;   // m/s^2
uniform float u_damping;  // 1/s

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
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
    g_forces[i] = vec4(f, 0.0);
}
