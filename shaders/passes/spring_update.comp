#version 430 core
// glcollide-features: GLC_GRAVITY GLC_DAMPING GLC_WIND
// SpringUpdate — Hooke force plus damping along each spring, gathered per node.
// The SpringUpdate stage of the AABB-octree pipeline (seeds/002, Table 2). The paper scatters per
// spring; we gather through a node->spring CSR list in a fixed order, so the sum is deterministic
// and needs no float atomics (GL 4.3 has none). Each spring is evaluated once per end. A node with
// more than GLC_HEAVY_ROW springs is gathered by a whole work group (common/row_gather.glsl).
// With GLC_GRAVITY / GLC_DAMPING / GLC_WIND it adds the external force (common/external_force.glsl)
// too, so a substep needs no NodeForce dispatch. Twin: cpu::springUpdate.
#include "common/layout.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/row_gather.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_positions[]; };
layout(std430, binding = GLC_BIND_NODE_VELOCITIES) readonly buffer NodeVelocitiesBuf { vec4 g_velocities[]; };
layout(std430, binding = GLC_BIND_SPRINGS) readonly buffer SpringsBuf { GpuSpring g_springs[]; };
layout(std430, binding = GLC_BIND_NODE_FORCES) writeonly buffer NodeForcesBuf { vec4 g_forces[]; };
layout(std430, binding = GLC_BIND_NODE_SPRING_LIST) readonly buffer NodeSpringListBuf { uint g_nodeSpringList[]; };
#include "common/external_force.glsl"
#include "common/spring_force.glsl"

void main() {
    if (groupIsPadding()) return; // whole groups only: the rest meet at barriers
    RowTask task = rowTask();
    uint i = task.node;
    vec3 f = task.gathers ? springForce(i, task.firstSpring, rowEnd(task), task.stride) : vec3(0.0);
    f = rowSum(vec4(f, 0.0)).xyz;
    if (!task.owner) return;
    g_forces[i] = vec4(f + externalForce(i), 0.0);
}
