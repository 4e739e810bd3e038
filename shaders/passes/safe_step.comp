#version 430 core
// SafeStep — one round of the intersection-free response's step cut (decision 0024), in two
// dispatches over the nodes. The cut is per object: a node's step is scaled like the rest of its
// body's, so a body that meets another keeps its shape (a per-node cut stopped the front of a ball
// and let its back fly on: its springs took the kinetic energy and gave it back a hundredfold).
//  u_reduce = 1: every node whose earliest time of impact t (the Ccd stage's lower bound over its
//    vertex-face and edge-edge pairs, GLC_BIND_NODE_TOI) is set lowers its object's (atomicMin
//    on the bits of a non-negative float: order-independent).
//  u_reduce = 0: every moving node of an object with a time of impact T advances only to
//    x0 + (u_fraction·T)·(x1 − x0) of its predicted step x1 (u_fraction 0: it stays at x0), and
//    its velocity becomes that displacement over the substep, so its kinetic energy only drops.
// The Ccd stage then checks the stored end positions again: what it proves safe is exactly what
// SafeStep commits, however this arithmetic rounds. u_everyNode = 1 (the last resort): every
// moving node stays at x0. Nodes that do not move are not counted.
// CPU twin: cpu::safeStepRound (src/cpu/safe_step_twin.cpp).
#include "common/layout.glsl"
#include "common/lists.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) buffer PredictedPositionsBuf { vec4 g_predicted[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_NODE_TOI) readonly buffer NodeToiBuf { uint g_nodeToi[]; };
layout(std430, binding = GLC_BIND_OBJECTS) readonly buffer ObjectsBuf { GpuObject g_objects[]; };
layout(std430, binding = GLC_BIND_OBJECT_TOI) buffer ObjectToiBuf { uint g_objectToi[]; };

uniform uint u_nodeCount;
uniform uint u_objectCount;
uniform uint u_reduce;    // 1: lower the objects' times of impact; 0: cut
uniform float u_fraction; // of the time of impact a cut node advances to; 0 freezes it
uniform float u_h;        // s: the substep
uniform uint u_everyNode; // 1: the last resort, every moving node stays at x0
uniform uint u_ground;    // 1: the ground is on: a step that crosses it is an impact too
uniform float u_groundHeight; // m

const uint kNoImpact = 0x7F800000u; // +inf bits: no pair of this node (object) may touch

// The object whose node range holds node i (objects are stored by ascending firstNode).
uint objectOf(uint i) {
    uint lo = 0u, hi = u_objectCount; // g_objects[lo].firstNode <= i < g_objects[hi].firstNode
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (g_objects[mid].firstNode <= i) lo = mid; else hi = mid;
    }
    return lo;
}

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    if (u_reduce != 0u) {
        uint toiBits = g_nodeToi[i];
        // The ground (NodePredict no longer clamps x1): a node that would go below it from above
        // reaches it at t = (y0 − g) / (y0 − y1), in [0, 1).
        if (u_ground != 0u) {
            float y0 = g_positions[i].y, y1 = g_predicted[i].y;
            if (y0 >= u_groundHeight && y1 < u_groundHeight) {
                float t = clamp((y0 - u_groundHeight) / (y0 - y1), 0.0, 1.0);
                toiBits = min(toiBits, floatBitsToUint(t));
                atomicAdd(g_counters.stats[GLC_STAT_SAFE_STEP_GROUND], 1u);
            }
        }
        if (toiBits != kNoImpact) atomicMin(g_objectToi[objectOf(i)], toiBits);
        return;
    }
    uint toiBits = g_objectToi[objectOf(i)];
    if (toiBits == kNoImpact && u_everyNode == 0u) return;
    vec4 x0 = g_positions[i], x1 = g_predicted[i];
    if (all(equal(x0.xyz, x1.xyz))) return; // already still: nothing to cut
    float s = u_everyNode != 0u ? 0.0 : u_fraction * uintBitsToFloat(toiBits);
    vec3 x = x0.xyz + s * (x1.xyz - x0.xyz);
    g_predicted[i] = vec4(x, x1.w);
    g_velocities[i] = vec4((x - x0.xyz) / u_h, 0.0);
    atomicAdd(g_counters.stats[GLC_STAT_SAFE_STEP_CUTS], 1u);
}
