#version 430 core
// glcollide-features: GLC_FORCES GLC_GROUND GLC_CONTACTS GLC_CHECK_FINITE
// NodeUpdate — one symplectic Euler substep (v += h w f; x += h v), pinned nodes (w = 0) held,
// optional ground plane with restitution and Coulomb friction on the velocity.
// The NodeUpdate stage of the AABB-octree pipeline (seeds/002, Table 2).
// GLC_FORCES: a force buffer exists. GLC_GROUND: the ground plane is on. GLC_CONTACTS: add the
// fixed-point contact forces of ContactResponse and clear them for the next substep.
// GLC_CHECK_FINITE: record the first non-finite new position or velocity in GpuHealth (a bit test
// on the exponent, which no compiler may fold away the way it may fold isnan/isinf).
// Twin: cpu::nodeUpdate.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
#ifdef GLC_FORCES
layout(std430, binding = GLC_BIND_NODE_FORCES) readonly buffer NodeForcesBuf { vec4 g_forces[]; };
#endif
#ifdef GLC_CONTACTS
layout(std430, binding = GLC_BIND_CONTACT_FORCES) buffer ContactForcesBuf { ivec4 g_contactForces[]; };
uniform float u_contactForceScale; // fixed-point units per N
#endif

#ifdef GLC_CHECK_FINITE
layout(std430, binding = GLC_BIND_HEALTH) buffer HealthBuf { GpuHealth g_health; };
uniform uint u_substep; // index of this substep within its frame
#endif

uniform uint u_nodeCount;
#include "common/advance_node.glsl"

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    vec3 f = vec3(0.0);
#ifdef GLC_FORCES
    f += g_forces[i].xyz;
#endif
#ifdef GLC_CONTACTS
    f += vec3(g_contactForces[i].xyz) / u_contactForceScale;
    g_contactForces[i] = ivec4(0);
#endif
#ifdef GLC_CHECK_FINITE
    advanceNode(i, f, u_substep);
#else
    advanceNode(i, f, 0u);
#endif
}
