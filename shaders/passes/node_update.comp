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
uniform float u_h; // s
#ifdef GLC_GROUND
uniform float u_groundHeight; // m
uniform float u_restitution;
uniform float u_friction;
#endif

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    vec4 p = g_positions[i];
    float w = p.w;
#ifdef GLC_CONTACTS
    vec3 contactForce = vec3(g_contactForces[i].xyz) / u_contactForceScale;
    g_contactForces[i] = ivec4(0);
#endif
    if (w <= 0.0) {
        g_velocities[i] = vec4(0.0);
        return;
    }
    vec3 v = g_velocities[i].xyz;
#ifdef GLC_FORCES
    v += (u_h * w) * g_forces[i].xyz;
#endif
#ifdef GLC_CONTACTS
    v += (u_h * w) * contactForce;
#endif
    vec3 x = p.xyz + u_h * v;
#ifdef GLC_GROUND
    if (x.y < u_groundHeight) {
        x.y = u_groundHeight;
        if (v.y < 0.0) {
            float normalSpeed = -v.y;
            v.y = u_restitution * normalSpeed;
            float tangentialSpeed = length(v.xz);
            if (tangentialSpeed > 0.0) {
                // Coulomb: the normal impulse (1+e)|vn| bounds the tangential change.
                float scale = max(0.0, 1.0 - u_friction * (1.0 + u_restitution) * normalSpeed / tangentialSpeed);
                v.xz *= scale;
            }
        }
    }
#endif
    g_positions[i] = vec4(x, w);
    g_velocities[i] = vec4(v, 0.0);
#ifdef GLC_CHECK_FINITE
    // Infinity and NaN are the floats whose 8 exponent bits are all ones.
    const uint exponent = 0x7F800000u;
    if (any(equal(floatBitsToUint(x) & exponent, uvec3(exponent))) ||
        any(equal(floatBitsToUint(v) & exponent, uvec3(exponent)))) {
        // An earlier substep of this frame (or an earlier frame, already reported) wrote a lower
        // index: keep it. All invocations of this dispatch share u_substep.
        if (g_health.badSubstep >= u_substep) {
            atomicMin(g_health.firstBadNode, i);
            atomicMin(g_health.badSubstep, u_substep);
        }
    }
#endif
}
