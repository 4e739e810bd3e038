// The force law of the contact response (contact_vertex_face.comp, contact_edge_edge.comp;
// docs/collisions.md): the thickness-based penalty of cloth/deformable contact codes.
// Force per contact: clamp(k·depth − c·v_n, 0, cap) along the contact normal, opposite forces on
// the other side spread by barycentric weights: momentum is conserved exactly up to rounding.
// Forces are summed per node with integer atomics in fixed point (u_forceScale units per N):
// integer addition is associative, so the sum does not depend on thread order or on how the
// contacts are split over dispatches. NodeUpdate adds and clears them.
// Include after layout.glsl. Twin: src/cpu/contact_twin.cpp.
#ifndef GLC_CONTACT_FORCE_GLSL
#define GLC_CONTACT_FORCE_GLSL

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_CONTACT_FORCES) buffer ContactForcesBuf { ivec4 g_contactForces[]; };

uniform float u_thickness;   // m
uniform float u_stiffness;   // N/m
uniform float u_damping;     // N·s/m
uniform float u_forceCap;    // N per contact
uniform float u_forceScale;  // fixed-point units per N

void addForce(uint node, vec3 f) {
    ivec3 q = ivec3(round(f * u_forceScale));
    if (q.x != 0) atomicAdd(g_contactForces[node].x, q.x);
    if (q.y != 0) atomicAdd(g_contactForces[node].y, q.y);
    if (q.z != 0) atomicAdd(g_contactForces[node].z, q.z);
}

// Normal force magnitude: penalty on the depth, damping on the normal speed (separating > 0),
// never pulling, never above the cap.
float normalForce(float depth, float normalSpeed) {
    return clamp(u_stiffness * depth - u_damping * normalSpeed, 0.0, u_forceCap);
}

#endif
