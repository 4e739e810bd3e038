#version 430 core
// EnergyGuard — the intersection-free response's promise that contact adds no energy (decision
// 0024, "Energy guard"). Between SafeStep's cut and its commit, the total energy of the candidate
// state (x1 as cut, v) is summed on the GPU and compared with the total at the start of the
// substep. A rise beyond the sum's float resolution is taken out:
//  - of the kinetic energy, by one velocity scale for every moving node, when it can pay;
//  - otherwise (the rise is potential: contacts that entered the thickness unopposed store a
//    penalty energy nothing paid for) by pulling the whole step back towards x0,
//    x = x0 + α·(x − x0) and v = α·v (α = ½ per round), and deciding again. Every state on the
//    way lies on the step the CCD proved free of intersections; the last round's α = 0 is x0 at
//    rest, whose energy is at most the start's, so the rounds end (EnergyGuardPass::dispatch).
// The guard is global: a rise in one island is paid by all, which is why every time it acts is
// counted (--stats energy_guard): it is a fail-safe.
// Modes, one dispatch each:
//  u_mode = 0 (terms): GLC_ENERGY_GROUPS groups stride over the nodes (½·m·|v|², −m·g·x, the
//    ground's ½·k_g·depth² below its band), the springs (½·k·(|xa − xb| − L)²) and the feature pairs
//    of the last detection (½·k·depth² of every contact, the response's own geometry,
//    common/contact_pair.glsl, sides from x itself); each group's sums go to g_guard.partials in a
//    fixed tree: deterministic, no float atomics. The lists' order changes from run to run (their
//    entries are appended by many invocations), so the contacts' terms are summed exactly instead,
//    in 128-bit fixed point (2⁻⁶⁴ J units) into g_guard.contactPartials: a float sum in list order
//    made the guard's decision, and with it the whole run, depend on that order.
//  u_mode = 1 (decide, one group): sums the partials in a fixed order and decides (above).
//    u_record = 1 only records the total as the start (a frame's start: the host may have moved
//    nodes since the last substep).
//  u_mode = 2 (pull back by u_alpha), u_mode = 3 (scale the velocities by the decided scale).
// Every term also adds its magnitude to a second sum, S, the scale of the rounding: the resolution
// is u_resolution·(S_start + S_now) (EnergyGuardPass::resolutionFactor says where it comes from).
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"

// The candidate state is SafeStep's x1 (w: inverse mass); x0 is the start of the substep.
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) buffer PredictedPositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_SPRINGS) readonly buffer SpringsBuf { GpuSpring g_springs[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };
layout(std430, binding = GLC_BIND_ENERGY_GUARD) buffer EnergyGuardBuf { GpuEnergyGuard g_guard; };

uniform uint u_mode;          // 0 terms, 1 decide, 2 pull back, 3 scale
uniform uint u_record;        // decide: 1 records the total as the start, never acts
uniform uint u_round;         // decide: 0 for the substep's first decision, then the pull-back round
uniform uint u_last;          // decide: 1 after the pull-back to x0 (accept whatever is left)
uniform float u_alpha;        // pull back: the fraction of the step kept
uniform uint u_nodeCount;
uniform uint u_springCount;   // 0 without the springs effect
uniform uint u_contacts;      // 1: the feature pairs' contact energy (a collision effect is on)
uniform vec3 u_gravity;       // m/s² (0 without the gravity effect)
uniform float u_thickness;    // m: the contacts' thickness
uniform float u_groundStiffness; // N/m per node below u_groundLevel (0: the ground has no potential)
uniform float u_groundLevel;  // m: the ground's height plus its band
uniform float u_resolution;   // relative resolution of the sums (see the header)

// The contact geometry reads the start of the substep for the sides of open faces: the energy of
// a state is the energy of its positions, so its sides are its own (as Engine::energy()'s twin).
vec3 previousPosition(uint n) { return g_positions[n].xyz; }
// Contacts within the thickness only (common/contact_pair.glsl).
const bool kContactCrossings = false;
#include "common/contact_pair.glsl"
#include "common/energy_sum.glsl"

// (energy, its magnitude scale, kinetic energy, penalty energy) of one node.
vec4 nodeTerms(uint i) {
    float w = g_positions[i].w;
    if (!(w > 0.0)) return vec4(0.0); // pinned: at rest, a constant potential
    float m = 1.0 / w;
    vec3 x = g_positions[i].xyz, v = g_velocities[i].xyz;
    float kinetic = 0.5 * m * dot(v, v);
    float gravity = -m * dot(u_gravity, x);
    float depth = max(u_groundLevel - x.y, 0.0);
    float ground = u_groundStiffness > 0.0 ? 0.5 * u_groundStiffness * depth * depth : 0.0;
    float groundScale = u_groundStiffness > 0.0 ? ground + u_groundStiffness * depth * (abs(x.y) + abs(u_groundLevel)) : 0.0;
    return vec4(kinetic + gravity + ground, kinetic + abs(gravity) + groundScale, kinetic, ground);
}

vec4 springTerms(uint s) {
    vec2 e = springEnergy(g_springs[s]);
    return vec4(e, 0.0, 0.0);
}

void sumTerms() {
    uint stride = GLC_ENERGY_GROUPS * GLC_WORKGROUP_SIZE;
    uint first = gl_GlobalInvocationID.x;
    vec4 acc = vec4(0.0);
    for (uint i = first; i < u_nodeCount; i += stride) acc += nodeTerms(i);
    for (uint s = first; s < u_springCount; s += stride) acc += springTerms(s);
    // The contacts' energy and magnitude, exactly (the lists' order varies between runs).
    uvec4 contactEnergy = uvec4(0u), contactMagnitude = uvec4(0u);
    if (u_contacts != 0u) addContactEnergies(first, stride, contactEnergy, contactMagnitude);
    vec4 total = groupTotal(acc);
    groupExactTotal(contactEnergy, contactMagnitude);
    if (gl_LocalInvocationID.x == 0u) {
        g_guard.partials[gl_WorkGroupID.x] = total;
        g_guard.contactPartials[2u * gl_WorkGroupID.x] = contactEnergy;
        g_guard.contactPartials[2u * gl_WorkGroupID.x + 1u] = contactMagnitude;
    }
}

void decide() {
    vec4 acc = vec4(0.0);
    uvec4 contactEnergy = uvec4(0u), contactMagnitude = uvec4(0u);
    for (uint k = gl_LocalInvocationID.x; k < GLC_ENERGY_GROUPS; k += GLC_WORKGROUP_SIZE) {
        acc += g_guard.partials[k];
        contactEnergy = add128(contactEnergy, g_guard.contactPartials[2u * k]);
        contactMagnitude = add128(contactMagnitude, g_guard.contactPartials[2u * k + 1u]);
    }
    vec4 total = groupTotal(acc);
    groupExactTotal(contactEnergy, contactMagnitude);
    if (gl_LocalInvocationID.x != 0u) return;
    float contact = fromFixed128(contactEnergy);
    total += vec4(contact, fromFixed128(contactMagnitude), 0.0, contact);
    float energy = total.x, magnitude = total.y, kinetic = total.z;
    g_guard.lastKinetic = kinetic;
    g_guard.lastContact = total.w;
    g_guard.scale = 1.0;
    g_guard.lastTotal = energy;
    g_guard.outcome = 0u;
    if (u_round == 0u) g_guard.firstTotal = energy;
    if (u_record == 0u && g_guard.hasStart != 0u) {
        float excess = energy - g_guard.startTotal;
        if (excess > u_resolution * (g_guard.startMagnitude + magnitude)) {
            if (u_round == 0u) {
                g_guard.acted += 1u;
                g_guard.largestExcess = max(g_guard.largestExcess, excess);
            }
            if (excess <= kinetic) {
                g_guard.scale = sqrt(max(kinetic - excess, 0.0) / kinetic);
                energy -= excess; // what the scaled state holds
                g_guard.lastKinetic = kinetic - excess;
            } else if (u_last == 0u) {
                g_guard.outcome = 1u; // pull back; the start stays
                return;
            } else {
                g_guard.unremoved += excess;
            }
        }
        g_guard.removed += max(g_guard.firstTotal - energy, 0.0);
        g_guard.lastTotal = energy; // the accepted state's
    }
    // The accepted state is the next substep's start: each substep may end up to the resolution
    // above its start. (A reference that never rises would stop such rounding-sized rises from
    // adding up, but then a stiff cloth's rounding, which the CG's truncation keeps one-sided,
    // crossed it in 79 % of substeps and the guard pulled the scene back in 77 %.)
    g_guard.startTotal = energy;
    g_guard.startMagnitude = magnitude;
    g_guard.hasStart = 1u;
}

void pullBack() {
    uint i = globalIndex();
    if (i >= u_nodeCount || !(g_positions[i].w > 0.0)) return;
    vec3 x0 = g_start[i].xyz;
    g_positions[i].xyz = x0 + u_alpha * (g_positions[i].xyz - x0);
    g_velocities[i].xyz *= u_alpha;
}

void scaleVelocities() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    float s = g_guard.scale;
    if (s < 1.0 && g_positions[i].w > 0.0) g_velocities[i].xyz *= s;
}

void main() {
    if (u_mode == 0u) sumTerms();
    else if (u_mode == 1u) decide();
    else if (u_mode == 2u) pullBack();
    else scaleVelocities();
}
