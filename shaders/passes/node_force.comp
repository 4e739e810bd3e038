#version 430 core
// glcollide-features: GLC_GRAVITY GLC_DAMPING GLC_WIND
// NodeForce — per-node external forces: gravity, viscous damping, linear wind drag on faces.
// The NodeForce stage of the AABB-octree pipeline (seeds/002, Table 2, Fig. 4). One invocation
// per node. Dispatched only for scenes without springs: with springs, SpringUpdate (or the
// implicit solver's setup) adds the same external force in its own dispatch. CPU twin: cpu::nodeForce.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_NODE_FORCES) writeonly buffer NodeForcesBuf { vec4 g_forces[]; };
#include "common/external_force.glsl"

uniform uint u_nodeCount;

void main() {
    uint i = globalIndex();
    if (i >= u_nodeCount) return;
    g_forces[i] = vec4(externalForce(i), 0.0);
}
