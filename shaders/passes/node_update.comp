#version 430 core
// glcollide-features: GLC_FORCES GLC_GROUND GLC_CONTACTS GLC_CHECK_FINITE GLC_PREDICT GLC_GROUND_BAND
// NodeUpdate — one symplectic Euler substep (v += h w f; x += h v), pinned nodes (w = 0) held,
// optional ground plane with restitution and Coulomb friction on the velocity.
// The NodeUpdate stage of the AABB-octree pipeline (seeds/002, Table 2).
// GLC_FORCES: a force buffer exists. GLC_GROUND: the ground plane is on. GLC_CONTACTS: add the
// fixed-point contact forces of ContactResponse and clear them for the next substep.
// GLC_CHECK_FINITE: record the first non-finite new position or velocity in GpuHealth (a bit test
// on the exponent, which no compiler may fold away the way it may fold isnan/isinf).
// GLC_PREDICT (NodePredict, continuous detection; docs/ccd.md "In the engine"): only the
// velocity half, v += h w f, and the predicted end position x1 = x + h v into
// GLC_BIND_PREDICTED_POSITIONS; x stays the start of the substep for the collision stages, and
// NodeUpdate (without GLC_FORCES) then adds the contact forces and moves x. With the
// intersection-free response (decision 0024) NodePredict also adds the contact forces and applies
// the ground to x1 (GLC_CONTACTS, GLC_GROUND): x1 is then the whole step, which the safe step
// cuts where the CCD finds a possible contact, and there is no NodeUpdate.
// GLC_GROUND_BAND (with GLC_PREDICT, the intersection-free response): the ground is a contact, not
// a clamp. A node within u_groundBand above the ground gets the ground's velocity response; x1 is
// not clamped (a per-node clamp crushes a body that lands fast: it put energy into its springs),
// SafeStep cuts the step of an object whose node would cross the ground instead. A node that
// starts below the ground (input) is still lifted onto it. An approach slower than u_restingSpeed
// (what gravity adds in two substeps) is resting contact: no restitution, or a resting node would
// be bounced up every substep (energy into resting piles, decision 0024). Under implicit Euler the
// response runs before the solve, on the start velocity (ContactApply), and not in the NodePredict
// after it (u_bandResponse 0): a velocity changed after the solve no longer solves its system.
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

#ifdef GLC_PREDICT
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) writeonly buffer PredictedPositionsBuf { vec4 g_predicted[]; };
#endif
#if defined(GLC_GROUND_BAND) && defined(GLC_GROUND)
uniform float u_groundBand; // m: nodes this close above the ground are in contact with it
uniform float u_restingSpeed; // m/s: slower approaches are resting contact: no restitution
uniform uint u_bandResponse;  // 0: no velocity response in the band (the NodePredict after an implicit solve)
uniform float u_groundStiffness; // N/m per node: the implicit solve's ground penalty (0 under symplectic Euler)
uniform vec3 u_predictedAcceleration; // m/s²: what the solve that follows adds (gravity; 0 under symplectic Euler)
#endif

uniform uint u_nodeCount;
#include "common/advance_node.glsl"

#if defined(GLC_GROUND_BAND) && defined(GLC_GROUND)
// The band's response: an approach faster than u_restingSpeed is reflected with the restitution,
// a slower one stopped; Coulomb friction bounded by μ times the normal impulse, which is the
// approach stopped plus, under implicit Euler, the ground penalty's push over the substep
// (h·w·k_g·depth: what holds a resting node up, so a resting node has friction too). The friction
// acts on the tangential velocity the solve will leave (u_predictedAcceleration added), so a node
// that sticks does not creep by one substep of gravity per substep.
void bandResponse(inout vec3 v, float w, float y) {
    float normalSpeed = max(-v.y, 0.0);
    float e = normalSpeed > u_restingSpeed ? u_restitution : 0.0;
    if (normalSpeed > 0.0) v.y = e * normalSpeed;
    float push = u_h * w * u_groundStiffness * max(u_groundHeight + u_groundBand - y, 0.0);
    float impulseSpeed = (1.0 + e) * normalSpeed + push;
    vec2 predicted = v.xz + u_h * u_predictedAcceleration.xz;
    float tangentialSpeed = length(predicted);
    if (tangentialSpeed > 0.0 && impulseSpeed > 0.0)
        v.xz -= predicted * min(1.0, u_friction * impulseSpeed / tangentialSpeed);
}
#endif

#ifdef GLC_PREDICT
void predictNode(uint i, vec3 f, uint substep) {
    vec4 p = g_positions[i];
    if (p.w <= 0.0) { // pinned: held
        g_velocities[i] = vec4(0.0);
        g_predicted[i] = p;
        return;
    }
    vec3 v = advancedVelocity(g_velocities[i].xyz, p.w, f);
#if defined(GLC_GROUND_BAND) && defined(GLC_GROUND)
    if (u_bandResponse != 0u && p.y <= u_groundHeight + u_groundBand) bandResponse(v, p.w, p.y);
    vec3 x = advancedPosition(p.xyz, v);
    if (p.y < u_groundHeight) x.y = max(x.y, u_groundHeight);
#else
    vec3 x = advancedPosition(p.xyz, v);
#ifdef GLC_GROUND
    applyGround(x, v);
#endif
#endif
    g_velocities[i] = vec4(v, 0.0);
    g_predicted[i] = vec4(x, p.w);
#ifdef GLC_CHECK_FINITE
    checkFinite(i, x, v, substep);
#endif
}
#endif

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
#if defined(GLC_PREDICT) && defined(GLC_CHECK_FINITE)
    predictNode(i, f, u_substep);
#elif defined(GLC_PREDICT)
    predictNode(i, f, 0u);
#elif defined(GLC_CHECK_FINITE)
    advanceNode(i, f, u_substep);
#else
    advanceNode(i, f, 0u);
#endif
}
