#version 430 core
// NewtonLineSearch — a backtracking line search for the further Newton steps of implicit Euler
// (decision 0024, "Line search"). Backward Euler's step v minimises the incremental potential
//   Φ(v) = Σ ½m|v − v0|² + U(x0 + h·v) + h·D(v),
// U: gravity, the springs', the contacts' and the ground's penalties; D: the dissipation of the
// springs' damping ½c(u·(vb − va))² and of the air's ½c_air·m|v|² (∇Φ = M(v − v0) − h·f is the
// system's residual). A Newton step from v1 to v1 + δ is not monotone where the penalty is not
// smooth (a pair pushed out of the band sees no force, the next step pulls it back deeper), so the
// host tries α = 1, ½, ¼ and keeps the first candidate v1 + α·δ whose Φ is not above Φ(v1) by more
// than the sums' resolution, or else v1 (NewtonLineSearchPass::dispatch).
// Modes, one dispatch each:
//  u_mode = 0 (terms): GLC_ENERGY_GROUPS groups stride over the nodes, the springs and the feature
//    pairs of the Newton step's detection (contacts with sides from x0, as the Newton step's setup
//    takes them), the float terms in fixed trees and the contacts' exactly (common/energy_sum.glsl):
//    deterministic, no float atomics.
//  u_mode = 1 (total, one group): sums the partials in a fixed order into g_search.
//  u_mode = 2 (candidate): v = v1 + u_alpha·(v_full − v1) and x = x0 + h·v for every free node,
//    and the largest |v_full − v1| into g_search.largestChange (the host zeroes it per Newton step;
//    it decides whether a further step is worth taking: ImplicitParams::newtonTolerance).
// Twin: cpu::incrementalPotential.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"

// The candidate x = x0 + h·v (w: inverse mass); x0 the start of the substep.
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) buffer PredictedPositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
// [0, n): v0, the substep's start velocity; [n, 2n): v1, the Newton step's start; [2n, 3n): v1 + δ.
layout(std430, binding = GLC_BIND_LINE_SEARCH_VELOCITIES) readonly buffer LineSearchVelocitiesBuf { vec4 g_searchVelocities[]; };
layout(std430, binding = GLC_BIND_SPRINGS) readonly buffer SpringsBuf { GpuSpring g_springs[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };
layout(std430, binding = GLC_BIND_LINE_SEARCH) buffer LineSearchBuf { GpuLineSearch g_search; };

uniform uint u_mode;             // 0 terms, 1 total, 2 candidate
uniform float u_alpha;           // candidate: the fraction of the Newton step taken
uniform float u_h;               // s: the substep
uniform float u_airDamping;      // 1/s: the air's damping coefficient c_air (force −c_air·m·v)
uniform uint u_nodeCount;
uniform uint u_springCount;      // 0 without the springs effect
uniform uint u_contacts;         // 1: the feature pairs' penalty counts
uniform vec3 u_gravity;          // m/s² (0 without the gravity effect)
uniform float u_thickness;       // m: the contacts' thickness
uniform float u_groundStiffness; // N/m per node below u_groundLevel (0: the ground has no potential)
uniform float u_groundLevel;     // m: the ground's height plus its band

// Sides of open faces from x0, as the Newton step's setup takes them (from x1 − h·v1).
vec3 previousPosition(uint n) { return g_start[n].xyz; }
// Contacts at any depth for pairs that went through each other (common/contact_pair.glsl).
const bool kContactCrossings = true;
#include "common/contact_pair.glsl"
#include "common/energy_sum.glsl"

// (Φ's node terms, their magnitude scale) of node i: inertia, air dissipation, gravity, ground.
vec2 nodeTerms(uint i) {
    float w = g_positions[i].w;
    if (!(w > 0.0)) return vec2(0.0); // pinned: at rest, a constant potential
    float m = 1.0 / w;
    vec3 x = g_positions[i].xyz, v = g_velocities[i].xyz, v0 = g_searchVelocities[i].xyz;
    vec3 dv = v - v0;
    float inertia = 0.5 * m * dot(dv, dv);
    float air = 0.5 * u_h * u_airDamping * m * dot(v, v);
    float gravity = -m * dot(u_gravity, x);
    float depth = max(u_groundLevel - x.y, 0.0);
    float ground = u_groundStiffness > 0.0 ? 0.5 * u_groundStiffness * depth * depth : 0.0;
    float groundScale = u_groundStiffness > 0.0 ? ground + u_groundStiffness * depth * (abs(x.y) + abs(u_groundLevel)) : 0.0;
    // v − v0 rounds relative to |v| + |v0|.
    float inertiaScale = inertia + m * length(dv) * (length(v) + length(v0));
    return vec2(inertia + air + gravity + ground, inertiaScale + air + abs(gravity) + groundScale);
}

// (Φ's spring terms, their magnitude scale): elastic energy plus h·½c(u·(vb − va))².
vec2 springTerms(uint s) {
    GpuSpring spring = g_springs[s];
    vec2 e = springEnergy(spring);
    vec3 d = g_positions[spring.nodeB].xyz - g_positions[spring.nodeA].xyz;
    float len = length(d);
    if (!(len > 0.0) || spring.damping == 0.0) return e;
    vec3 va = g_velocities[spring.nodeA].xyz, vb = g_velocities[spring.nodeB].xyz;
    float rate = dot(vb - va, d / len);
    float dissipation = 0.5 * u_h * spring.damping * rate * rate;
    return e + vec2(dissipation, dissipation + u_h * spring.damping * abs(rate) * (length(va) + length(vb)));
}

void sumTerms() {
    uint stride = GLC_ENERGY_GROUPS * GLC_WORKGROUP_SIZE;
    uint first = gl_GlobalInvocationID.x;
    vec2 acc = vec2(0.0);
    for (uint i = first; i < u_nodeCount; i += stride) acc += nodeTerms(i);
    for (uint s = first; s < u_springCount; s += stride) acc += springTerms(s);
    uvec4 contactEnergy = uvec4(0u), contactMagnitude = uvec4(0u);
    if (u_contacts != 0u) addContactEnergies(first, stride, contactEnergy, contactMagnitude);
    vec4 total = groupTotal(vec4(acc, 0.0, 0.0));
    groupExactTotal(contactEnergy, contactMagnitude);
    if (gl_LocalInvocationID.x == 0u) {
        g_search.partials[gl_WorkGroupID.x] = total;
        g_search.contactPartials[2u * gl_WorkGroupID.x] = contactEnergy;
        g_search.contactPartials[2u * gl_WorkGroupID.x + 1u] = contactMagnitude;
    }
}

void sumPartials() {
    vec4 acc = vec4(0.0);
    uvec4 contactEnergy = uvec4(0u), contactMagnitude = uvec4(0u);
    for (uint k = gl_LocalInvocationID.x; k < GLC_ENERGY_GROUPS; k += GLC_WORKGROUP_SIZE) {
        acc += g_search.partials[k];
        contactEnergy = add128(contactEnergy, g_search.contactPartials[2u * k]);
        contactMagnitude = add128(contactMagnitude, g_search.contactPartials[2u * k + 1u]);
    }
    vec4 total = groupTotal(acc);
    groupExactTotal(contactEnergy, contactMagnitude);
    if (gl_LocalInvocationID.x != 0u) return;
    g_search.total = total.x + fromFixed128(contactEnergy);
    g_search.magnitude = total.y + fromFixed128(contactMagnitude);
}

void writeCandidate() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    vec4 x0 = g_start[i];
    if (!(x0.w > 0.0)) return; // pinned: stays at x0 with its velocity
    vec3 start = g_searchVelocities[u_nodeCount + i].xyz, full = g_searchVelocities[2u * u_nodeCount + i].xyz;
    // A maximum of non-negative floats by their bits: exact and the same in any order (a NaN's
    // bits are above every finite float's, so a non-finite change reads as a large one).
    atomicMax(g_search.largestChange, floatBitsToUint(length(full - start)));
    vec3 v = start + u_alpha * (full - start);
    g_velocities[i].xyz = v;
    g_positions[i] = vec4(x0.xyz + u_h * v, x0.w);
}

void main() {
    if (u_mode == 0u) sumTerms();
    else if (u_mode == 1u) sumPartials();
    else writeCandidate();
}
