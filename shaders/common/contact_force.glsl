// The force law of the contact response (contact_vertex_face.comp, contact_edge_edge.comp;
// docs/collisions.md, docs/design/decisions/0019-cloth-response.md). A contact is four nodes with
// signed weights a (side A: +, summing to 1; side B: −, summing to −1) and a unit normal u pointing
// from B to A. Its force is f·u on side A and the opposite on side B, spread by the weights, so
// momentum is conserved exactly up to rounding. With the penalty response (or dt = 0) f is the
// penalty clamp(k·depth − c·v_n, 0, cap). With the Bridson response it is Bridson, Fedkiw,
// Anderson 2002, §7.1, as forces: a contact is acting when v_n < v_t = depth / max(10·dt, τ)
// (the speed that restores the thickness in 10 substeps, or in the relaxation time τ); an acting
// contact gets
// - the inelastic impulse that cancels an approaching v_n < 0, and
// - the penalty, but at most what raises v_n to v_t (no bounce off the stored penalty energy),
// each a change Δv_n of the pair turned into the force Δv_n / (Σ a_i² w_i · dt) (w: inverse
// masses) and divided by the largest count of acting contacts on any of its moved nodes (counted
// by a first pass into .w of the force sums), so the Jacobi sum on a node is at most the average
// of its contacts' corrections, never more than the largest one. Capped at u_forceCap.
// Forces are summed per node with integer atomics in fixed point (u_forceScale units per N):
// integer addition is associative, so the sum does not depend on thread order or on how the
// contacts are split over dispatches. NodeUpdate adds and clears them (.w too).
// Friction (u_friction = μ > 0, dt > 0; docs/collisions.md "Friction between bodies"): every
// contact that pushes also pulls against its relative tangential velocity v_t = v_rel − v_n·u,
// with min(μ·f, |v_t| / (Σ a_i² w_i · dt · count)): Coulomb's cone, but never more than stops
// the sliding in this substep (Jacobi-averaged like the normal part), so it cannot reverse it or
// add energy. With the penalty the count pass then counts the pushing contacts (it counts
// nothing otherwise); at μ = 0 nothing changes.
// Include after layout.glsl. Twin: src/cpu/contact_twin.cpp.
#ifndef GLC_CONTACT_FORCE_GLSL
#define GLC_CONTACT_FORCE_GLSL

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_CONTACT_FORCES) buffer ContactForcesBuf { ivec4 g_contactForces[]; };
#ifdef GLC_PREDICTED_FORCES
// The forces at the start of the substep (NodeForce or SpringUpdate): the filter before an implicit
// solve predicts the solve's velocity change h·w·f from them (ContactParams::predictedForces).
layout(std430, binding = GLC_BIND_NODE_FORCES) readonly buffer NodeForcesBuf { vec4 g_forces[]; };
#endif

uniform float u_thickness;   // m
uniform float u_stiffness;   // N/m
uniform float u_damping;     // N·s/m
uniform float u_forceCap;    // N per contact
uniform float u_forceScale;  // fixed-point units per N
uniform float u_substep;     // s: the substep length dt (0: penalty only, sides from the current positions)
uniform uint u_velocityResponse; // 1: Bridson's response (below); 0: the penalty alone
uniform float u_relaxationTime;  // s: Bridson's target speed restores the thickness over at least this
uniform uint u_repulsion;        // 0: the filter before an implicit solve (below)
uniform uint u_countPass;    // 1: count acting contacts per node into .w; 0: add the forces
uniform uint u_previousSides; // 1: sides of open surfaces from x − dt·v; 0: from x (intersection-free response)
uniform float u_friction;    // Coulomb μ between bodies (0: none)
uniform float u_leavingStep;  // s: ContactParams::leavingStep (0: none leaves the solve)
uniform float u_leavingSpeed; // m/s: ContactParams::leavingSpeed

// Position at the start of the substep: symplectic Euler's last step was x += dt·v with this v
// (up to rounding, and except for nodes the ground plane clamped), so x − dt·v is where it was.
// The intersection-free response (u_previousSides = 0) starts every substep intersection-free and
// runs after this substep's velocity update: x itself is on the side to keep.
vec3 previousPosition(uint n) {
    float back = u_previousSides != 0u ? u_substep : 0.0;
    return g_positions[n].xyz - back * g_velocities[n].xyz;
}

void addForce(uint node, vec3 f) {
    ivec3 q = ivec3(round(f * u_forceScale));
    if (q.x != 0) atomicAdd(g_contactForces[node].x, q.x);
    if (q.y != 0) atomicAdd(g_contactForces[node].y, q.y);
    if (q.z != 0) atomicAdd(g_contactForces[node].z, q.z);
}

// A contact's force F on side A, spread over its four nodes by their signed weights. Returns 1.
uint addContactForce(uvec4 n, vec4 a, vec3 F) {
    addForce(n.x, a.x * F);
    addForce(n.y, a.y * F);
    addForce(n.z, a.z * F);
    addForce(n.w, a.w * F);
    return 1u;
}

// Normal force magnitude: penalty on the depth, damping on the normal speed (separating > 0),
// never pulling, never above the cap.
float normalForce(float depth, float normalSpeed) {
    return clamp(u_stiffness * depth - u_damping * normalSpeed, 0.0, u_forceCap);
}

// The largest count of acting contacts (the count pass's .w) on the nodes the contact moves.
int actingCount(uvec4 n, vec4 share) {
    int count = max(max(share.x > 0.0 ? g_contactForces[n.x].w : 0, share.y > 0.0 ? g_contactForces[n.y].w : 0),
                    max(share.z > 0.0 ? g_contactForces[n.z].w : 0, share.w > 0.0 ? g_contactForces[n.w].w : 0));
    return max(count, 1);
}

// Coulomb friction of a contact pushing with normal force f (> 0): against the relative
// tangential velocity vt, at most μ·f and at most the force that stops vt in this substep
// (perSpeed: N per m/s of relative velocity changed, already divided by the count).
vec3 frictionForce(vec3 vt, float f, float perSpeed) {
    float speed = length(vt);
    if (!(speed > 0.0)) return vec3(0.0);
    float magnitude = min(u_friction * f, speed * perSpeed);
    return vt * (-magnitude / speed);
}

// The contact of nodes n with signed weights a along u at the given depth (see the top). In the
// count pass it only counts; returns 1 when it added a force.
uint respond(uvec4 n, vec4 a, vec3 u, float depth) {
    vec3 vRel = a.x * g_velocities[n.x].xyz + a.y * g_velocities[n.y].xyz + a.z * g_velocities[n.z].xyz +
                a.w * g_velocities[n.w].xyz;
    float vn = dot(vRel, u);
    // Each node's share a_i² w_i of the effective inverse mass; nodes with none (pinned, or weight
    // 0) are not moved by the contact, so they neither count it nor limit it.
    vec4 share = a * a * vec4(g_positions[n.x].w, g_positions[n.y].w, g_positions[n.z].w, g_positions[n.w].w);
    float wSum = share.x + share.y + share.z + share.w;
    // Bridson's target separating speed: the thickness restored over 10 substeps (his 0.1·d/dt),
    // or over the relaxation time when that is longer (our substeps are short: 0.1·h/dt would let
    // pairs leave the thickness at metres per second).
    bool bridson = u_velocityResponse != 0u && u_substep > 0.0 && wSum > 0.0;
    bool friction = u_friction > 0.0 && u_substep > 0.0 && wSum > 0.0;
    // The filter before an implicit solve (u_repulsion 0; decision 0024, "Velocity filters before
    // the solve"): the penalty is in the solve's matrix, so the filter does not push; it stops an
    // approach (inelastic) and applies friction bounded by μ times that impulse plus the penalty
    // k·depth the solve will apply (a resting contact has friction too), against the relative
    // tangential velocity after the solve, predicted from the forces at the start
    // (GLC_PREDICTED_FORCES: a sticking contact does not creep).
    bool beforeSolve = bridson && u_repulsion == 0u;
    float target = bridson && !beforeSolve ? depth / max(10.0 * u_substep, u_relaxationTime) : 0.0;
    // A bounce leaving the thickness gets no penalty from the solve (ContactParams::leavingStep).
    bool leaving = u_leavingStep > 0.0 && vn > u_leavingSpeed && vn * u_leavingStep >= depth;
    float penalty = leaving ? 0.0 : min(u_stiffness * max(depth, 0.0), u_forceCap);
    bool acting = beforeSolve ? vn < 0.0 || (friction && penalty > 0.0) : bridson && vn < target;
    float f = normalForce(depth, vn);
    // What the count pass counts: Bridson's acting contacts; with the penalty and friction, the
    // pushing ones (the same f > 0 as below, f ≤ the cap).
    bool counted = bridson ? acting : friction && f > 0.0;
    if (u_countPass != 0u) {
        if (counted) {
            if (share.x > 0.0) atomicAdd(g_contactForces[n.x].w, 1);
            if (share.y > 0.0) atomicAdd(g_contactForces[n.y].w, 1);
            if (share.z > 0.0) atomicAdd(g_contactForces[n.z].w, 1);
            if (share.w > 0.0) atomicAdd(g_contactForces[n.w].w, 1);
        }
        return 0u;
    }
    // N per m/s of relative velocity changed, averaged over the node's contacts (Jacobi).
    float perSpeed = counted ? 1.0 / (wSum * u_substep * float(actingCount(n, share))) : 0.0;
    if (beforeSolve) {
        if (!acting) return 0u;
        float inelastic = max(-vn, 0.0) * perSpeed;
        vec3 F = inelastic * u;
        if (friction) {
            vec3 vAfter = vRel;
#ifdef GLC_PREDICTED_FORCES
            // + h Σ a_i w_i f_i: what the solve will add (pinned nodes: w = 0)
            vAfter += u_substep * (a.x * g_positions[n.x].w * g_forces[n.x].xyz +
                                   a.y * g_positions[n.y].w * g_forces[n.y].xyz +
                                   a.z * g_positions[n.z].w * g_forces[n.z].xyz +
                                   a.w * g_positions[n.w].w * g_forces[n.w].xyz);
#endif
            F += frictionForce(vAfter - dot(vAfter, u) * u, inelastic + penalty, perSpeed);
        }
        if (F == vec3(0.0)) return 0u;
        return addContactForce(n, a, F);
    }
    if (bridson) {
        if (!acting) return 0u;                 // separating at the target speed or faster: no push
        float vAfter = max(vn, 0.0);            // after the inelastic part
        f = (vAfter - vn) * perSpeed + min(f, (target - vAfter) * perSpeed);
    }
    f = min(f, u_forceCap);
    if (!(f > 0.0)) return 0u;
    vec3 F = f * u;
    if (friction) F += frictionForce(vRel - vn * u, f, perSpeed);
    return addContactForce(n, a, F);
}

#endif
