#version 430 core
// ContactImpact — restitution between bodies at any step (decision 0024, "Restitution between
// bodies"; pass: src/passes/contact_impact.hpp). After SafeStep's cuts (and GroundImpact), before
// the energy guard. A pair that meets within a substep is stopped there by the implicit solve's
// contact penalty or by SafeStep's cut, so whatever bounce the scene asks for is lost: contacts were
// inelastic at any step. This pass gives every contact of the final state (x1 as cut; the last
// detection's vertex-face and edge-edge pairs within the thickness, common/contact_pair.glsl, sides
// from x1 itself, which the CCD proved intersection-free, as the energy guard takes them) that came
// from an impact the normal speed its restitution says:
//  - the contact's nodes n, signed weights a and normal u (from side B to side A) at x1;
//  - its normal speed at the start of the substep vn0 = u·Σ a_j v0_j (v0: StartVelocities), its
//    separation along u then d0 = u·Σ a_j x0_j, and gravity's pull on it a_n = (g·u)·Σ a_j over the
//    nodes that move (pinned nodes do not fall): its free flight from x0 to the thickness gives the
//    impact speed vImp² = vn0² − 2·a_n·max(d0 − h, 0) — the ground's rule (ground_impact.comp) for a
//    pair; a pair already within the thickness at x0 had an impact if it approached then (vn0 < 0);
//  - an impact faster than u_restingSpeed (what gravity adds in two substeps: slower is resting
//    contact) must leave with at least e·vImp along u.
// The pairs' impulses are found by rounds of projected Jacobi (respond() below: each pair's
// accumulated normal impulse λ ≥ 0, averaged over the pairs on its nodes, ContactImpactParams::
// iterations rounds), then Coulomb friction once, bounded by the normal impulse λ implies. The
// velocity changes are summed per node in fixed point with integer atomics (no float atomics; the
// sum does not depend on thread order; addVelocityChange says how its scale is chosen), and a pair's
// impulse is capped at u_forceCap, the response's cap. The positions are not changed, so the CCD's
// check stands, and the energy guard that follows sees the new velocities.
// Modes, one dispatch each: u_mode = 0 counts the impact pairs of list u_list per node (.w of the
// sums), 4 chooses the fixed-point scale, 1 moves their impulses (velocity changes into .xyz), 3 adds
// their friction, 2 applies the sums to the velocities (one invocation per node) and clears them.
// Twin: cpu::contactImpact.
#include "common/layout.glsl"
#include "common/lists.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/contact_geometry.glsl"

// x1 as cut (w: inverse mass); x0, the start of the substep.
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_START_VELOCITIES) readonly buffer StartVelocitiesBuf { vec4 g_startVelocities[]; };
layout(std430, binding = GLC_BIND_CONTACT_FORCES) buffer ContactForcesBuf { ivec4 g_sums[]; };
layout(std430, binding = GLC_BIND_FACE_INFO) readonly buffer FaceInfoBuf { GpuFaceInfo g_faceInfo[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_VERTEX_FACE_PAIRS) readonly buffer VertexFacePairsBuf { uvec2 g_vertexFace[]; };
layout(std430, binding = GLC_BIND_EDGE_EDGE_PAIRS) readonly buffer EdgeEdgePairsBuf { uvec2 g_edgeEdge[]; };
// Word 0: the largest velocity change one pair may give a node in a round (float bits, atomicMax:
// non-negative floats order as their bits); word 1: the fixed-point scale (float bits, units per
// m/s); from word 2 on, two per pair: its accumulated impulse λ (float bits; −1: not a member) and
// its friction's normal impulse per unit of λ (float bits; mode 0).
layout(std430, binding = GLC_BIND_IMPACT_IMPULSES) buffer ImpactImpulsesBuf { uint g_words[]; };
const uint kImpulseHeader = 2u;
float impulseOf(uint slot) { return uintBitsToFloat(g_words[kImpulseHeader + 2u * slot]); }
void setImpulse(uint slot, float lambda) { g_words[kImpulseHeader + 2u * slot] = floatBitsToUint(lambda); }
float normalPerImpulseOf(uint slot) { return uintBitsToFloat(g_words[kImpulseHeader + 2u * slot + 1u]); }

uniform uint u_mode;          // 0 count, 1 normal impulses, 2 apply, 3 friction
uniform uint u_list;          // GLC_LIST_VERTEX_FACE or GLC_LIST_EDGE_EDGE (modes 0 and 1)
uniform uint u_edgeEdgeBase;  // the impulses' slot of edge-edge entry 0: the vertex-face list's capacity
uniform uint u_clearCounts;   // mode 2: 1 after the last dispatch (the counts of mode 0 serve every round)
uniform uint u_nodeCount;
uniform float u_thickness;    // m: the band searched, twice the contacts' thickness (common/contact_pair.glsl)
uniform float u_band;         // m: the contacts' thickness h
uniform float u_restitution;  // (0, 1]
uniform float u_friction;     // Coulomb μ (mode 3)
uniform float u_restingSpeed; // m/s: slower impacts are resting contact
uniform vec3 u_gravity;       // m/s² (0 without gravity)
uniform float u_substep;      // s: impulses are summed as forces over it
uniform float u_forceCap;     // N per pair: the largest impulse (over the substep) one pair may hold

vec3 previousPosition(uint n) { return g_positions[n].xyz; } // sides from x1 itself
// Contacts within the thickness only (common/contact_pair.glsl).
const bool kContactCrossings = false;
#include "common/contact_pair.glsl"
#include "common/tangled.glsl"

struct Impact {
    bool acting;
    vec4 share;        // a_j²·w_j: each node's part of the pair's inverse mass
    float perSpeed;    // N per m/s of the pair's relative velocity changed (before the Jacobi count)
    float target;      // m/s: the normal speed it must leave with, e·vImp
    float impactSpeed; // m/s: vImp
    bool met;          // it met within the substep (it was beyond the thickness at x0)
};

vec3 weightedSum(vec4 a, vec3 x0, vec3 x1, vec3 x2, vec3 x3) {
    return a.x * x0 + a.y * x1 + a.z * x2 + a.w * x3;
}

// Whether the pair had an impact in the substep (the header), and its target. Independent of the
// velocities after the step, so every round sees the same pairs and the same counts.
Impact impactOf(ContactPair c) {
    Impact none = Impact(false, vec4(0.0), 0.0, 0.0, 0.0, false);
    uvec4 n = c.nodes;
    vec4 a = c.weights;
    vec4 w = vec4(g_positions[n.x].w, g_positions[n.y].w, g_positions[n.z].w, g_positions[n.w].w);
    vec4 share = a * a * w;
    float wSum = share.x + share.y + share.z + share.w;
    if (!(wSum > 0.0)) return none; // every node pinned or of weight 0
    vec3 u = c.normal;
    float vn0 = dot(weightedSum(a, g_startVelocities[n.x].xyz, g_startVelocities[n.y].xyz,
                                g_startVelocities[n.z].xyz, g_startVelocities[n.w].xyz), u);
    float d0 = dot(weightedSum(a, g_start[n.x].xyz, g_start[n.y].xyz, g_start[n.z].xyz, g_start[n.w].xyz), u);
    float an = dot(u_gravity, u) * dot(a, vec4(greaterThan(w, vec4(0.0))));
    float gap = max(d0 - u_band, 0.0);
    if (!(vn0 < 0.0 || (an < 0.0 && gap > 0.0))) return none; // neither approaching nor pulled together
    float impactSpeed = sqrt(max(vn0 * vn0 - 2.0 * an * gap, 0.0));
    if (!(impactSpeed > u_restingSpeed)) return none;
    return Impact(true, share, 1.0 / (wSum * u_substep), u_restitution * impactSpeed, impactSpeed, gap > 0.0);
}

// The velocity changes are summed in fixed point with a scale chosen for this pass (mode 4) from the
// largest change one pair may give a node in a round (mode 0), so that GLC_IMPACT_HEADROOM of them
// fit in an int with room for four times that change (later rounds correct what earlier ones left):
// the resolution follows the impacts' own speeds, in any unit (no constant with a unit). A change
// beyond that room is clamped to it (a slower convergence, never an overflow).
#define GLC_IMPACT_HEADROOM 1024.0
const float kImpactUnits = 2147483647.0 / GLC_IMPACT_HEADROOM; // per contribution
void addVelocityChange(uint node, vec3 dv) {
    ivec3 q = ivec3(round(clamp(dv * uintBitsToFloat(g_words[1]), -kImpactUnits, kImpactUnits)));
    if (q.x != 0) atomicAdd(g_sums[node].x, q.x);
    if (q.y != 0) atomicAdd(g_sums[node].y, q.y);
    if (q.z != 0) atomicAdd(g_sums[node].z, q.z);
}

void countOn(uint node, float share) {
    if (share > 0.0) atomicAdd(g_sums[node].w, 1);
}

// The largest count of impact pairs (mode 0's .w) on the nodes the pair moves.
int actingCount(uvec4 n, vec4 share) {
    int count = max(max(share.x > 0.0 ? g_sums[n.x].w : 0, share.y > 0.0 ? g_sums[n.y].w : 0),
                    max(share.z > 0.0 ? g_sums[n.z].w : 0, share.w > 0.0 ? g_sums[n.w].w : 0));
    return max(count, 1);
}

// One pair of list slot `slot` in mode 0 (count), 1 (normal impulse) or 3 (friction). Mode 0 decides
// which impact pairs take part (λ = 0) and which not (λ = −1) from the velocities after the step, and
// counts the members on their nodes. Mode 1 is projected Jacobi on each member's accumulated impulse
// λ ≥ 0 (g_impulses): λ moves
// by what takes the pair's normal speed to its target, averaged over the pairs on its nodes, and is
// never negative — an impulse that overshot, with its neighbours', is taken back, so the rounds
// approach the smallest impulses that leave every pair at least as fast as its target (a flat cloth
// on a sheet: every node alike), instead of keeping whatever a round overshot. Mode 3, once after
// the rounds: Coulomb friction against the pair's relative sliding, at most μ times its normal
// impulse — λ, and for a pair that met within the substep also the stop that the solve (without
// friction) gave it: (1 + e)·vImp in all, the ground's rule, of which λ moved target − vn — and at
// most what stops the sliding (Jacobi-averaged like the normal part).
void respond(ContactPair c, uint slot) {
    if (!c.found) return;
    Impact im = impactOf(c);
    if (!im.acting) return;
    uvec4 n = c.nodes;
    vec4 a = c.weights;
    vec3 u = c.normal;
    vec3 vRel = weightedSum(a, g_velocities[n.x].xyz, g_velocities[n.y].xyz, g_velocities[n.z].xyz,
                            g_velocities[n.w].xyz);
    float vn = dot(vRel, u);
    if (u_mode == 0u) {
        // Beyond the thickness, a pair takes part only while it still approaches after the step (the
        // solve often leaves a landing pair on the band's edge, some of its nodes just outside).
        bool member = u_thickness - c.depth <= u_band || vn < 0.0;
        setImpulse(slot, member ? 0.0 : -1.0);
        if (!member) return;
        // Friction's normal impulse per unit of λ: λ takes the pair from vn to its target; a pair that
        // met within the substep had the rest of its normal change, from −vImp to vn, from the solve
        // (or the cut), which has no friction: the whole change (1 + e)·vImp, as the ground's.
        float change = im.target - vn;
        float perImpulse = im.met && change > 0.0 ? (im.target + im.impactSpeed) / change : 1.0;
        g_words[kImpulseHeader + 2u * slot + 1u] = floatBitsToUint(perImpulse);
        // Its largest change of a node's velocity in round 0: a_j·w_j/Σ a²w of its change.
        vec4 w = vec4(g_positions[n.x].w, g_positions[n.y].w, g_positions[n.z].w, g_positions[n.w].w);
        vec4 reach = abs(a) * w;
        float wSum = im.share.x + im.share.y + im.share.z + im.share.w;
        float largest = abs(im.target - vn) * max(max(reach.x, reach.y), max(reach.z, reach.w)) / wSum;
        atomicMax(g_words[0], floatBitsToUint(largest));
        countOn(n.x, im.share.x);
        countOn(n.y, im.share.y);
        countOn(n.z, im.share.z);
        countOn(n.w, im.share.w);
        return;
    }
    float before = impulseOf(slot);
    if (before < 0.0) return; // not a member (mode 0)
    float perSpeed = im.perSpeed / float(actingCount(n, im.share));
    vec3 F;
    if (u_mode == 1u) {
        float after = clamp(before + (im.target - vn) * perSpeed, 0.0, u_forceCap);
        setImpulse(slot, after);
        F = (after - before) * u;
    } else {
        vec3 vt = vRel - vn * u;
        float speed = length(vt);
        if (!(speed > 0.0)) return;
        float magnitude = min(u_friction * normalPerImpulseOf(slot) * before, speed * perSpeed);
        F = vt * (-magnitude / speed);
    }
    if (F == vec3(0.0)) return;
    // Node j's velocity change: h·w_j·a_j·F.
    addVelocityChange(n.x, (u_substep * g_positions[n.x].w * a.x) * F);
    addVelocityChange(n.y, (u_substep * g_positions[n.y].w * a.y) * F);
    addVelocityChange(n.z, (u_substep * g_positions[n.z].w * a.z) * F);
    addVelocityChange(n.w, (u_substep * g_positions[n.w].w * a.w) * F);
}

void main() {
    uint i = globalIndex();
    if (u_mode == 4u) { // one invocation: the scale, a power of two (exact products)
        if (i != 0u) return;
        float largest = uintBitsToFloat(g_words[0]);
        float scale = largest > 0.0 ? exp2(floor(log2(kImpactUnits / (4.0 * largest)))) : 1.0;
        g_words[1] = floatBitsToUint(scale);
        return;
    }
    if (u_mode == 2u) {
        if (i >= u_nodeCount) return;
        ivec4 q = g_sums[i];
        g_sums[i] = ivec4(0, 0, 0, u_clearCounts != 0u ? 0 : q.w);
        if (g_positions[i].w > 0.0 && q.xyz != ivec3(0))
            g_velocities[i].xyz += vec3(q.xyz) / uintBitsToFloat(g_words[1]);
        return;
    }
    if (i >= storedCount(u_list)) return;
    if (u_list == GLC_LIST_VERTEX_FACE) {
        uvec2 item = g_vertexFace[i]; // (node, face)
        GpuFaceInfo info = g_faceInfo[item.y];
        respond(vertexFaceContact(item.x, faceNodes(item.y), info.owned, g_objects[info.object]), i);
    } else {
        uvec2 item = g_edgeEdge[i]; // (3*fa+e, 3*fb+g)
        if (faceTangled(item.x / 3u) || faceTangled(item.y / 3u)) return; // intersecting at x0 (tangled.glsl)
        uvec3 fa = faceNodes(item.x / 3u), fb = faceNodes(item.y / 3u);
        uint e = item.x % 3u, g = item.y % 3u;
        respond(edgeEdgeContact(fa[e], fa[(e + 1u) % 3u], fb[g], fb[(g + 1u) % 3u]), u_edgeEdgeBase + i);
    }
}
