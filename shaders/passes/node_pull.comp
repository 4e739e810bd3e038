#version 430 core
// NodePull — the host's pull on one node (Engine::setPull; a mouse perturbation as in MuJoCo's
// simulate): a spring of stiffness k from the node to a target point, with damping c against the
// node's velocity, applied as an external force for one substep of length h:
//   v += h · w · (k · (target − x) − c · v)
// It runs at the start of each substep, before the pipeline's passes, so symplectic Euler's
// NodeUpdate then moves x with the new v: the same arithmetic as adding the force to the node's
// force sum (the update is linear in the force). A pinned node (w = 0) is not moved. Dispatched only
// while a pull is set: scenes without one run nothing of it. One invocation, one node.
#include "common/layout.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) buffer NodeVelocitiesBuf { vec4 g_velocities[]; };

uniform uint u_node;      // global node index (< node count: Engine::setPull checks it)
uniform vec3 u_target;    // m
uniform float u_stiffness; // N/m
uniform float u_damping;   // N·s/m
uniform float u_h;         // s: the substep's length

void main() {
    vec4 p = g_positions[u_node];
    if (p.w <= 0.0) return; // pinned: held by the integrator anyway
    vec3 v = g_velocities[u_node].xyz;
    vec3 f = u_stiffness * (u_target - p.xyz) - u_damping * v;
    g_velocities[u_node] = vec4(v + (u_h * p.w) * f, 0.0);
}
